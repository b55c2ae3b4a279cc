// The Monte Carlo path tracer against exact answers: the white furnace, its energy balance
// with one emitting face, a box standing in it, and two closed-form form factors (Howell C-11 and C-14), the second
// with receiver points touching the emitter.
#include <gtest/gtest.h>

#include <cmath>

#include "radiosity/path_tracer.h"
#include "tests/radiosity/scenes_for_tests.h"
#include "tests/support/analytic_form_factors.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

TraceResult trace(const Scene& scene, std::uint64_t samples, std::uint64_t seed = 0) {
  TraceOptions options;
  options.samples = samples;
  options.seed = seed;
  return tracePatches(scene, options);
}

// Every face's normal points into the unit cube, so the furnace is closed from inside.
TEST(PathTracerFurnaceTest, FacesPointIntoTheCube) {
  const Scene scene = testing::furnaceScene(1.0, 0.5);
  ASSERT_EQ(scene.patches.size(), 6u);
  const Vec centre = Vec::Constant(0.5);
  for (const ScenePatch& face : scene.patches) {
    EXPECT_NEAR(face.patch.area, 1.0, 1e-12) << face.name;
    EXPECT_GT(face.patch.normal.dot(centre - face.patch.centre()), 0.49) << face.name;
  }
}

// E = 1 and rho = 0.5 on every face: B = E / (1 - rho) = 2 everywhere.
TEST(PathTracerFurnaceTest, RadiosityIsEmissionOverOneMinusReflectance) {
  const double emission = 1.0, rho = 0.5, exact = emission / (1.0 - rho);
  const TraceResult result = trace(testing::furnaceScene(emission, rho), 4096);
  for (std::size_t p = 0; p < result.patches.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      const double mean = result.patches[p].meanRadiosity[c];
      const double error = result.patches[p].standardError[c];
      EXPECT_GT(error, 0.0) << "face " << p;  // roulette makes the estimate random
      EXPECT_LT(error, 0.01 * exact) << "face " << p;
      EXPECT_NEAR(mean, exact, 4.5 * error) << "face " << p << " channel " << c;
    }
  }
  EXPECT_EQ(result.truncatedPaths, 0u);
}

// Only face 0 emits (E = 1), rho = 0.5 everywhere. In a closed box every patch's outgoing
// power lands on the box, so sum A_i B_i = sum A_i E_i / (1 - rho): the area-weighted mean
// radiosity is (1/6) / (1 - rho) = 1/3. The emitting face itself is brightest.
TEST(PathTracerFurnaceTest, OneEmittingFaceConservesEnergy) {
  const double rho = 0.5;
  Scene scene = testing::furnaceScene(0.0, rho);
  scene.patches[0].emission = Vec::Constant(1.0);
  const TraceResult result = trace(scene, 4096);
  for (int c = 0; c < 3; ++c) {
    double power = 0.0, variance = 0.0, area = 0.0;
    for (std::size_t p = 0; p < scene.patches.size(); ++p) {
      const double a = scene.patches[p].patch.area;
      power += a * result.patches[p].meanRadiosity[c];
      variance += a * a * std::pow(result.patches[p].standardError[c], 2);
      area += a;
    }
    const double mean = power / area, error = std::sqrt(variance) / area;
    const double exact = (1.0 / 6.0) / (1.0 - rho);
    EXPECT_LT(error, 0.01 * exact);
    EXPECT_NEAR(mean, exact, 4.5 * error) << "channel " << c;
  }
  for (std::size_t p = 1; p < scene.patches.size(); ++p) {
    EXPECT_GT(result.patches[0].meanRadiosity[0], result.patches[p].meanRadiosity[0]);
  }
}

// A patch along `facing`: the edges are swapped when edge_u x edge_v points the other way.
Patch facingPatch(const Vec& origin, const Vec& u, const Vec& v, const Vec& facing) {
  return u.cross(v).dot(facing) >= 0.0 ? Patch::make(origin, u, v, "block")
                                       : Patch::make(origin, v, u, "block");
}

