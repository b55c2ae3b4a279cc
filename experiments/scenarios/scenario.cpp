#include "experiments/scenarios/scenario.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "experiments/json_input.h"
#include "experiments/scenarios/random_stream.h"
#include "kernel/input_error.h"

namespace radquad {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

const std::array<std::pair<Orientation, const char*>, 3> kOrientationNames = {{
    {Orientation::parallel, "parallel"},
    {Orientation::perpendicular, "perpendicular"},
    {Orientation::tilted, "tilted"},
}};
const std::array<std::pair<OccluderKind, const char*>, 5> kOccluderNames = {{
    {OccluderKind::none, "none"},
    {OccluderKind::oneBlocker, "one_blocker"},
    {OccluderKind::severalBlockers, "several_blockers"},
    {OccluderKind::slats, "slats"},
    {OccluderKind::soup, "soup"},
}};

template <typename Enum, std::size_t N>
std::vector<Enum> parseNames(const nlohmann::json& value, const std::string& where,
                             const std::array<std::pair<Enum, const char*>, N>& names,
                             std::size_t firstAllowed) {
  if (!value.is_array() || value.empty())
    throw InputError(where + ": expected a non-empty array of names");
  std::vector<Enum> out;
  for (std::size_t k = 0; k < value.size(); ++k) {
    const std::string item = value[k].is_string() ? value[k].get<std::string>() : "";
    bool found = false;
    std::string valid;
    for (std::size_t n = firstAllowed; n < N; ++n) {
      valid += std::string(valid.empty() ? "" : ", ") + names[n].second;
      if (item == names[n].second) {
        out.push_back(names[n].first);
        found = true;
      }
    }
    if (!found) {
      throw InputError(where + "[" + std::to_string(k) + "]: unknown name " + value[k].dump() +
                       " (valid: " + valid + ")");
    }
  }
  return out;
}

constexpr double kMaxGeneratedSide = 1e9;
constexpr double kMaxDistanceFactor = 1e4;

double positive(const nlohmann::json& object, const char* key, const std::string& where,
                double fallback) {
  if (!object.contains(key)) return fallback;
  const double number = finiteNumber(object[key], where + ": " + key);
  if (number <= 0.0) throw InputError(where + ": " + key + " must be positive");
  return number;
}

// A right-handed orthonormal pair (e1, e2) with e1 x e2 = n.
std::pair<Eigen::Vector3d, Eigen::Vector3d> planeAxes(const Eigen::Vector3d& n) {
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (helper - helper.dot(n) * n).normalized();
  return {e1, n.cross(e1)};
}

// A w x h parallelogram centred at `centre` with edges along e1 and e2.
Patch centredPatch(const Eigen::Vector3d& centre, const Eigen::Vector3d& e1,
                   const Eigen::Vector3d& e2, double w, double h, const char* what) {
  return Patch::make(centre - 0.5 * w * e1 - 0.5 * h * e2, w * e1, h * e2, what);
}

Eigen::Vector3d randomUnitInPlane(ScenarioRandom& random, const Eigen::Vector3d& e1,
                                  const Eigen::Vector3d& e2) {
  const double angle = random.uniform(0.0, 2.0 * std::numbers::pi);
  return std::cos(angle) * e1 + std::sin(angle) * e2;
}

// Every corner of `patch` strictly in front of `other` (by a margin): then the patches do
// not touch and both cosines are positive everywhere.
bool inFrontOf(const Patch& patch, const Patch& other, double margin) {
  for (const double u : {0.0, 1.0}) {
    for (const double v : {0.0, 1.0}) {
      if (other.normal.dot(patch.pointAt(u, v) - other.origin) <= margin) return false;
    }
  }
  return true;
}

void placePatches(const GeometryRanges& ranges, ScenarioRandom& random, GeneratedLink& link) {
  double a, b, c, e;
  if (random.uniform() < ranges.mixedFraction) {
    a = random.logUniform(ranges.minSide, ranges.maxSide);
    b = random.logUniform(ranges.minSide, ranges.maxSide);
    c = random.logUniform(ranges.minSide, ranges.maxSide);
    e = random.logUniform(ranges.minSide, ranges.maxSide);
  } else {
    a = b = c = e = random.logUniform(ranges.minSide, ranges.maxSide);
  }
  const double largest = std::max({a, b, c, e});
  link.distanceFactor = random.logUniform(ranges.minDistanceFactor, ranges.maxDistanceFactor);
  const double distance = link.distanceFactor * largest;
  link.orientation = ranges.orientations[random.index(ranges.orientations.size())];
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  link.receiver = centredPatch(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                               Eigen::Vector3d::UnitY(), a, b, "receiver");

  if (link.orientation == Orientation::perpendicular) {
    const Eigen::Vector3d n = -Eigen::Vector3d::UnitX();
    const double elevation = random.uniform(20.0, 70.0) * kDegree;
    const double height = std::max(distance * std::sin(elevation), 0.5 * e + 0.05 * largest);
    const Eigen::Vector3d centre(0.5 * a + distance * std::cos(elevation),
                                 random.uniform(-0.25, 0.25) * largest, height);
    link.source = centredPatch(centre, Eigen::Vector3d::UnitY(), n.cross(Eigen::Vector3d::UnitY()),
                               c, e, "source");
    return;
  }
  const Eigen::Vector3d centre(random.uniform(-0.25, 0.25) * largest,
                               random.uniform(-0.25, 0.25) * largest, distance);
  const double spin = random.uniform(0.0, 0.5 * std::numbers::pi);
  const Eigen::Vector3d n = -z;
  const Eigen::Vector3d e1(std::cos(spin), std::sin(spin), 0.0);
  const Eigen::Vector3d e2 = n.cross(e1);
  link.source = centredPatch(centre, e1, e2, c, e, "source");
  if (link.orientation == Orientation::parallel) return;

  // Tilted: redraw both tilts until each patch lies wholly in front of the other (a zero
  // tilt always qualifies, so this ends).
  const Patch flatReceiver = link.receiver;
  const Patch flatSource = link.source;
  for (int attempt = 0;; ++attempt) {
    const double scale = attempt < 1000 ? 1.0 : 0.0;
    const auto tilt = [&](const Patch& patch, const Eigen::Vector3d& u1,
                          const Eigen::Vector3d& u2) {
      const Eigen::Vector3d axis = randomUnitInPlane(random, u1, u2);
      const double angle = scale * random.uniform(0.0, ranges.maxTiltDegrees) * kDegree;
      const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
      const Eigen::Vector3d middle = patch.centre();
      return Patch::make(middle + rotation * (patch.origin - middle), rotation * patch.edgeU,
                         rotation * patch.edgeV, "tilted patch");
    };
    link.receiver = tilt(flatReceiver, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    link.source = tilt(flatSource, e1, e2);
    const double margin = 1e-3 * largest;
    if (inFrontOf(link.source, link.receiver, margin) &&
        inFrontOf(link.receiver, link.source, margin))
      return;
  }
}

// A parallelogram across the beam at fraction `along` from the receiver's centre to the
// source's, offset laterally, spun and tilted by up to 30 degrees out of the cross-section.
Patch beamBlocker(ScenarioRandom& random, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                  double along, double lateral, double w, double h) {
  const Eigen::Vector3d axis = (to - from).normalized();
  const auto [p, q] = planeAxes(axis);
  const Eigen::Vector3d centre = from + along * (to - from) +
                                 random.uniform(-lateral, lateral) * p +
                                 random.uniform(-lateral, lateral) * q;
  const double spin = random.uniform(0.0, std::numbers::pi);
  Eigen::Vector3d u1 = std::cos(spin) * p + std::sin(spin) * q;
  const Eigen::Vector3d u2 = axis.cross(u1);
  const double tilt = random.uniform(-30.0, 30.0) * kDegree;
  u1 = std::cos(tilt) * u1 + std::sin(tilt) * axis;
  return centredPatch(centre, u1, u2, w, h, "blocker");
}

void placeOccluders(const GeometryRanges& ranges, ScenarioRandom& random, GeneratedLink& link) {
  link.occluderKind = ranges.occluders[random.index(ranges.occluders.size())];
  const Eigen::Vector3d from = link.receiver.centre();
  const Eigen::Vector3d to = link.source.centre();
  const double largest = std::max({link.receiver.edgeU.norm(), link.receiver.edgeV.norm(),
                                   link.source.edgeU.norm(), link.source.edgeV.norm()});
  switch (link.occluderKind) {
    case OccluderKind::none:
    case OccluderKind::scene:  // never in the ranges (not a parseable name)
      return;
    case OccluderKind::oneBlocker: {
      const double w = random.uniform(0.3, 1.0) * largest, h = random.uniform(0.3, 1.0) * largest;
      link.parallelograms.push_back(
          beamBlocker(random, from, to, random.uniform(0.3, 0.7), 0.3 * largest, w, h));
      return;
    }
    case OccluderKind::severalBlockers: {
      const int count = 2 + int(random.index(5));
      for (int k = 0; k < count; ++k) {
        const double w = random.uniform(0.15, 0.5) * largest,
                     h = random.uniform(0.15, 0.5) * largest;
        link.parallelograms.push_back(
            beamBlocker(random, from, to, random.uniform(0.2, 0.8), 0.5 * largest, w, h));
      }
      return;
    }
    case OccluderKind::slats: {
      const Eigen::Vector3d axis = (to - from).normalized();
      const auto [p0, q0] = planeAxes(axis);
      const double spin = random.uniform(0.0, std::numbers::pi);
      const Eigen::Vector3d p = std::cos(spin) * p0 + std::sin(spin) * q0;
      const Eigen::Vector3d q = axis.cross(p);
      const Eigen::Vector3d centre = from + random.uniform(0.3, 0.7) * (to - from);
      const int count = 5 + int(random.index(11));
      const double span = 1.6 * largest, pitch = span / count;
      const double width = random.uniform(0.2, 0.7) * pitch;
      const bool crossed = random.uniform() < 0.3;
      for (int set = 0; set < (crossed ? 2 : 1); ++set) {
        const Eigen::Vector3d across = set == 0 ? p : q, along = set == 0 ? q : p;
        for (int k = 0; k < count; ++k) {
          const double offset = (k + 0.5) * pitch - 0.5 * span;
          // The second set sits a hair behind the first so the two never coincide.
          const Eigen::Vector3d middle = centre + offset * across + set * 1e-3 * largest * axis;
          link.parallelograms.push_back(centredPatch(middle, across, along, width, span, "slat"));
        }
      }
      return;
    }
    case OccluderKind::soup: {
      const Eigen::Vector3d axis = (to - from).normalized();
      const auto [p, q] = planeAxes(axis);
      for (int k = 0; k < ranges.soupTriangles; ++k) {
        const Eigen::Vector3d centre = from + random.uniform(0.2, 0.8) * (to - from) +
                                       random.uniform(-0.7, 0.7) * largest * p +
                                       random.uniform(-0.7, 0.7) * largest * q;
        const double size = random.logUniform(0.03, 0.12) * largest;
        std::array<Eigen::Vector3d, 3> corners;
        for (Eigen::Vector3d& corner : corners) {
          corner = centre + size * Eigen::Vector3d(random.uniform(-1, 1), random.uniform(-1, 1),
                                                   random.uniform(-1, 1));
        }
        link.addTriangle(corners[0], corners[1], corners[2]);
      }
      return;
    }
  }
}

}  // namespace

const char* studyClassName(StudyClass linkClass) {
  switch (linkClass) {
    case StudyClass::unoccluded: return "unoccluded";
    case StudyClass::partial: return "partial";
    case StudyClass::singular: return "singular";
  }
  return "partial";
}
const char* orientationName(Orientation orientation) {
  for (const auto& [value, name] : kOrientationNames)
    if (value == orientation) return name;
  return "?";
}
const char* occluderKindName(OccluderKind kind) {
  for (const auto& [value, name] : kOccluderNames)
    if (value == kind) return name;
  if (kind == OccluderKind::scene) return "scene";
  return "?";
}

GeometryRanges parseGeometryRanges(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where,
            {"min_side", "max_side", "mixed_fraction", "min_distance_factor", "max_distance_factor",
             "orientations", "max_tilt_degrees", "occluders", "soup_triangles"},
            {});
  GeometryRanges ranges;
  ranges.minSide = positive(value, "min_side", where, ranges.minSide);
  ranges.maxSide = positive(value, "max_side", where, ranges.maxSide);
  ranges.minDistanceFactor =
      positive(value, "min_distance_factor", where, ranges.minDistanceFactor);
  ranges.maxDistanceFactor =
      positive(value, "max_distance_factor", where, ranges.maxDistanceFactor);
  if (ranges.minSide > ranges.maxSide) throw InputError(where + ": min_side exceeds max_side");
  // Generated corners stay far inside the coordinate limit of link geometry (1e15).
  if (ranges.maxSide > kMaxGeneratedSide) {
    throw InputError(where + ": max_side must be at most " + std::to_string(kMaxGeneratedSide));
  }
  if (ranges.maxDistanceFactor > kMaxDistanceFactor) {
    throw InputError(where + ": max_distance_factor must be at most " +
                     std::to_string(kMaxDistanceFactor));
  }
  if (ranges.minDistanceFactor > ranges.maxDistanceFactor) {
    throw InputError(where + ": min_distance_factor exceeds max_distance_factor");
  }
  if (value.contains("mixed_fraction")) {
    ranges.mixedFraction = finiteNumber(value["mixed_fraction"], where + ": mixed_fraction");
    if (ranges.mixedFraction < 0.0 || ranges.mixedFraction > 1.0) {
      throw InputError(where + ": mixed_fraction must lie in [0, 1]");
    }
  }
  if (value.contains("max_tilt_degrees")) {
    ranges.maxTiltDegrees = finiteNumber(value["max_tilt_degrees"], where + ": max_tilt_degrees");
    if (ranges.maxTiltDegrees < 0.0 || ranges.maxTiltDegrees >= 90.0) {
      throw InputError(where + ": max_tilt_degrees must lie in [0, 90)");
    }
  }
  if (value.contains("orientations")) {
    ranges.orientations =
        parseNames(value["orientations"], where + ": orientations", kOrientationNames, 0);
  }
  if (value.contains("occluders")) {
    ranges.occluders = parseNames(value["occluders"], where + ": occluders", kOccluderNames, 1);
  }
  if (value.contains("soup_triangles")) {
    const auto& count = value["soup_triangles"];
    if (!count.is_number_integer() || count.get<long long>() < 1 ||
        count.get<long long>() > 1000000) {
      throw InputError(where + ": soup_triangles must be an integer in [1, 1000000]");
    }
    ranges.soupTriangles = count.get<int>();
  }
  return ranges;
}

nlohmann::json geometryRangesToJson(const GeometryRanges& ranges) {
  nlohmann::json orientations = nlohmann::json::array(), occluders = nlohmann::json::array();
  for (const auto orientation : ranges.orientations)
    orientations.push_back(orientationName(orientation));
  for (const auto kind : ranges.occluders) occluders.push_back(occluderKindName(kind));
  return {{"min_side", ranges.minSide},
          {"max_side", ranges.maxSide},
          {"mixed_fraction", ranges.mixedFraction},
          {"min_distance_factor", ranges.minDistanceFactor},
          {"max_distance_factor", ranges.maxDistanceFactor},
          {"orientations", orientations},
          {"max_tilt_degrees", ranges.maxTiltDegrees},
          {"occluders", occluders},
          {"soup_triangles", ranges.soupTriangles}};
}

GeneratedLink generateLink(const GeometryRanges& ranges, StudyClass linkClass, std::uint64_t seed) {
  ScenarioRandom random(seed);
  GeneratedLink link;
  placePatches(ranges, random, link);
  if (linkClass == StudyClass::partial) placeOccluders(ranges, random, link);
  return link;
}

}  // namespace radquad
