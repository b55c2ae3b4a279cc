#include "tests/radiosity/scenes_for_tests.h"

namespace radquad::testing {

using Vec = Eigen::Vector3d;

Scene furnaceScene(double emission, double rho) {
  Scene scene;
  const Vec x = Vec::UnitX(), y = Vec::UnitY(), z = Vec::UnitZ(), o = Vec::Zero();
  // (origin, edge_u, edge_v) with edge_u x edge_v pointing into the cube.
  const Vec faces[6][3] = {{o, x, y}, {z, y, x}, {o, z, x}, {y, x, z}, {o, y, z}, {x, z, y}};
  for (int f = 0; f < 6; ++f) {
    scene.patches.push_back(ScenePatch{"face " + std::to_string(f),
                                       Patch::make(faces[f][0], faces[f][1], faces[f][2], "face"),
                                       Vec::Constant(rho), Vec::Constant(emission)});
  }
  return scene;
}

Scene opposedSquaresScene(double rho) {
  Scene scene;
  scene.patches.push_back(
      ScenePatch{"emitter", Patch::make(Vec::Zero(), Vec::UnitX(), Vec::UnitY(), "emitter"),
                 Vec::Zero(), Vec::Constant(1.0)});
  scene.patches.push_back(
      ScenePatch{"receiver", Patch::make(Vec::UnitZ(), Vec::UnitY(), Vec::UnitX(), "receiver"),
                 Vec::Constant(rho), Vec::Zero()});
  return scene;
}

}  // namespace radquad::testing