// The furnace with a rotated box standing on its floor (face 0, z = 0), every patch E = 1 and
// rho = 0.5: a point outside the box sees only front sides, so B = 2 there, on the box's
// outward faces and on every wall but the floor; the floor under the box sees only the box's
// back sides, so B = E = 1 there, and the floor's mean is 2 - (box footprint) / 1. Exercises
// patches touching along edges at arbitrary angles, and back sides that end paths.
TEST(PathTracerFurnaceTest, ABoxStandingInTheFurnace) {
  Scene scene = testing::furnaceScene(1.0, 0.5);
  ASSERT_GT(scene.patches[0].patch.normal.z(), 0.99);
  const double angle = 0.3, width = 0.4, depth = 0.35, height = 0.3;
  const Vec ex = width * Vec(std::cos(angle), std::sin(angle), 0.0);
  const Vec ey = depth * Vec(-std::sin(angle), std::cos(angle), 0.0);
  const Vec ez = height * Vec::UnitZ();
  const Vec base = Vec(0.5, 0.5, 0.0) - 0.5 * ex - 0.5 * ey;
  const Patch faces[5] = {facingPatch(base, ey, ez, -ex), facingPatch(base + ex, ey, ez, ex),
                          facingPatch(base, ex, ez, -ey), facingPatch(base + ey, ex, ez, ey),
                          facingPatch(base + ez, ex, ey, ez)};
  for (const Patch& face : faces) {
    scene.patches.push_back(ScenePatch{"box", face, Vec::Constant(0.5), Vec::Constant(1.0)});
  }
  const TraceResult result = trace(scene, 4096);
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    const double exact = p == 0 ? 2.0 - width * depth : 2.0;
    const double mean = result.patches[p].meanRadiosity[0];
    const double error = result.patches[p].standardError[0];
    EXPECT_LT(error, 0.01 * exact) << "patch " << p;
    EXPECT_NEAR(mean, exact, 4.5 * error) << "patch " << p;
  }
}

// A black emitter (E = 1, rho = 0) facing a receiver (rho = 0.5, E = 0) at distance 1: the
// receiver's mean radiosity is rho F, F the form factor of opposed unit squares.
TEST(PathTracerFormFactorTest, OpposedSquares) {
  const double rho = 0.5;
  const double exact = rho * analytic::parallelRectangles(1.0, 1.0, 1.0);
  ASSERT_NEAR(exact / rho, 0.19982489569838746, 1e-15);
  const TraceResult result = trace(testing::opposedSquaresScene(rho), 16384);
  // The emitter shows its emission only, exactly.
  EXPECT_EQ(result.patches[0].meanRadiosity, Vec::Constant(1.0));
  EXPECT_EQ(result.patches[0].standardError, Vec::Zero());
  for (int c = 0; c < 3; ++c) {
    const double mean = result.patches[1].meanRadiosity[c];
    const double error = result.patches[1].standardError[c];
    EXPECT_LT(error, 0.005 * exact);
    EXPECT_NEAR(mean, exact, 4.0 * error) << "channel " << c;
  }
}

// Two unit squares at right angles sharing an edge (Howell C-14): receiver points near the
// edge touch the emitter, where G is unbounded; the MIS weights keep every term below E.
TEST(PathTracerFormFactorTest, PerpendicularSquaresSharingAnEdge) {
  const double rho = 0.5;
  const double exact = rho * analytic::perpendicularRectangles(1.0, 1.0, 1.0);
  Scene scene;
  // The emitter in z = 0 facing +z; the receiver in y = 0 facing +y; common edge on the x axis.
  scene.patches.push_back(
      ScenePatch{"emitter", Patch::make(Vec::Zero(), Vec::UnitX(), Vec::UnitY(), "emitter"),
                 Vec::Zero(), Vec::Constant(1.0)});
  scene.patches.push_back(
      ScenePatch{"receiver", Patch::make(Vec::Zero(), Vec::UnitZ(), Vec::UnitX(), "receiver"),
                 Vec::Constant(rho), Vec::Zero()});
  ASSERT_GT(scene.patches[1].patch.normal.y(), 0.99);
  const TraceResult result = trace(scene, 131072);
  for (int c = 0; c < 3; ++c) {
    const double mean = result.patches[1].meanRadiosity[c];
    const double error = result.patches[1].standardError[c];
    EXPECT_LT(error, 0.005 * exact);
    EXPECT_NEAR(mean, exact, 4.0 * error) << "channel " << c;
  }
}

}  // namespace
}  // namespace radquad
