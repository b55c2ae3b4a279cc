#include "experiments/rule_file.h"
#include "experiments/study/study_config.h"

#include "experiments/json_input.h"
#include "experiments/study/reference_estimate.h"
#include "kernel/input_error.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

int positiveInteger(const nlohmann::json& value, const std::string& where, long long limit) {
  if (!value.is_number_integer() || value.get<long long>() < 1 || value.get<long long>() > limit) {
    throw InputError(where + ": expected an integer in [1, " + std::to_string(limit) + "]");
  }
  return value.get<int>();
}

std::string ruleName(const nlohmann::json& value, const std::string& where) {
  if (!value.is_string()) throw InputError(where + ": expected a rule name (a string)");
  const std::string name = value.get<std::string>();
  try {
    findAnyRule(name);
  } catch (const InputError& error) {
    throw InputError(where + ": " + error.what());
  }
  return name;
}

}  // namespace

StudyConfig parseStudyConfig(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where,
            {"_doc", "figure", "seed", "classes", "rules", "trials", "reference", "gold",
             "visible_fraction", "max_candidates_per_link", "geometry", "links"},
            {"figure", "seed", "classes", "rules"});
  StudyConfig config;
  const auto& figure = value["figure"];
  if (figure == "fig1") {
    config.figure = StudyFigure::fig1;
  } else if (figure == "fig2") {
    config.figure = StudyFigure::fig2;
  } else {
    throw InputError(where + ": figure: expected \"fig1\" or \"fig2\", got " + figure.dump());
  }
  if (!value["seed"].is_number_unsigned())
    throw InputError(where + ": seed: expected an unsigned integer");
  config.seed = value["seed"].get<std::uint64_t>();

  const auto& classes = value["classes"];
  checkKeys(classes, where + ": classes", {"unoccluded", "partial", "singular"}, {});
  for (const StudyClass linkClass :
       {StudyClass::unoccluded, StudyClass::partial, StudyClass::singular}) {
    const char* name = studyClassName(linkClass);
    if (classes.contains(name)) {
      config.classes.emplace_back(
          linkClass, positiveInteger(classes[name], where + ": classes: " + name, 1000000));
    }
  }
  if (config.classes.empty()) throw InputError(where + ": classes: name at least one class");
  if (config.figure == StudyFigure::fig1 &&
      (config.classes.size() != 1 || config.classes[0].first != StudyClass::partial)) {
    throw InputError(where + ": classes: Figure 1 is measured on partial links only");
  }

  const auto& rules = value["rules"];
  if (!rules.is_array() || rules.empty())
    throw InputError(where + ": rules: expected a non-empty array");
  for (std::size_t k = 0; k < rules.size(); ++k) {
    config.rules.push_back(ruleName(rules[k], where + ": rules[" + std::to_string(k) + "]"));
  }
  if (value.contains("trials"))
    config.trials = positiveInteger(value["trials"], where + ": trials", 100000);
  if (value.contains("reference"))
    config.reference = parseReferenceOptions(value["reference"], where + ": reference");
  if (value.contains("gold")) config.gold = parseGoldOptions(value["gold"], where + ": gold");
  if (value.contains("visible_fraction")) {
    const auto& range = value["visible_fraction"];
    if (!range.is_array() || range.size() != 2) {
      throw InputError(where + ": visible_fraction: expected [low, high]");
    }
    config.minVisibleFraction = finiteNumber(range[0], where + ": visible_fraction[0]");
    config.maxVisibleFraction = finiteNumber(range[1], where + ": visible_fraction[1]");
    if (!(0.0 <= config.minVisibleFraction &&
          config.minVisibleFraction < config.maxVisibleFraction &&
          config.maxVisibleFraction <= 1.0)) {
      throw InputError(where + ": visible_fraction: expected 0 <= low < high <= 1");
    }
  }
  if (value.contains("max_candidates_per_link")) {
    config.maxCandidatesPerLink = positiveInteger(value["max_candidates_per_link"],
                                                  where + ": max_candidates_per_link", 100000);
  }
  if (value.contains("geometry"))
    config.geometry = parseGeometryRanges(value["geometry"], where + ": geometry");
  if (value.contains("links")) {
    if (value.contains("geometry")) {
      throw InputError(where + ": links: scene-derived links take no geometry");
    }
    config.sceneLinks = parseSceneLinkOptions(value["links"], where + ": links");
  } else if (classes.contains("singular")) {
    throw InputError(where + ": classes: singular links are scene-derived only (generated "
                             "links never touch); give \"links\"");
  }
  return config;
}

StudyConfig readStudyConfig(const std::filesystem::path& path) {
  return parseStudyConfig(readJsonFile(path), path.string());
}

nlohmann::json studyConfigToJson(const StudyConfig& config) {
  nlohmann::json classes = nlohmann::json::object();
  for (const auto& [linkClass, count] : config.classes) classes[studyClassName(linkClass)] = count;
  nlohmann::json out = {{"figure", config.figure == StudyFigure::fig1 ? "fig1" : "fig2"},
          {"degree", config.degree()},
          {"seed", config.seed},
          {"classes", classes},
          {"rules", config.rules},
          {"trials", config.trials},
          {"reference", referenceOptionsToJson(config.reference)},
          {"gold", goldOptionsToJson(config.gold)},
          {"visible_fraction", {config.minVisibleFraction, config.maxVisibleFraction}},
          {"max_candidates_per_link", config.maxCandidatesPerLink},
          {"geometry", geometryRangesToJson(config.geometry)}};
  if (config.sceneLinks) {
    out.erase("geometry");
    out.erase("visible_fraction");
    out["links"] = sceneLinkOptionsToJson(*config.sceneLinks);
  }
  return out;
}

}  // namespace radquad
