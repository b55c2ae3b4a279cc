#include "experiments/rule_file.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "experiments/json_input.h"
#include "experiments/npz_input.h"
#include "kernel/input_error.h"
#include "quadrature/registry.h"
#include "quadrature/rules/data_rule.h"

namespace radquad {
namespace {

std::vector<double> numbers(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array()) throw InputError(where + ": expected an array of numbers");
  std::vector<double> out;
  for (std::size_t k = 0; k < value.size(); ++k) {
    out.push_back(finiteNumber(value[k], where + "[" + std::to_string(k) + "]"));
  }
  return out;
}

// Points of `dimension` coordinates and their weights, as columns.
std::vector<std::vector<double>> pointColumns(const nlohmann::json& points, std::size_t dimension,
                                              const std::string& where) {
  if (!points.is_array()) throw InputError(where + ": expected an array of points");
  std::vector<std::vector<double>> columns(dimension);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::string name = where + "[" + std::to_string(k) + "]";
    const std::vector<double> point = numbers(points[k], name);
    if (point.size() != dimension) {
      throw InputError(name + ": expected " + std::to_string(dimension) + " coordinates");
    }
    for (std::size_t axis = 0; axis < dimension; ++axis) columns[axis].push_back(point[axis]);
  }
  return columns;
}

PatchSamples patchSet(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where, {"points", "weights"}, {"points", "weights"});
  const auto columns = pointColumns(value["points"], 2, where + ".points");
  PatchSamples out;
  out.u = columns[0];
  out.v = columns[1];
  out.weight = numbers(value["weights"], where + ".weights");
  if (out.weight.size() != out.u.size()) {
    throw InputError(where + ": " + std::to_string(out.u.size()) + " points but " +
                     std::to_string(out.weight.size()) + " weights");
  }
  return out;
}

nlohmann::json patchSetJson(const PatchSamples& samples) {
  nlohmann::json points = nlohmann::json::array();
  for (std::size_t k = 0; k < samples.size(); ++k) points.push_back({samples.u[k], samples.v[k]});
  return {{"points", points}, {"weights", samples.weight}};
}

// An array of `rows` x `columns` numbers (columns 0: a vector) as JSON rows.
nlohmann::json npzMatrix(const NpyArray& array, std::size_t columns, const std::string& where) {
  if (array.isString) throw InputError(where + ": expected numbers, not strings");
  const bool shaped = columns == 0 ? array.shape.size() == 1
                                   : array.shape.size() == 2 && array.shape[1] == columns;
  if (!shaped) {
    std::string shape = "(";
    for (std::size_t k = 0; k < array.shape.size(); ++k) {
      shape += (k ? ", " : "") + std::to_string(array.shape[k]);
    }
    throw InputError(where + ": shape " + shape + ") where " +
                     (columns == 0 ? std::string("(N,)") : "(N, " + std::to_string(columns) + ")") +
                     " is expected");
  }
  nlohmann::json out = nlohmann::json::array();
  if (columns == 0) {
    for (double value : array.numbers) out.push_back(value);
    return out;
  }
  for (std::size_t row = 0; row < array.shape[0]; ++row) {
    nlohmann::json point = nlohmann::json::array();
    for (std::size_t c = 0; c < columns; ++c) point.push_back(array.numbers[row * columns + c]);
    out.push_back(std::move(point));
  }
  return out;
}

// An array of shape (T, N, columns) (columns 0: (T, N)) as T JSON matrices, one per draw.
std::vector<nlohmann::json> npzDraws(const NpyArray& array, std::size_t columns,
                                     const std::string& where) {
  const std::size_t axes = columns == 0 ? 2 : 3;
  if (array.isString || array.shape.size() != axes || (columns != 0 && array.shape[2] != columns)) {
    throw InputError(where + ": draws need shape " +
                     (columns == 0 ? std::string("(T, N)") : "(T, N, " + std::to_string(columns) + ")"));
  }
  std::vector<nlohmann::json> out;
  const std::size_t rows = array.shape[1], width = std::max<std::size_t>(columns, 1);
  for (std::size_t t = 0; t < array.shape[0]; ++t) {
    NpyArray slice;
    slice.shape = columns == 0 ? std::vector<std::size_t>{rows} : std::vector<std::size_t>{rows, columns};
    const auto begin = array.numbers.begin() + std::ptrdiff_t(t * rows * width);
    slice.numbers.assign(begin, begin + std::ptrdiff_t(rows * width));
    out.push_back(npzMatrix(slice, columns, where));
  }
  return out;
}

std::string npzString(const NpyArray& array, const std::string& where) {
  if (!array.isString || array.size() != 1) throw InputError(where + ": expected one string");
  return array.strings.front();
}

