// Deterministic link geometries and occluder scenes shared by the benchmarks.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "kernel/coupling.h"
#include "kernel/occluder_scene.h"

namespace radquad::bench {

// Opposed, slightly tilted patch pairs about one unit apart, varied by a fixed sequence.
inline std::vector<Link> makeLinks(std::size_t count, const OccluderScene* occluders) {
  std::vector<Link> links;
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  auto next = [&state] {  // SplitMix64 mapped to [0,1)
    state += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  for (std::size_t k = 0; k < count; ++k) {
    const double size = 0.5 + 0.5 * next();
    const Patch receiver = Patch::make({next() * 0.2, next() * 0.2, 0}, {size, 0, 0.1 * next()},
                                       {0, size, 0.1 * next()}, "receiver");
    const Patch source = Patch::make({next() * 0.2, size + next() * 0.2, 1 + 0.2 * next()},
                                     {size, 0, 0}, {0, -size, 0.1 * next()}, "source");
    links.push_back(Link{receiver, source, occluders});
  }
  return links;
}

// Blockers in the plane z = 0.5 between the patches of makeLinks: `count` squares on a
// grid covering about half of the region the links' rays cross.
inline std::unique_ptr<OccluderScene> makeBlockerScene(int perSide) {
  auto scene = std::make_unique<OccluderScene>();
  const double cell = 1.4 / perSide;
  for (int i = 0; i < perSide; ++i) {
    for (int j = 0; j < perSide; ++j) {
      if ((i + j) % 2 == 1 && perSide > 1) continue;
      const double side = perSide == 1 ? 0.6 : cell;
      scene->addParallelogram(
          Patch::make({i * cell, j * cell, 0.55}, {side, 0, 0}, {0, side, 0}, "blocker"));
    }
  }
  scene->commit();
  return scene;
}

}  // namespace radquad::bench
