// Couplings of links whose elements are near each other: touching (a shared edge or corner),
// cut by the other's plane, or closer than their sizes (link_integration.h, nearField).
//
// There the kernel varies over the link far faster than a product rule's points are spaced
// (it is singular where elements touch), so no fixed product rule is accurate: one point on two
// unit squares sharing an edge gives a form factor of 1/pi instead of 0.2000, and a small
// square 4 cm under a large ceiling, whose kernel peaks over a patch of the ceiling as wide as
// the gap, got couplings off by either sign. Instead the source side is integrated exactly:
//   K[a][b] = sqrt(A_R / A_S) int_R phi_a(x) I_b(x) dx,
//   I_b(x)  = int_{V(x)} cos cos / (pi r^2) phi_b dA',
// with V(x) the part of the source that x sees (the source in front of x's tangent plane, less
// the occluders' shadows: reference/exact_visibility.h) and I_b in closed form over V(x)'s
// edges (reference/source_moments.h: Lambert's formula for the constant function, the polar
// moments above). The inner integral is bounded (a point form factor is at most 1) but varies
// sharply near the boundary of the visible source S' (the source clipped to the receiver's
// front half-space) and along shadow edges, so the outer integral over the receiver is
// adaptive: a piece's Gauss product estimates with n = max(2, d + 1) and n + 1 points per axis
// are compared, and the piece is split (halved across its long side when more than twice as
// long as wide, else quartered) while they differ by more than its share (by area) of the
// tolerance (relative to the coupling's largest entry), or while it is larger than the band
// in which the inner integral changes near an edge of S' and lies in it (its points could all
// miss the band; only where the band can hold a share of the coupling above the tolerance),
// or larger than S' and nearer to it than its size (near_field.cpp, mustSplit), up to
// kMaxLevel and kMaxForcedLevel quarterings. Accepted pieces contribute their n + 1 point
// estimates.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "kernel/coupling.h"
#include "reference/exact_visibility.h"
#include "reference/source_moments.h"

namespace radquad {

class NearFieldIntegrator {
 public:
  // The solver's defaults: pieces are quartered for their estimates' disagreement at most
  // kMaxLevel times (halvings of elongated pieces do not count), and for lying in an edge's
  // band (mustSplit) at most kMaxForcedLevel times; the tolerance is relative to the
  // coupling's largest entry. The oracle refines links that carry energy until their elements are about as far
  // apart as they are large, so the near field mostly meets touching and plane-cut pairs of
  // similar elements, which these settle (radiosity/README.md, "Couplings", has the cost).
  static constexpr int kMaxLevel = 1;
  static constexpr int kMaxForcedLevel = 8;
  // The outer integral's tolerance, relative to the coupling's largest entry.
  static constexpr double kTolerance = 1e-2;
  // An edge nearer to a piece than this fraction of its size touches it.
  static constexpr double kTouching = 1e-6;

  explicit NearFieldIntegrator(double tolerance = kTolerance, int maxLevel = kMaxLevel)
      : maxLevel_(maxLevel), relativeTolerance_(tolerance) {}

  // A rectangle [u0, u0 + du] x [v0, v0 + dv] of the receiver's parameter square.
  struct Piece {
    double u0 = 0.0, v0 = 0.0, du = 1.0, dv = 1.0;
  };

  struct Counts {
    std::uint64_t points = 0;  // receiver points, each with its exact inner integrals
    std::uint64_t pieces = 0;
  };

  // The inner integrals' accuracy (reference/source_moments.h): relative error at most 2e-7
  // where x lies over the source, more at grazing angles where the integrals are small.
  static constexpr double kInnerAccuracy = 1e-6;

  // Writes the link's coupling (rows receiver, columns source functions of degree `degree`).
  // The occluders are polygons[i], i in `candidates` (none for an unoccluded link); the
  // link's own patches must not be among them.
  Counts integrate(const Link& link, const std::vector<std::vector<Eigen::Vector3d>>& polygons,
                   const std::vector<int>& candidates, int degree,
                   Eigen::Map<Eigen::MatrixXd> coupling);

 private:
  bool mustSplit(const Piece& piece, int level) const;
  int children(const Piece& piece, Piece* out) const;
  void estimate(const Piece& piece, int points, Eigen::MatrixXd& out);
  void refine(const Piece& piece, int level, Eigen::MatrixXd& total);

  // The link being integrated (set by integrate).
  ExactVisibility* visibility_ = nullptr;
  SourceMoments* moments_ = nullptr;
  const Patch* receiver_ = nullptr;
  int maxLevel_, degree_ = 0, points_ = 2;
  double relativeTolerance_, scale_ = 1.0, tolerance_ = -1.0;
  Counts counts_;
  Eigen::MatrixXd coarse_, fine_;

  std::vector<Eigen::Vector3d> sourceCorners_, visibleSource_;  // S and S' (clipped)
  double visibleDiameter_ = 0.0;
  std::vector<char> bandMatters_;  // per edge of S'
  VisibleRings rings_;
};

}  // namespace radquad
