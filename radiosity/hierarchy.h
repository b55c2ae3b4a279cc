// The element hierarchy: one quadtree per patch. An element is a sub-parallelogram of its
// patch, [u0, u0+size] x [v0, v0+size] of the patch's parameter square, with its own
// orthonormal tensor Legendre basis of degree d (docs/design.md, "Conventions",
// with the element's own area) and RGB coefficients for
//   radiosity B   (what the element shows and sends),
//   gathered  E   (the irradiance coefficients arriving through the element's own links),
//   emission  B^e (the projection of the patch's constant emission).
// Radiosity B = B^e + rho E, channel by channel (rho constant per patch).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "kernel/patch.h"
#include "radiosity/scene.h"
#include "radiosity/two_scale.h"

namespace radquad {

struct Element {
  int patch = 0;
  int parent = -1;
  int firstChild = -1;  // the four children are firstChild .. firstChild+3, or none (-1)
  int level = 0;
  double u0 = 0.0, v0 = 0.0, size = 1.0;
  Patch geometry;
  Coefficients radiosity, gathered, emission;
  std::vector<int> links;  // indices of the active links that this element receives

  bool isLeaf() const { return firstChild < 0; }
  // The mean radiosity per channel: B_0 / sqrt(A) (the constant function is 1/sqrt(A)).
  Eigen::Vector3d meanRadiosity() const;
};

class Hierarchy {
 public:
  Hierarchy(const Scene& scene, int degree);

  int degree() const { return twoScale_.degree(); }
  int functions() const { return (degree() + 1) * (degree() + 1); }
  const TwoScale& twoScale() const { return twoScale_; }
  const Scene& scene() const { return *scene_; }

  std::size_t size() const { return elements_.size(); }
  Element& operator[](int e) { return elements_[std::size_t(e)]; }
  const Element& operator[](int e) const { return elements_[std::size_t(e)]; }
  // The root element of patch p (roots are elements 0 .. patches-1).
  int root(int p) const { return p; }

  // Creates the four children of a leaf (radiosity and emission pushed from it, gathered 0);
  // returns firstChild. Does nothing but return firstChild when the children exist.
  int subdivide(int e);

  // Push/pull of one patch's tree (Gortler et al. 1993, "PushPullRad"): the gathered
  // irradiance is pushed down to the leaves, B = B^e + rho E there, and the radiosity is
  // pulled back up by area-weighted projection.
  void pushPull(int p);

  // The leaf of patch p containing (u, v), and the radiosity there (the leaf's polynomial).
  int leafAt(int p, double u, double v) const;
  Eigen::Vector3d radiosityAt(int p, double u, double v) const;

  // Area-weighted L2 norm over all surfaces of the radiosity difference between two
  // solutions of the same scene (any refinements, any degrees), evaluated with a Gauss
  // rule of `points` per axis on every leaf of the finer of the two at each point, summed
  // over channels. Returns {||B_this - B_other||, ||B_other||}.
  std::pair<double, double> l2Difference(const Hierarchy& other, int points = 4) const;
  // The largest relative difference of a patch's mean radiosity from `other`'s, over patches
  // and channels (|B / B_other - 1|, channels where B_other is 0 left out), with its patch and
  // channel (0 red, 1 green, 2 blue); a global L2 difference can hide it.
  struct PatchDifference {
    double value = 0.0;
    int patch = -1;
    int channel = -1;
  };
  PatchDifference largestPatchDifference(const Hierarchy& other) const;

 private:
  void pushPullElement(int e, const Coefficients& down);

  const Scene* scene_;
  TwoScale twoScale_;
  std::vector<Element> elements_;
};

}  // namespace radquad
