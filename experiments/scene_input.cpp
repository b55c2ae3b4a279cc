#include "experiments/scene_input.h"

#include <filesystem>

#include "experiments/json_input.h"
#include "kernel/input_error.h"

namespace radquad {
namespace {

Camera parseCamera(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where, {"eye", "look_at", "up", "fov_degrees", "width", "height"},
            {"eye", "look_at", "up", "fov_degrees", "width", "height"});
  Camera camera;
  camera.eye = finiteVector3(value["eye"], where + ".eye");
  camera.lookAt = finiteVector3(value["look_at"], where + ".look_at");
  camera.up = finiteVector3(value["up"], where + ".up");
  camera.fovDegrees = finiteNumber(value["fov_degrees"], where + ".fov_degrees");
  for (const char* key : {"width", "height"}) {
    if (!value[key].is_number_integer())
      throw InputError(where + "." + key + ": expected an integer");
  }
  camera.width = value["width"].get<int>();
  camera.height = value["height"].get<int>();
  return camera;
}

}  // namespace

Scene parseScene(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where, {"patches", "camera"}, {"patches"});
  const nlohmann::json& patches = value["patches"];
  if (!patches.is_array()) throw InputError(where + ": patches: expected an array");
  Scene scene;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const nlohmann::json& item = patches[k];
    std::string name;
    if (item.is_object() && item.contains("name")) {
      if (!item["name"].is_string()) {
        throw InputError(where + ": patches[" + std::to_string(k) + "].name: expected a string");
      }
      name = item["name"].get<std::string>();
    }
    const std::string patchWhere =
        where + ": patches[" + std::to_string(k) + "]" + (name.empty() ? "" : " (" + name + ")");
    ScenePatch patch;
    patch.name = name.empty() ? "patch " + std::to_string(k) : name;
    patch.patch = parsePatch(item, patchWhere, {"reflectance", "emission", "name"});
    if (!item.contains("reflectance")) throw InputError(patchWhere + ": missing key 'reflectance'");
    patch.reflectance = finiteVector3(item["reflectance"], patchWhere + ".reflectance");
    if (item.contains("emission")) {
      patch.emission = finiteVector3(item["emission"], patchWhere + ".emission");
    }
    scene.patches.push_back(std::move(patch));
  }
  if (value.contains("camera")) scene.camera = parseCamera(value["camera"], where + ": camera");
  validateScene(scene, where);
  return scene;
}

Scene loadScene(const std::string& nameOrPath) {
  if (auto builtin = builtinScene(nameOrPath)) return *builtin;
  if (!std::filesystem::exists(nameOrPath)) {
    std::string names;
    for (const std::string& name : builtinSceneNames()) names += (names.empty() ? "" : ", ") + name;
    throw InputError(nameOrPath + ": no such scene file, and not a built-in scene (" + names + ")");
  }
  return parseScene(readJsonFile(nameOrPath), nameOrPath);
}

}  // namespace radquad
