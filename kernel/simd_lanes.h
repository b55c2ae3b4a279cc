// The lane types of the hand-vectorised loops (GCC/Clang vector extensions), in one place:
// eight lanes, so that an accumulator is one AVX-512 register where the CPU has them, and a
// pair or quadruple of narrower ones elsewhere. Used by the product and block contractions,
// the ray masks of the coupling paths and the Philox generator.
#pragma once

#include <cstdint>

// These vectors never cross a non-inlined boundary with external linkage, so GCC's note that
// their ABI differs without AVX-512 (a RADQUAD_NATIVE=OFF build, or a CPU without it) is
// moot; it is silenced here for every file that includes this header.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace radquad::simd {

inline constexpr int kLanes = 8;
using Doubles8 = double __attribute__((vector_size(64)));
using Floats8 = float __attribute__((vector_size(32)));
using Int64s8 = std::int64_t __attribute__((vector_size(64)));
using UInt64s8 = std::uint64_t __attribute__((vector_size(64)));

}  // namespace radquad::simd
