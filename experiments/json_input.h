// Strict JSON input: every file radquad reads goes through these helpers, so that unknown
// keys, wrong types, wrong lengths and non-finite numbers are rejected with a message that
// names the file and the offending key.
#pragma once

#include <array>

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "kernel/coupling.h"
#include "kernel/link_geometry.h"
#include "kernel/occluder_scene.h"
#include "kernel/patch.h"

namespace radquad {

// Input files are read up to a size limit: 256 MiB by default, or the positive decimal
// number of bytes in the environment variable RADQUAD_MAX_INPUT_BYTES.
inline constexpr std::uint64_t kDefaultMaxInputBytes = 256ull << 20;
std::uint64_t maxInputBytes();

// A key as error messages quote it: at most its first 80 characters (an input may hold a
// key of megabytes).
std::string quotedKey(const std::string& key);

// Reads and parses a JSON file; InputError names the path when it cannot be read or parsed
// (a folder is named as one), or is larger than maxInputBytes() (devices and pipes included:
// reading stops there).
nlohmann::json readJsonFile(const std::filesystem::path& path);
// The same rules (duplicate keys, non-finite literals) on text in memory; `where` names it.
nlohmann::json parseJsonText(const std::string& text, const std::string& where);

// Throws InputError when `object` is not an object or has a key outside `allowed`, or misses
// one of `required`. `where` names the object in messages (e.g. "link.json: receiver").
void checkKeys(const nlohmann::json& object, const std::string& where,
               const std::vector<const char*>& allowed, const std::vector<const char*>& required);

double finiteNumber(const nlohmann::json& value, const std::string& where);
Eigen::Vector3d finiteVector3(const nlohmann::json& value, const std::string& where);

// PATCH = {"origin": [x,y,z], "edge_u": [x,y,z], "edge_v": [x,y,z]}, plus `extraKeys`.
Patch parsePatch(const nlohmann::json& value, const std::string& where,
                 std::initializer_list<const char*> extraKeys = {});

// LINK.json = {"receiver": PATCH, "source": PATCH, "occluders": [OCCLUDER, ...]}, an occluder
// a parallelogram PATCH or a triangle {"triangle": [a, b, c]}.
LinkGeometry parseLink(const nlohmann::json& value, const std::string& where);
LinkGeometry readLinkFile(const std::filesystem::path& path);

nlohmann::json patchToJson(const Patch& patch);
// An occluder polygon as a link file writes it: a parallelogram (4 corners in Patch::corners
// order) as {origin, edge_u, edge_v}, a triangle as {"triangle": [a, b, c]}.
nlohmann::json occluderToJson(const std::vector<Eigen::Vector3d>& polygon);
nlohmann::json matrixToJson(const Eigen::MatrixXd& matrix);

}  // namespace radquad
