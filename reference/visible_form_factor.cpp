// Lambert's contour formula over the part of the source a receiver point sees
// (SourceMoments::formFactor, source_moments.h): the degree-0 inner integral of the exact
// gold, exact, its edges batched over the lanes of radial_moments.h.
#include <cmath>
#include <numbers>

#include "reference/radial_moments.h"
#include "reference/source_moments.h"

// With -fopenmp-simd (GCC, reference/CMakeLists.txt) the loop over a batch's edges calls
// glibc's vector atan2 (libmvec), which errs by at most 4 units in the last place; elsewhere,
// the scalar function. The declaration adds the vector variant to glibc's own (global, C
// linkage) function.
#if defined(RADQUAD_VECTOR_MATH)
extern "C" {
#pragma omp declare simd notinbranch
double atan2(double, double) noexcept;
}
#endif

namespace radquad {

using detail::kLanes;

double SourceMoments::formFactor(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                                 const VisibleRings& visible) const {
  // Lambert: sum over edges (r0, r1) of n . (r0 x r1) / |r0 x r1| * angle(r0, r1), r the
  // offsets of the ring's vertices from x. The edges, of all rings and segments in turn, go
  // kLanes at a time through branch-free loops over the lanes (vector instructions; with
  // GCC, glibc's vector atan2), each lane summing its own edges; the lanes are summed in a
  // fixed order at the end.
  const Eigen::Vector3d o = source_.origin - x;
  const Eigen::Vector3d& eu = source_.edgeU;
  const Eigen::Vector3d& ev = source_.edgeV;
  double lanes[kLanes] = {};
  // The edges of every ring and the outline's segments, one after another, fill the lanes;
  // a batch goes through the loops below when full, and the last one padded.
  double ax[kLanes], ay[kLanes], az[kLanes], bx[kLanes], by[kLanes], bz[kLanes];
  double weight[kLanes];
  int filled = 0;
  const auto flush = [&] {
    // Lanes past the last edge repeat the first with no weight.
    for (int k = filled; k < kLanes; ++k) {
      ax[k] = ax[0];
      ay[k] = ay[0];
      az[k] = az[0];
      bx[k] = bx[0];
      by[k] = by[0];
      bz[k] = bz[0];
      weight[k] = 0.0;
    }
    double crossNorm[kLanes], cosine[kLanes], normal[kLanes];
    for (int k = 0; k < kLanes; ++k) {
      const double cx = ay[k] * bz[k] - az[k] * by[k];
      const double cy = az[k] * bx[k] - ax[k] * bz[k];
      const double cz = ax[k] * by[k] - ay[k] * bx[k];
      crossNorm[k] = std::sqrt(cx * cx + cy * cy + cz * cz);
      cosine[k] = ax[k] * bx[k] + ay[k] * by[k] + az[k] * bz[k];
      normal[k] = n.x() * cx + n.y() * cy + n.z() * cz;
    }
    double angle[kLanes];
#if defined(RADQUAD_VECTOR_MATH)
#pragma omp simd
#endif
    for (int k = 0; k < kLanes; ++k) angle[k] = ::atan2(crossNorm[k], cosine[k]);
    for (int k = 0; k < kLanes; ++k) {
      // A zero cross product (an edge of no length, or in line with x) adds nothing.
      const bool some = crossNorm[k] > 0.0;
      const double inverse = 1.0 / (some ? crossNorm[k] : 1.0);
      lanes[k] += some ? weight[k] * normal[k] * inverse * angle[k] : 0.0;
    }
    filled = 0;
  };
  // One edge (a, b) in (u, v), counted with weight w.
  const auto push = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, double w) {
    const int k = filled;
    ax[k] = o.x() + a.x() * eu.x() + a.y() * ev.x();
    ay[k] = o.y() + a.x() * eu.y() + a.y() * ev.y();
    az[k] = o.z() + a.x() * eu.z() + a.y() * ev.z();
    bx[k] = o.x() + b.x() * eu.x() + b.y() * ev.x();
    by[k] = o.y() + b.x() * eu.y() + b.y() * ev.y();
    bz[k] = o.z() + b.x() * eu.z() + b.y() * ev.z();
    weight[k] = w;
    if (++filled == kLanes) flush();
  };
  // An edge counter-clockwise about the source's normal, seen from x in front of the source,
  // gives a negative term.
  for (std::size_t r = 0; r < visible.count(); ++r) {
    const SourceRing& ring = visible.ring(r);
    const std::size_t count = ring.size();
    const double sign = -visible.sign(r);
    for (std::size_t i = 0; i < count; ++i) push(ring[i], ring[i + 1 < count ? i + 1 : 0], sign);
  }
  for (std::size_t i = 0; i < visible.segmentCount(); ++i) {
    push(visible.segmentStart(i), visible.segmentEnd(i), -visible.segmentSign(i));
  }
  if (filled > 0) flush();
  double total = 0.0;
  detail::sumLanes(lanes, 1, &total);
  return total / (2.0 * std::numbers::pi);
}

}  // namespace radquad
