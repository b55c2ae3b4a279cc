#include "radiosity/hierarchy.h"
#include "kernel/input_error.h"

#include <cmath>

#include "kernel/legendre_basis.h"
#include "quadrature/gauss_legendre.h"

namespace radquad {
namespace {

// The constant emission B^e projected on an element: only the constant function,
// coefficient B^e sqrt(A) (since M_0 = 1/sqrt(A)).
Coefficients emissionCoefficients(const Eigen::Vector3d& emission, double area, int functions) {
  Coefficients coefficients = Coefficients::Zero(functions, 3);
  coefficients.row(0) = emission.transpose() * std::sqrt(area);
  return coefficients;
}

}  // namespace

Eigen::Vector3d Element::meanRadiosity() const {
  return radiosity.row(0).transpose() / std::sqrt(geometry.area);
}

Hierarchy::Hierarchy(const Scene& scene, int degree) : scene_(&scene), twoScale_(degree) {
  elements_.reserve(scene.patches.size() * 16);
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    Element root;
    root.patch = int(p);
    root.geometry = scene.patches[p].patch;
    root.emission =
        emissionCoefficients(scene.patches[p].emission, root.geometry.area, functions());
    root.radiosity = root.emission;
    root.gathered = Coefficients::Zero(functions(), 3);
    elements_.push_back(std::move(root));
  }
}

int Hierarchy::subdivide(int e) {
  if (!elements_[std::size_t(e)].isLeaf()) return elements_[std::size_t(e)].firstChild;
  const int first = int(elements_.size());
  for (int c = 0; c < 4; ++c) {
    const Element& parent = elements_[std::size_t(e)];
    Element child;
    child.patch = parent.patch;
    child.parent = e;
    child.level = parent.level + 1;
    child.size = 0.5 * parent.size;
    child.u0 = parent.u0 + (c / 2) * child.size;
    child.v0 = parent.v0 + (c % 2) * child.size;
    const Patch& patch = scene_->patches[std::size_t(parent.patch)].patch;
    child.geometry = Patch::make(patch.pointAt(child.u0, child.v0), patch.edgeU * child.size,
                                 patch.edgeV * child.size, "element");
    child.radiosity = twoScale_.push(parent.radiosity, c);
    child.emission = twoScale_.push(parent.emission, c);
    child.gathered = Coefficients::Zero(functions(), 3);
    elements_.push_back(std::move(child));  // may reallocate: `parent` is not used after this
  }
  elements_[std::size_t(e)].firstChild = first;
  return first;
}

void Hierarchy::pushPull(int p) {
  pushPullElement(root(p), Coefficients::Zero(functions(), 3));
}

void Hierarchy::pushPullElement(int e, const Coefficients& down) {
  Element& element = elements_[std::size_t(e)];
  const Coefficients total = element.gathered + down;
  if (element.isLeaf()) {
    const Eigen::Vector3d& rho = scene_->patches[std::size_t(element.patch)].reflectance;
    element.radiosity = element.emission + total * rho.asDiagonal();
    return;
  }
  Coefficients pulled = Coefficients::Zero(functions(), 3);
  for (int c = 0; c < 4; ++c) {
    const int child = element.firstChild + c;
    pushPullElement(child, twoScale_.push(total, c));
    twoScale_.pullAdd(elements_[std::size_t(child)].radiosity, c, pulled);
  }
  element.radiosity = pulled;
}

int Hierarchy::leafAt(int p, double u, double v) const {
  int e = root(p);
  while (!elements_[std::size_t(e)].isLeaf()) {
    const Element& element = elements_[std::size_t(e)];
    const double half = 0.5 * element.size;
    const int cu = u >= element.u0 + half ? 1 : 0;
    const int cv = v >= element.v0 + half ? 1 : 0;
    e = element.firstChild + 2 * cu + cv;
  }
  return e;
}

Eigen::Vector3d Hierarchy::radiosityAt(int p, double u, double v) const {
  const Element& leaf = elements_[std::size_t(leafAt(p, u, v))];
  double values[basisFunctionCount(kMaxBasisDegree)];
  const double lu = std::clamp((u - leaf.u0) / leaf.size, 0.0, 1.0);
  const double lv = std::clamp((v - leaf.v0) / leaf.size, 0.0, 1.0);
  tensorBasisValues(degree(), lu, lv, values);
  Eigen::Vector3d result = Eigen::Vector3d::Zero();
  for (int a = 0; a < functions(); ++a) result += values[a] * leaf.radiosity.row(a).transpose();
  return result / std::sqrt(leaf.geometry.area);
}

namespace {

// Integrates |B_a - B_b|^2 and |B_b|^2 over the region of element ea (in a) / eb (in b),
// descending wherever either tree is finer.
void accumulateDifference(const Hierarchy& a, int ea, const Hierarchy& b, int eb, int points,
                          double& difference, double& norm) {
  const Element& elementA = a[ea];
  const Element& elementB = b[eb];
  if (!elementA.isLeaf() || !elementB.isLeaf()) {
    for (int c = 0; c < 4; ++c) {
      accumulateDifference(a, elementA.isLeaf() ? ea : elementA.firstChild + c, b,
                           elementB.isLeaf() ? eb : elementB.firstChild + c, points, difference,
                           norm);
    }
    return;
  }
  // Same region on both sides only when both descend together: take the smaller one.
  const Element& region = elementA.size <= elementB.size ? elementA : elementB;
  const GaussLegendreRule& gauss = gaussLegendreUnit(points);
  const double area = region.geometry.area;
  for (std::size_t i = 0; i < gauss.nodes.size(); ++i) {
    for (std::size_t j = 0; j < gauss.nodes.size(); ++j) {
      const double u = region.u0 + gauss.nodes[i] * region.size;
      const double v = region.v0 + gauss.nodes[j] * region.size;
      const double w = gauss.weights[i] * gauss.weights[j] * area;
      const Eigen::Vector3d valueA = a.radiosityAt(region.patch, u, v);
      const Eigen::Vector3d valueB = b.radiosityAt(region.patch, u, v);
      difference += w * (valueA - valueB).squaredNorm();
      norm += w * valueB.squaredNorm();
    }
  }
}

}  // namespace

std::pair<double, double> Hierarchy::l2Difference(const Hierarchy& other, int points) const {
  RADQUAD_REQUIRE(scene_->patches.size() == other.scene().patches.size());
  double difference = 0.0, norm = 0.0;
  for (std::size_t p = 0; p < scene_->patches.size(); ++p) {
    accumulateDifference(*this, root(int(p)), other, other.root(int(p)), points, difference, norm);
  }
  return {std::sqrt(difference), std::sqrt(norm)};
}

Hierarchy::PatchDifference Hierarchy::largestPatchDifference(const Hierarchy& other) const {
  PatchDifference largest;
  for (std::size_t p = 0; p < scene_->patches.size(); ++p) {
    const Eigen::Vector3d mine = elements_[std::size_t(root(int(p)))].meanRadiosity();
    const Eigen::Vector3d theirs = other[other.root(int(p))].meanRadiosity();
    for (int c = 0; c < 3; ++c) {
      if (theirs[c] == 0.0) continue;
      const double difference = mine[c] / theirs[c] - 1.0;
      if (std::abs(difference) > std::abs(largest.value) || largest.patch < 0) {
        largest = {difference, int(p), c};
      }
    }
  }
  return largest;
}

}  // namespace radquad