// The .npz arrays as the JSON form of the rule: points/weights, or receiver_points,
// receiver_weights, source_points, source_weights; name and citation strings, degree an
// integer (absent: none declared). The name defaults to the file's stem.
nlohmann::json npzRuleJson(const std::map<std::string, NpyArray>& arrays,
                           const std::filesystem::path& path) {
  const std::string where = path.string();
  nlohmann::json rule = {{"name", path.stem().string()}};
  // Draws of a random rule: points (T, N, 4) or receiver_points (T, N, 2) and their kin.
  const auto points = arrays.find("points");
  const auto receiverPoints = arrays.find("receiver_points");
  const bool stacked = (points != arrays.end() && points->second.shape.size() == 3) ||
                       (receiverPoints != arrays.end() && receiverPoints->second.shape.size() == 3);
  if (stacked) {
    nlohmann::json draws = nlohmann::json::array();
    auto member = [&](const std::string& name, std::size_t columns, auto&& place) {
      const auto found = arrays.find(name);
      if (found == arrays.end()) return;
      const auto matrices = npzDraws(found->second, columns, where + ": " + name);
      if (!draws.empty() && draws.size() != matrices.size()) {
        throw InputError(where + ": " + name + " holds " + std::to_string(matrices.size()) +
                         " draws, the other arrays " + std::to_string(draws.size()));
      }
      for (std::size_t t = 0; t < matrices.size(); ++t) {
        if (draws.size() <= t) draws.push_back(nlohmann::json::object());
        place(draws[t], matrices[t]);
      }
    };
    member("points", 4, [](nlohmann::json& d, const nlohmann::json& m) { d["points"] = m; });
    member("weights", 0, [](nlohmann::json& d, const nlohmann::json& m) { d["weights"] = m; });
    for (const std::string side : {"receiver", "source"}) {
      member(side + "_points", 2,
             [&](nlohmann::json& d, const nlohmann::json& m) { d[side]["points"] = m; });
      member(side + "_weights", 0,
             [&](nlohmann::json& d, const nlohmann::json& m) { d[side]["weights"] = m; });
    }
    rule["draws"] = std::move(draws);
  }
  for (const auto& [name, array] : arrays) {
    if (stacked && (name == "points" || name == "weights" || name == "receiver_points" ||
                    name == "receiver_weights" || name == "source_points" ||
                    name == "source_weights")) {
      continue;  // in the draws above
    }
    const std::string member = where + ": " + name;
    if (name == "name" || name == "citation") {
      rule[name] = npzString(array, member);
    } else if (name == "degree") {
      if (array.isString || array.size() != 1) throw InputError(member + ": expected one integer");
      const double degree = array.numbers.front();
      if (degree != std::floor(degree) || std::fabs(degree) > 1e9) {
        throw InputError(member + ": expected an integer");
      }
      rule["degree"] = (long long)(degree);
    } else if (name == "points") {
      rule["points"] = npzMatrix(array, 4, member);
    } else if (name == "weights") {
      rule["weights"] = npzMatrix(array, 0, member);
    } else if (name == "receiver_points" || name == "source_points") {
      rule[name.substr(0, name.find('_'))]["points"] = npzMatrix(array, 2, member);
    } else if (name == "receiver_weights" || name == "source_weights") {
      rule[name.substr(0, name.find('_'))]["weights"] = npzMatrix(array, 0, member);
    } else {
      throw InputError(member + ": unknown array (name, degree, citation, points, weights, "
                       "receiver_points, receiver_weights, source_points, source_weights)");
    }
  }
  return rule;
}

// One draw's points: {"points", "weights"} or {"receiver", "source"} (keys of `value` that
// belong to the draw; the caller has checked the others).
RuleSamples parseDraw(const nlohmann::json& value, const std::string& where) {
  const bool product = value.contains("receiver") || value.contains("source");
  const bool scattered = value.contains("points") || value.contains("weights");
  if (product == scattered) {
    throw InputError(where + ": give either points and weights, or receiver and source");
  }
  RuleSamples draw;
  draw.isProduct = product;
  if (product) {
    if (!value.contains("receiver") || !value.contains("source")) {
      throw InputError(where + ": a product rule needs both receiver and source");
    }
    draw.receiver = patchSet(value["receiver"], where + ": receiver");
    draw.source = patchSet(value["source"], where + ": source");
    return draw;
  }
  if (!value.contains("points") || !value.contains("weights")) {
    throw InputError(where + ": a rule of 4D points needs both points and weights");
  }
  const auto columns = pointColumns(value["points"], 4, where + ": points");
  draw.points.s = columns[0];
  draw.points.t = columns[1];
  draw.points.u = columns[2];
  draw.points.v = columns[3];
  draw.points.weight = numbers(value["weights"], where + ": weights");
  if (draw.points.weight.size() != draw.points.s.size()) {
    throw InputError(where + ": " + std::to_string(draw.points.s.size()) + " points but " +
                     std::to_string(draw.points.weight.size()) + " weights");
  }
  return draw;
}

nlohmann::json drawJson(const RuleSamples& samples) {
  nlohmann::json out = nlohmann::json::object();
  if (samples.isProduct) {
    out["receiver"] = patchSetJson(samples.receiver);
    out["source"] = patchSetJson(samples.source);
  } else {
    nlohmann::json points = nlohmann::json::array();
    const LinkSamples& p = samples.points;
    for (std::size_t k = 0; k < p.size(); ++k) points.push_back({p.s[k], p.t[k], p.u[k], p.v[k]});
    out["points"] = points;
    out["weights"] = p.weight;
  }
  return out;
}

}  // namespace

