// The outline of the union of convex shadows (exact_visibility.h): the pieces of their edges
// that no other shadow covers, closed up to the bit (union_outline.cpp says how).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "reference/visible_rings.h"

namespace radquad {

// The outline of the union of convex counter-clockwise rings lying inside a convex
// counter-clockwise `border` ring (in the exact gold: the overlapping shadows, inside S'), as
// the pieces of the rings' edges that no other ring covers, in their rings' direction: what
// Lambert's formula and the polar integral need, without forming polygons (details in
// union_outline.cpp). Scratch storage is kept from call to call.
class UnionOutline {
 public:
  // The rings rings[i], i in `members`, with their boxes bounds[i] (low u, low v, high u,
  // high v) and, per vertex, onBorder[i][v]: bit s set where the vertex lies on the line of
  // the border's edge s (as the caller's clip placed it; 0 where not known). Adds the pieces
  // to `out` with sign `sign`; false, and `out` as it was, where they do not close up.
  bool add(const std::vector<SourceRing>& rings, const std::vector<std::size_t>& members,
           const std::vector<Eigen::Vector4d>& bounds,
           const std::vector<std::vector<std::uint32_t>>& onBorder, const SourceRing& border,
           double sign, VisibleRings& out);

 private:
  // Closes the pieces from segment `first` on: every end meets a start.
  bool close(std::size_t first, double tolerance, double sign, VisibleRings& out);

  // The parts [from, to] of one ring's edge that ring `cover` covers, and the edges of
  // `cover` they begin and end on (kNoEdge: the covered edge's own end).
  static constexpr std::size_t kNoEdge = std::size_t(-1);
  struct CoveredPart {
    double from, to;
    std::size_t fromEdge, toEdge;
    std::size_t cover = 0;
  };
  std::vector<CoveredPart> covered_;
  // Per ring: (edge vector, squared length, the edge of the border it runs along or -1).
  std::vector<std::vector<Eigen::Vector4d>> edgeLines_;
  // A ring's edge along edge `side` of the border, from parameter `from` to `to` along it;
  // the border's edges whose lines its start and end lie on (bits, as in add()).
  struct BorderPart {
    std::size_t side;
    double from, to;
    Eigen::Vector2d start, end;
    std::uint32_t startOn, endOn;
  };
  std::vector<BorderPart> borderParts_, mergedBorder_;
  std::vector<std::pair<Eigen::Vector2d, std::size_t>> starts_, ends_;  // close()'s
};

}  // namespace radquad
