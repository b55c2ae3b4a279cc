#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "kernel/input_error.h"
#include "kernel/patch.h"

namespace radquad {
namespace {

TEST(Patch, NormalAndAreaFollowTheEdges) {
  const Patch patch = Patch::make({1, 2, 3}, {2, 0, 0}, {1, 3, 0}, "p");
  EXPECT_DOUBLE_EQ(patch.area, 6.0);
  EXPECT_EQ(patch.normal, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(patch.pointAt(1, 1), Eigen::Vector3d(4, 5, 3));
}

void expectRejected(const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    const std::string& fragment) {
  try {
    Patch::make(o, a, b, "occluders[2]");
    FAIL() << "accepted a bad patch";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("occluders[2]"), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

TEST(Patch, RejectsDegenerateAndNonFinitePatches) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expectRejected({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, "degenerate");
  expectRejected({0, 0, 0}, {1, 1, 0}, {2, 2, 0}, "degenerate");
  expectRejected({0, 0, 0}, {1, 0, 0}, {1, 1e-12, 0}, "degenerate");
  expectRejected({nan, 0, 0}, {1, 0, 0}, {0, 1, 0}, "finite");
  expectRejected({0, 0, 0}, {inf, 0, 0}, {0, 1, 0}, "finite");
  // Finite in double, beyond what single-precision tracing can hold.
  expectRejected({0, 1, 1}, {7.8e63, 0, 1}, {5, -2, 0}, "coordinate limit");
  expectRejected({2e15, 0, 0}, {1, 0, 0}, {0, 1, 0}, "coordinate limit");
  EXPECT_NO_THROW(Patch::make({-1e14, 0, 0}, {1e14, 0, 0}, {0, 1e14, 0}, "large"));
}

}  // namespace
}  // namespace radquad
