// The unit receiver and source of the exact visibility's tests with occluders halfway between
// them, whose visible form factor follows by inclusion and exclusion from closed forms
// (exact_visibility_test.cpp, exact_visibility_contacts_test.cpp).
#pragma once

#include <Eigen/Core>
#include <cstddef>

#include "kernel/occluder_scene.h"
#include "kernel/patch.h"
#include "reference/exact_visibility.h"
#include "reference/point_polygon_form_factor.h"
#include "reference/source_moments.h"

namespace radquad {

// The unit receiver at z = 0 seen from its centre x, and the unit source facing it at z = 1.
// Occluders halfway between them and parallel to both cast shadows that are the occluders
// scaled by 2 about x's foot, so the visible form factor follows from closed-form
// point-to-rectangle form factors by inclusion and exclusion: no ring, no union, no clipping.
struct HalfwaySetup {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const Eigen::Vector3d x{0.5, 0.5, 0.0}, n{0, 0, 1};

  // The form factor from x to the rectangle [x0, x1] x [y0, y1] of the source's plane,
  // facing the receiver as the source does.
  double toRectangle(double x0, double x1, double y0, double y1) const {
    return pointToPatchFormFactor(
        x, n, Patch::make({x0, y1, 1}, {x1 - x0, 0, 0}, {0, y0 - y1, 0}, "shadow"));
  }
  double toSource() const { return pointToPatchFormFactor(x, n, source); }

  // What x sees of the source past `scene`'s occluders, by the exact visibility and
  // Lambert's formula; `unions` and `rings` report how it was formed.
  double visibleFormFactor(const OccluderScene& scene, std::size_t& unions, std::size_t& rings,
                           ShadowUnion method = ShadowUnion::inclusionExclusion) const {
    const Link link{receiver, source, &scene};
    ExactVisibility visibility(link, method);
    VisibleRings visible;
    visibility.visibleRings(x, visible);
    unions = visibility.statistics().unions;
    rings = visible.count();
    return SourceMoments(source, 0).formFactor(x, n, visible);
  }
};

}  // namespace radquad
