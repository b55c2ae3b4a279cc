// The path tracer on two-sided surfaces made of coincident, opposite-facing patches (twins):
// which patches are plane mates, which face a ray hits, and whole traces against exact
// answers (Howell C-11 on both faces of a twin panel, a lamp with a coincident dark back, a
// tilted twin panel in the white furnace), with the twins coincident to the bit and off by
// less than the mates' tolerance either way.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "radiosity/path_tracer.h"
#include "radiosity/trace_scene.h"
#include "tests/radiosity/scenes_for_tests.h"
#include "tests/support/analytic_form_factors.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;
using testing::scenePatch;

TraceResult trace(const Scene& scene, std::uint64_t samples, std::uint64_t seed = 0) {
  TraceOptions options;
  options.samples = samples;
  options.seed = seed;
  return tracePatches(scene, options);
}

// The unit square at height z facing +z (up) or -z (down), its corners listed from `start`
// (twins whose corners come in another order make Embree split the quads along the other
// diagonal, so the two faces' hit distances need not agree to the bit).
Patch square(double z, bool up, int start = 0) {
  const Vec corners[4] = {Vec(0, 0, z), Vec(1, 0, z), Vec(1, 1, z), Vec(0, 1, z)};
  const Vec& o = corners[start % 4];
  const Vec a = corners[(start + 1) % 4] - o, b = corners[(start + 3) % 4] - o;
  return up ? Patch::make(o, a, b, "square") : Patch::make(o, b, a, "square");
}

ScenePatch named(const std::string& name, const Patch& patch, double rho, double emission = 0) {
  return ScenePatch{name, patch, Vec::Constant(rho), Vec::Constant(emission)};
}

TEST(PlaneMatesTest, CoplanarPatchesThatMeetAreMatesAndNothingElse) {
  Scene scene;
  scene.patches.push_back(named("up", square(0.0, true), 0.5));
  scene.patches.push_back(named("down", square(0.0, false, 2), 0.5));       // twin
  scene.patches.push_back(named("off by 1e-9", square(1e-9, false), 0.5));  // near twin
  scene.patches.push_back(named("gap 1e-3", square(-1e-3, false), 0.5));    // a slab
  scene.patches.push_back(
      named("tile", scenePatch("t", Vec(1, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), 0.5).patch,
            0.5));  // touches
  scene.patches.push_back(
      named("far tile", scenePatch("f", Vec(3, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), 0.5).patch, 0.5));
  const std::vector<std::vector<int>> mates = planeMates(scene);
  EXPECT_EQ(mates[0], (std::vector<int>{0, 1, 2, 4}));
  EXPECT_EQ(mates[1], (std::vector<int>{0, 1, 2, 4}));
  EXPECT_EQ(mates[3], (std::vector<int>{3}));
  EXPECT_EQ(mates[4], (std::vector<int>{0, 1, 2, 4}));
  EXPECT_EQ(mates[5], (std::vector<int>{5}));
}

// A ray arriving at a twin pair hits the face turned to it, whichever Embree meets first and
// in whichever order the faces are listed; a ray leaving one face passes its twin.
TEST(TraceSceneTest, ARayHitsTheFaceOfATwinPanelThatFacesIt) {
  for (const double offset : {0.0, 1e-9, -1e-9}) {
    for (int start = 0; start < 4; ++start) {
      for (const bool upFirst : {true, false}) {
        Scene scene;
        const Patch up = square(0.0, true), down = square(offset, false, start);
        scene.patches.push_back(named("first", upFirst ? up : down, 0.5));
        scene.patches.push_back(named("second", upFirst ? down : up, 0.5));
        scene.patches.push_back(named("roof", square(1.0, false), 0.5));
        const int upIndex = upFirst ? 0 : 1, downIndex = 1 - upIndex;
        const TraceScene rays(scene);
        const std::string what = "offset " + std::to_string(offset) + " start " +
                                 std::to_string(start) + (upFirst ? " up first" : " down first");
        double t = 0.0;
        for (const Vec& at : {Vec(0.3, 0.6, 0.0), Vec(0.71, 0.2, 0.0), Vec(0.5, 0.5, 0.0)}) {
          EXPECT_EQ(rays.firstHit(at + Vec(0.1, 0.05, 0.5), Vec(-0.1, -0.05, -0.5), -1, t), upIndex)
              << what;
          EXPECT_NEAR(t, 1.0, 1e-6) << what;
          EXPECT_EQ(rays.firstHit(at - Vec(0.1, 0.2, 0.5), Vec(0.1, 0.2, 0.5), -1, t), downIndex)
              << what;
          // Leaving the upper face upwards: the roof, not the twin at distance 0.
          EXPECT_EQ(rays.firstHit(at, Vec(0.01, 0.02, 1.0), upIndex, t), 2) << what;
          // Leaving the lower face downwards: nothing.
          EXPECT_EQ(rays.firstHit(at, Vec(0.01, 0.02, -1.0), downIndex, t), -1) << what;
          // Shadow rays from either face pass the twin; from elsewhere the panel blocks.
          EXPECT_TRUE(rays.unobstructed(at, Vec(0.2, 0.3, 1.0), upIndex, 2)) << what;
          EXPECT_FALSE(rays.unobstructed(at + Vec(0, 0, 0.5), at - Vec(0, 0, 0.5), 2, 2)) << what;
        }
        EXPECT_TRUE(rays.mates(upIndex, downIndex));
        EXPECT_FALSE(rays.mates(upIndex, 2));
      }
    }
  }
}

