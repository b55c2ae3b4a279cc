// Stratified (jittered) sampling on [0,1]^4: every axis cut into k strata, one uniformly
// jittered point in each of the k^4 cells, weight 1/k^4.
//
// Citation: J. Neyman, "On the two different aspects of the representative method", J. Roy.
// Statist. Soc. 97 (1934) (stratified sampling); R. L. Cook, "Stochastic sampling in
// computer graphics", ACM TOG 5 (1986) (jittering); Gershbein 1995, section 3 ("Stratified",
// 3 strata per axis) and section 4 (the 10,000-point reference, 10 strata per axis).
//
// | name           | samples | parameter                |
// |----------------|---------|--------------------------|
// | `Stratified`   | 81      | k = 3                    |
// | `Reference`    | 10,000  | k = 10                   |
// | `Stratified:k` | k^4     | k = 1..56 strata per axis |
// Degree: none. Seed: the cell c = ((i_s k + i_t) k + i_u) k + i_v draws its jitter from
// Philox blocks 2c and 2c+1 of stream randomStream(kFamily, 0), so the point of a cell depends only on
// (seed, c). Order: for odd k, point p is cell p. For even k, points come in blocks of 2 x 2
// x 2 x 2 cells: point p = 16 b + i lies in the cell with digits i_x = 2 b_x + (bit x of i),
// (b_s, b_t, b_u, b_v) the digits of b in base k / 2 and i's bits 3, 2, 1, 0 for s, t, u, v.
// Consecutive points are then near each other on both patches, so a packet of 16 visibility
// rays (kernel/occluder_scene.h) spans a narrow beam instead of a strip across the source:
// the dense stratified gold of a 1,000-triangle soup costs about a third less (the same
// points, summed in another order). pointStream(seed) gives the same points in the same order,
// any range of them, which the reference integrates without storing them.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "quadrature/random/random_rule.h"

namespace radquad {

class StratifiedRule : public RandomPointRule {
 public:
  explicit StratifiedRule(int strataPerAxis, std::string name = "");

  std::string name() const override { return name_; }
  std::size_t sampleCount() const override;
  static constexpr std::string_view kFamily = "Stratified Monte Carlo";  // also names its random streams
  std::string family() const override { return std::string(kFamily); }
  std::string citation() const override;
  void drawSamples(std::uint64_t seed, RuleSamples& out) const override;
  std::unique_ptr<PointStream> pointStream(std::uint64_t seed) const override;

  // Writes points first .. first + count - 1 of the draw `seed` (what samples(seed) lists at
  // those indices, in the order above) to s, t, u, v.
  void fillPoints(std::uint64_t seed, std::size_t first, std::size_t count, double* s, double* t,
                  double* u, double* v) const;

  int strataPerAxis() const { return strata_; }

 private:
  int strata_;
  std::string name_;
};

std::shared_ptr<const Rule> makeStratifiedRule(const std::string& parameter);

}  // namespace radquad