std::shared_ptr<const Rule> parseRuleJson(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where,
            {"name", "degree", "citation", "points", "weights", "receiver", "source", "draws"},
            {"name"});
  DataRuleSpec spec;
  if (!value["name"].is_string()) throw InputError(where + ": name must be a string");
  spec.name = value["name"].get<std::string>();
  if (value.contains("degree") && !value["degree"].is_null()) {
    if (!value["degree"].is_number_integer()) {
      throw InputError(where + ": degree must be an integer or null");
    }
    const long long degree = value["degree"].get<long long>();
    if (degree < 0 || degree > kMaxDataRuleDegree) {
      throw InputError(where + ": degree " + value["degree"].dump() + " is not in [0, " +
                       std::to_string(kMaxDataRuleDegree) + "] (or null)");
    }
    spec.degree = int(degree);
  }
  if (value.contains("citation")) {
    if (!value["citation"].is_string()) throw InputError(where + ": citation must be a string");
    spec.citation = value["citation"].get<std::string>();
  }
  if (value.contains("draws")) {
    for (const char* key : {"points", "weights", "receiver", "source"}) {
      if (value.contains(key)) {
        throw InputError(where + ": give either draws or one set of points, not both (" +
                         std::string(key) + ")");
      }
    }
    const nlohmann::json& draws = value["draws"];
    if (!draws.is_array() || draws.empty()) {
      throw InputError(where + ": draws must be a non-empty array of point sets");
    }
    spec.random = true;
    for (std::size_t d = 0; d < draws.size(); ++d) {
      const std::string at = where + ": draws[" + std::to_string(d) + "]";
      if (!draws[d].is_object()) throw InputError(at + ": expected an object");
      checkKeys(draws[d], at, {"points", "weights", "receiver", "source"}, {});
      spec.draws.push_back(parseDraw(draws[d], at));
    }
  } else {
    spec.draws.push_back(parseDraw(value, where));
  }
  return makeDataRule(std::move(spec), where);
}

std::shared_ptr<const Rule> loadRuleFile(const std::filesystem::path& path) {
  if (path.extension() == ".npz") return parseRuleJson(npzRuleJson(readNpz(path), path), path.string());
  return parseRuleJson(readJsonFile(path), path.string());
}

std::shared_ptr<const Rule> findAnyRule(std::string_view name) {
  constexpr std::string_view prefix = "File:";
  if (name.substr(0, prefix.size()) == prefix) {
    const std::string_view path = name.substr(prefix.size());
    if (path.empty()) throw InputError("rule 'File:': expected File:PATH");
    return loadRuleFile(std::filesystem::path(std::string(path)));
  }
  try {
    return findRule(name);
  } catch (const InputError& error) {
    throw InputError(std::string(error.what()) + ", File:PATH");
  }
}

void checkSampleBudget(const Rule& rule, int trials, const std::string& where) {
  const double total = double(rule.sampleCount()) * double(std::max(trials, 1));
  if (total > kMaxSamplesPerLink) {
    throw InputError(where + ": " + std::to_string(rule.sampleCount()) + " samples x " +
                     std::to_string(trials) + " trials exceed the budget of 1e10 kernel "
                     "evaluations per link");
  }
}

nlohmann::json ruleToJson(const Rule& rule, std::uint64_t seed, int draws) {
  const auto degree = rule.degree();
  nlohmann::json out = {{"name", rule.name()},
                        {"degree", degree ? nlohmann::json(*degree) : nlohmann::json(nullptr)},
                        {"citation", rule.citation()}};
  if (rule.drawCount() > 0) {  // a listed rule is written whole
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t d = 0; d < rule.drawCount(); ++d) list.push_back(drawJson(rule.listedDraw(d)));
    out["draws"] = std::move(list);
    return out;
  }
  if (draws > 0 && rule.isRandom()) {
    if (seed > ~std::uint64_t(0) - std::uint64_t(draws - 1)) {
      throw InputError("seed " + std::to_string(seed) + " with " + std::to_string(draws) +
                       " draws: the last seed would pass 2^64 - 1");
    }
    checkSampleBudget(rule, draws, "rule " + rule.name());
    nlohmann::json list = nlohmann::json::array();
    for (int d = 0; d < draws; ++d) list.push_back(drawJson(rule.samples(seed + std::uint64_t(d))));
    out["draws"] = std::move(list);
    return out;
  }
  out.update(drawJson(rule.samples(seed)));
  return out;
}

nlohmann::json registeredRulesJson() {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& rule : namedRules()) {
    const auto degree = rule->degree();
    out.push_back({{"name", rule->name()},
                   {"samples", rule->sampleCount()},
                   {"degree", degree ? nlohmann::json(*degree) : nlohmann::json(nullptr)},
                   {"family", rule->family()},
                   {"citation", rule->citation()}});
  }
  return out;
}

}  // namespace radquad
