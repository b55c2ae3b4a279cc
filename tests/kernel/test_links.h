// Link geometries shared by the kernel tests.
#pragma once

#include "kernel/patch.h"

namespace radquad::testing {

// A receiver a x b in the plane z = 0 facing +z, and a source of the same size directly
// above it at height c facing -z.
inline Patch opposedReceiver(double a, double b) {
  return Patch::make({0, 0, 0}, {a, 0, 0}, {0, b, 0}, "receiver");
}
inline Patch opposedSource(double a, double b, double c) {
  return Patch::make({0, b, c}, {a, 0, 0}, {0, -b, 0}, "source");
}

// Perpendicular rectangles sharing the edge from (0,0,0) to (l,0,0): the receiver of width w
// lies in z = 0 (y in [0,w]) facing +z; the source of height h lies in y = 0 (z in [0,h])
// facing +y.
inline Patch perpendicularReceiver(double l, double w) {
  return Patch::make({0, 0, 0}, {l, 0, 0}, {0, w, 0}, "receiver");
}
inline Patch perpendicularSource(double l, double h) {
  return Patch::make({0, 0, 0}, {0, 0, h}, {l, 0, 0}, "source");
}

}  // namespace radquad::testing
