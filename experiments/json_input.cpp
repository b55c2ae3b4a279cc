#include <cerrno>
#include <cstdlib>
#include "experiments/json_input.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "kernel/input_error.h"
#include "kernel/patch_intersection.h"

namespace radquad {

std::uint64_t maxInputBytes() {
  const char* value = std::getenv("RADQUAD_MAX_INPUT_BYTES");
  if (value == nullptr || *value == '\0') return kDefaultMaxInputBytes;
  char* end = nullptr;
  errno = 0;
  const unsigned long long parsed = std::strtoull(value, &end, 10);
  if (errno != 0 || *end != '\0' || parsed == 0 || value[0] == '-') {
    throw InputError(std::string("RADQUAD_MAX_INPUT_BYTES: expected a positive decimal integer, got '") +
                     value + "'");
  }
  return parsed;
}

std::string quotedKey(const std::string& key) {
  constexpr std::size_t kShown = 80;
  if (key.size() <= kShown) return key;
  return key.substr(0, kShown) + "... (" + std::to_string(key.size()) + " characters)";
}

nlohmann::json readJsonFile(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError(path.string() + ": is a folder");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  // Read at most the cap plus one byte, so that a device or a pipe without end (/dev/zero)
  // is refused after the cap instead of filling memory.
  const std::uint64_t cap = maxInputBytes();
  std::string text;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    text.append(buffer, std::size_t(in.gcount()));
    if (text.size() > cap) {
      throw InputError(path.string() + ": larger than the input limit of " + std::to_string(cap) +
                       " bytes (set RADQUAD_MAX_INPUT_BYTES to raise it)");
    }
  }
  return parseJsonText(text, path.string());
}

nlohmann::json parseJsonText(const std::string& text, const std::string& where) {
  // Keys seen in each open object, innermost last: a key given twice in one object is an
  // error (nlohmann keeps the last one silently).
  std::vector<std::vector<std::string>> openObjects;
  const auto rejectDuplicateKeys = [&](int, nlohmann::json::parse_event_t event,
                                       nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start) openObjects.emplace_back();
    if (event == Event::object_end && !openObjects.empty()) openObjects.pop_back();
    if (event == Event::key && !openObjects.empty()) {
      const std::string key = parsed.get<std::string>();
      for (const std::string& seen : openObjects.back()) {
        if (seen == key) throw InputError(where + ": duplicate key '" + quotedKey(key) + "'");
      }
      openObjects.back().push_back(key);
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, rejectDuplicateKeys);
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(where + ": malformed JSON: " + error.what());
  } catch (const nlohmann::json::out_of_range& error) {
    // A literal such as 1e999 overflows to infinity while parsing.
    throw InputError(where + ": non-finite number: " + error.what());
  }
}

void checkKeys(const nlohmann::json& object, const std::string& where,
               const std::vector<const char*>& allowed, const std::vector<const char*>& required) {
  if (!object.is_object()) throw InputError(where + ": expected a JSON object");
  for (const auto& item : object.items()) {
    bool known = false;
    for (const char* key : allowed) known = known || item.key() == key;
    if (!known) {
      std::string list;
      for (const char* key : allowed) list += std::string(list.empty() ? "" : ", ") + key;
      throw InputError(where + ": unknown key '" + quotedKey(item.key()) + "' (allowed: " + list +
                       ")");
    }
  }
  for (const char* key : required) {
    if (!object.contains(key)) throw InputError(where + ": missing key '" + key + "'");
  }
}

double finiteNumber(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number()) throw InputError(where + ": expected a number");
  const double number = value.get<double>();
  if (!std::isfinite(number)) throw InputError(where + ": expected a finite number");
  return number;
}

Eigen::Vector3d finiteVector3(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array() || value.size() != 3) {
    throw InputError(where + ": expected an array of 3 numbers");
  }
  Eigen::Vector3d vector;
  for (int axis = 0; axis < 3; ++axis) {
    vector[axis] = finiteNumber(value[axis], where + "[" + std::to_string(axis) + "]");
  }
  return vector;
}

