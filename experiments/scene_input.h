// Scene files (radiosity/README.md, "Scene format"): parsed strictly, so that unknown keys,
// wrong types, degenerate patches and physically impossible materials are rejected with a
// message naming the file and the patch.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "radiosity/scene.h"

namespace radquad {

// `where` names the input in messages (a path).
Scene parseScene(const nlohmann::json& value, const std::string& where);

// A built-in scene name ("cornell", "slats") or a path to a scene JSON file.
Scene loadScene(const std::string& nameOrPath);

}  // namespace radquad
