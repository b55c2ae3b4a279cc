// Built against an installed radquad: integrates the form factor between two opposed unit
// squares one unit apart with a 8^4-point Gauss product from the rule registry and checks
// it against the closed form (Howell's catalogue, C-11: 0.1998248917). Exit 0 when it agrees
// within 1e-6, 1 otherwise.
#include <cmath>
#include <cstdio>

#include "kernel/coupling.h"
#include "kernel/patch.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"

int main() {
  using radquad::Patch;
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY();
  const radquad::Link link{Patch::make(Eigen::Vector3d::UnitZ(), y, x, "receiver"),
                           Patch::make(Eigen::Vector3d::Zero(), x, y, "source"), nullptr};
  const radquad::PreparedRule rule(radquad::findRule("Gauss:8x8x8x8"), 0);
  const double formFactor = rule.integrate(link).formFactor;
  const double exact = 0.1998248917;
  std::printf("form factor %.10f, closed form %.10f\n", formFactor, exact);
  return std::abs(formFactor - exact) < 1e-6 ? 0 : 1;
}