Patch parsePatch(const nlohmann::json& value, const std::string& where,
                 std::initializer_list<const char*> extraKeys) {
  std::vector<const char*> allowed = {"origin", "edge_u", "edge_v"};
  allowed.insert(allowed.end(), extraKeys.begin(), extraKeys.end());
  checkKeys(value, where, allowed, {"origin", "edge_u", "edge_v"});
  return Patch::make(finiteVector3(value["origin"], where + ".origin"),
                     finiteVector3(value["edge_u"], where + ".edge_u"),
                     finiteVector3(value["edge_v"], where + ".edge_v"), where);
}

LinkGeometry parseLink(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where, {"receiver", "source", "occluders"}, {"receiver", "source"});
  LinkGeometry link;
  link.receiver = parsePatch(value["receiver"], where + ": receiver");
  link.source = parsePatch(value["source"], where + ": source");
  if (const auto crossing = patchesInterpenetrate(link.receiver, link.source)) {
    throw InputError(where + ": receiver and source " + *crossing +
                     " (the kernel is not integrable there; touching along an edge is allowed)");
  }
  if (value.contains("occluders")) {
    const auto& occluders = value["occluders"];
    if (!occluders.is_array()) throw InputError(where + ": occluders: expected an array");
    for (std::size_t k = 0; k < occluders.size(); ++k) {
      const std::string name = where + ": occluders[" + std::to_string(k) + "]";
      if (occluders[k].is_object() && occluders[k].contains("triangle")) {
        checkKeys(occluders[k], name, {"triangle"}, {"triangle"});
        const auto& corners = occluders[k]["triangle"];
        if (!corners.is_array() || corners.size() != 3) {
          throw InputError(name + ".triangle: expected an array of 3 points");
        }
        std::array<Eigen::Vector3d, 3> triangle;
        for (int c = 0; c < 3; ++c) {
          triangle[std::size_t(c)] =
              finiteVector3(corners[std::size_t(c)], name + ".triangle[" + std::to_string(c) + "]");
          if (triangle[std::size_t(c)].cwiseAbs().maxCoeff() > kMaxCoordinate) {
            throw InputError(name + ".triangle[" + std::to_string(c) +
                             "]: a coordinate beyond 1e15 (single-precision ray tracing)");
          }
        }
        if (!((triangle[1] - triangle[0]).cross(triangle[2] - triangle[0]).norm() > 0.0)) {
          throw InputError(name + ".triangle: degenerate (zero area)");
        }
        link.addTriangle(triangle[0], triangle[1], triangle[2]);
        continue;
      }
      link.parallelograms.push_back(parsePatch(occluders[k], name));
    }
  }
  return link;
}

LinkGeometry readLinkFile(const std::filesystem::path& path) {
  return parseLink(readJsonFile(path), path.string());
}

nlohmann::json patchToJson(const Patch& patch) {
  auto vector = [](const Eigen::Vector3d& v) { return nlohmann::json{v.x(), v.y(), v.z()}; };
  return {{"origin", vector(patch.origin)},
          {"edge_u", vector(patch.edgeU)},
          {"edge_v", vector(patch.edgeV)}};
}

nlohmann::json occluderToJson(const std::vector<Eigen::Vector3d>& polygon) {
  auto vector = [](const Eigen::Vector3d& v) { return nlohmann::json{v.x(), v.y(), v.z()}; };
  if (polygon.size() == 4) {
    return {{"origin", vector(polygon[0])},
            {"edge_u", vector(polygon[1] - polygon[0])},
            {"edge_v", vector(polygon[3] - polygon[0])}};
  }
  if (polygon.size() != 3) {
    throw std::logic_error("occluderToJson: a polygon of " + std::to_string(polygon.size()) +
                           " vertices");
  }
  return {{"triangle", {vector(polygon[0]), vector(polygon[1]), vector(polygon[2])}}};
}

nlohmann::json matrixToJson(const Eigen::MatrixXd& matrix) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index a = 0; a < matrix.rows(); ++a) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index b = 0; b < matrix.cols(); ++b) row.push_back(matrix(a, b));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace radquad
