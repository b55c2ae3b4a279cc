// Small scenes with known answers.
#pragma once

#include "radiosity/scene.h"

namespace radquad::testing {

// A scene patch with a grey reflectance `rho` and emission `emission` on every channel.
inline ScenePatch scenePatch(const std::string& name, const Eigen::Vector3d& origin,
                             const Eigen::Vector3d& edgeU, const Eigen::Vector3d& edgeV,
                             double rho, double emission = 0.0) {
  return ScenePatch{name, Patch::make(origin, edgeU, edgeV, name), Eigen::Vector3d::Constant(rho),
                    Eigen::Vector3d::Constant(emission)};
}

// The unit cube seen from inside, every face emitting `emission` with reflectance `rho`:
// the white furnace, whose exact radiosity is emission / (1 - rho) everywhere.
Scene furnaceScene(double emission, double rho);

// Two opposed unit squares at distance 1: a black emitter (E = 1) at z = 0 facing +z and a
// receiver with reflectance rho at z = 1 facing -z.
Scene opposedSquaresScene(double rho);

// The closed-form form factor between two opposed unit squares at distance 1
// (Howell's catalogue, configuration C-11).
inline constexpr double kOpposedUnitSquaresFormFactor = 0.1998248917;

}  // namespace radquad::testing