// Where a twin panel is smaller than its other face, the uncovered part of the larger face's
// back is still a back side: it stops the ray, and the hit reports it.
TEST(TraceSceneTest, ABackSideWithoutATwinStillStopsTheRay) {
  Scene scene;
  scene.patches.push_back(named("up", square(0.0, true), 0.5));
  scene.patches.push_back(
      named("half down", Patch::make(Vec::Zero(), Vec(0, 0.5, 0), Vec(1, 0, 0), "h"), 0.5));
  const TraceScene rays(scene);
  double t = 0.0;
  EXPECT_EQ(rays.firstHit(Vec(0.5, 0.25, -1), Vec(0, 0, 1), -1, t), 1);  // under the twin
  EXPECT_EQ(rays.firstHit(Vec(0.5, 0.75, -1), Vec(0, 0, 1), -1, t), 0);  // the bare back
}

// A twin panel at z = 1 between two black unit emitters at z = 0 and z = 2: each face's
// radiosity is rho F, F the form factor of opposed unit squares at distance 1 (Howell C-11).
TEST(PathTracerTwinsTest, BothFacesOfATwinPanelMatchTheClosedForm) {
  const double rho = 0.5;
  const double exact = rho * analytic::parallelRectangles(1.0, 1.0, 1.0);
  for (const double offset : {0.0, 1e-9, -1e-9}) {
    for (const bool upFirst : {true, false}) {
      Scene scene;
      scene.patches.push_back(named("floor light", square(0.0, true), 0.0, 1.0));
      scene.patches.push_back(named("roof light", square(2.0, false), 0.0, 1.0));
      const Patch down = square(1.0, false), up = square(1.0 + offset, true, 1);
      scene.patches.push_back(named("first", upFirst ? up : down, rho));
      scene.patches.push_back(named("second", upFirst ? down : up, rho));
      const TraceResult result = trace(scene, 16384);
      for (const std::size_t face : {2u, 3u}) {
        const double mean = result.patches[face].meanRadiosity[0];
        const double error = result.patches[face].standardError[0];
        EXPECT_LT(error, 0.005 * exact);
        EXPECT_NEAR(mean, exact, 4.0 * error)
            << "face " << face << " offset " << offset << (upFirst ? " up first" : "");
      }
    }
  }
}

// A lamp: a black emitter at z = 1 facing down whose back is a coincident grey patch facing
// up, lit by a black emitter at z = 2. The receiver at z = 0 and the lamp's back each read
// rho F (C-11): shadow rays to the lamp end on its twin, and direction samples that reach
// the lamp from below must see the emitting face.
TEST(PathTracerTwinsTest, ALampWithACoincidentDarkBack) {
  const double rho = 0.5;
  const double exact = rho * analytic::parallelRectangles(1.0, 1.0, 1.0);
  for (const bool lampFirst : {true, false}) {
    Scene scene;
    scene.patches.push_back(named("receiver", square(0.0, true), rho));
    const ScenePatch lamp = named("lamp", square(1.0, false), 0.0, 1.0);
    const ScenePatch back = named("lamp back", square(1.0, true, 3), rho);
    scene.patches.push_back(lampFirst ? lamp : back);
    scene.patches.push_back(lampFirst ? back : lamp);
    scene.patches.push_back(named("roof light", square(2.0, false), 0.0, 1.0));
    const TraceResult result = trace(scene, 16384);
    for (const std::size_t p : {std::size_t(0), lampFirst ? std::size_t(2) : std::size_t(1)}) {
      const double mean = result.patches[p].meanRadiosity[0];
      const double error = result.patches[p].standardError[0];
      EXPECT_LT(error, 0.005 * exact);
      EXPECT_NEAR(mean, exact, 4.0 * error) << scene.patches[p].name;
    }
  }
}

// A tilted two-sided panel (twin patches) hung in the white furnace (every patch E = 1,
// rho = 0.5): every point, on the walls or on either face, sees only front sides, so the
// radiosity is exactly E / (1 - rho) = 2 everywhere.
TEST(PathTracerTwinsTest, ATwinPanelInTheFurnaceReadsTheExactRadiosity) {
  const double exact = 2.0;
  const Vec o(0.2, 0.3, 0.25), a(0.5, 0.1, 0.15), b(0.05, 0.35, 0.3);
  const Vec shift = 1e-9 * a.cross(b).normalized();
  for (const Vec& offset : {Vec(Vec::Zero()), shift, Vec(-shift)}) {
    Scene scene = testing::furnaceScene(1.0, 0.5);
    scene.patches.push_back(
        ScenePatch{"front", Patch::make(o, a, b, "front"), Vec::Constant(0.5), Vec::Constant(1.0)});
    scene.patches.push_back(ScenePatch{"back", Patch::make(o + offset + a, -a, b, "back"),
                                       Vec::Constant(0.5), Vec::Constant(1.0)});
    const TraceResult result = trace(scene, 4096);
    for (std::size_t p = 0; p < scene.patches.size(); ++p) {
      const double mean = result.patches[p].meanRadiosity[0];
      const double error = result.patches[p].standardError[0];
      EXPECT_LT(error, 0.01 * exact) << scene.patches[p].name;
      EXPECT_NEAR(mean, exact, 4.5 * error) << scene.patches[p].name << " offset " << offset.norm();
    }
  }
}

}  // namespace
}  // namespace radquad
