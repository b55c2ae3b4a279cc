#include "experiments/study/baseline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "kernel/input_error.h"

namespace radquad {
namespace {

constexpr int kSchema = 1;

// The table's rule entries per class: Figure 1's top-level list is the class "partial".
std::map<std::string, const nlohmann::json*> rulesByClass(const nlohmann::json& table,
                                                          const std::string& where) {
  std::map<std::string, const nlohmann::json*> classes;
  if (!table.is_object()) throw InputError(where + ": not a study table (a JSON object)");
  if (table.contains("classes") && table["classes"].is_object()) {
    for (const auto& [name, part] : table["classes"].items()) {
      if (!part.is_object() || !part.contains("rules") || !part["rules"].is_array()) {
        throw InputError(where + ": class '" + name + "' has no rule list");
      }
      classes[name] = &part["rules"];
    }
  } else if (table.contains("rules") && table["rules"].is_array()) {
    classes["partial"] = &table["rules"];
  }
  if (classes.empty() || !table.contains("options") || !table["options"].is_object()) {
    throw InputError(where + ": not a study table (no options, classes or rules)");
  }
  return classes;
}

// The suite a table describes: its options but for the rules scored and the config's path.
nlohmann::json suiteOf(const nlohmann::json& table) {
  nlohmann::json suite = table["options"];
  suite.erase("rules");
  suite.erase("config_path");
  return suite;
}

// The candidates scored, per class: the links themselves. A visibility ray that rounds the
// other way on another machine can accept or reject a candidate near the visible-fraction
// limits; then every rule's scores are of other links, and no band can say anything.
nlohmann::json linksOf(const nlohmann::json& table, const std::string& where) {
  nlohmann::json links = nlohmann::json::object();
  auto candidates = [&](const nlohmann::json& perLink) {
    nlohmann::json ids = nlohmann::json::array();
    if (!perLink.is_array()) throw InputError(where + ": per_link is not a list");
    for (const auto& link : perLink) {
      if (!link.is_object() || !link.contains("candidate") ||
          !link["candidate"].is_number_integer()) {
        throw InputError(where + ": a per_link entry has no integer candidate");
      }
      ids.push_back(link["candidate"]);
    }
    return ids;
  };
  if (table.contains("classes") && table["classes"].is_object()) {
    for (const auto& [name, part] : table["classes"].items()) {
      links[name] = candidates(part.value("per_link", nlohmann::json()));
    }
  } else {
    links["partial"] = candidates(table.value("per_link", nlohmann::json()));
  }
  return links;
}

bool scoredAgainstGold(const nlohmann::json& rules) {
  return !rules.empty() && rules[0].contains("relative_error_vs_gold");
}

// (metric name, value) of one rule entry: every metric of its figure, against the gold when
// scored so.
std::vector<std::pair<std::string, double>> metricsOf(const nlohmann::json& rule, bool gold,
                                                      const std::string& where) {
  const std::string suffix = gold ? "_vs_gold" : "";
  std::vector<std::pair<std::string, double>> out;
  auto add = [&](const std::string& metric, const char* statistic) {
    const std::string key = metric + suffix;
    if (!rule.contains(key)) return;
    const auto& value = rule[key];
    if (!value.is_object() || !value.contains(statistic) ||
        !(value[statistic].is_number() || value[statistic].is_null())) {
      throw InputError(where + ": " + key + " has no number '" + statistic + "'");
    }
    // A score that was not finite is written as null: it fails every band.
    out.emplace_back(key + "." + statistic, value[statistic].is_null()
                                                ? std::numeric_limits<double>::quiet_NaN()
                                                : value[statistic].get<double>());
  };
  for (const char* statistic : {"mean", "median", "p90"}) add("relative_error", statistic);
  for (const char* statistic : {"mean", "median", "p90"}) add("relative_frobenius_error", statistic);
  for (const char* statistic : {"total", "total_median", "total_p90"}) add("l1_error_bound", statistic);
  if (out.empty()) throw InputError(where + ": a rule entry has no scores");
  return out;
}

std::string ruleName(const nlohmann::json& rule, const std::string& where) {
  if (!rule.is_object() || !rule.contains("name") || !rule["name"].is_string()) {
    throw InputError(where + ": a rule entry has no name");
  }
  return rule["name"].get<std::string>();
}

std::string firstDifference(const nlohmann::json& a, const nlohmann::json& b) {
  for (const auto& [key, value] : a.items()) {
    if (!b.contains(key)) return key + " (only in the baseline)";
    if (b[key] != value) return key + " (baseline " + value.dump() + ", table " + b[key].dump() + ")";
  }
  for (const auto& [key, value] : b.items()) {
    if (!a.contains(key)) return key + " (only in the table)";
  }
  return "";
}

std::string format(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

std::string escapeXml(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

void checkBaselineShape(const nlohmann::json& baseline, const std::string& where) {
  if (!baseline.is_object() || !baseline.contains("schema") ||
      !baseline["schema"].is_number_integer() || baseline["schema"].get<int>() != kSchema ||
      !baseline.contains("suite") || !baseline["suite"].is_object() ||
      !baseline.contains("links") || !baseline["links"].is_object() ||
      !baseline.contains("rules") || !baseline["rules"].is_object() ||
      !baseline.contains("scored_against") || !baseline["scored_against"].is_string()) {
    throw InputError(where + ": not a radquad baseline (schema " + std::to_string(kSchema) +
                     " with suite, links, scored_against and rules)");
  }
}

// What makes `table` another suite than `baseline`'s ("" when it is the same): its options,
// its links, or what it was scored against.
std::string suiteDifference(const nlohmann::json& baseline, const nlohmann::json& table,
                            const std::string& where) {
  const std::string difference = firstDifference(baseline["suite"], suiteOf(table));
  if (!difference.empty()) return difference;
  if (baseline["links"] != linksOf(table, where)) {
    return "the links (a candidate accepted or rejected by a visibility ray that rounds "
           "differently here, or another generator)";
  }
  const auto classes = rulesByClass(table, where);
  const bool gold = scoredAgainstGold(*classes.begin()->second);
  if (baseline["scored_against"] != (gold ? "gold" : "the paper's reference")) {
    return std::string("what it is scored against (the table: ") +
           (gold ? "the gold" : "the paper's reference") + ", the baseline: " +
           baseline["scored_against"].get<std::string>() + ")";
  }
  return "";
}

nlohmann::json makeBaselineUnchecked(const nlohmann::json& table, const std::string& tableName,
                                     const std::vector<std::string>& rules,
                                     const nlohmann::json* existing, const BaselineMargin& margin);
CheckReport checkTableUnchecked(const nlohmann::json& table, const std::string& tableName,
                                const nlohmann::json& baseline, const std::string& baselineName);

}  // namespace

// Malformed JSON of the right syntax (a string where a number belongs) is bad input too.
nlohmann::json makeBaseline(const nlohmann::json& table, const std::string& tableName,
                            const std::vector<std::string>& rules, const nlohmann::json* existing,
                            const BaselineMargin& margin) {
  try {
    return makeBaselineUnchecked(table, tableName, rules, existing, margin);
  } catch (const nlohmann::json::exception& error) {
    throw InputError(tableName + ": " + error.what());
  }
}

CheckReport checkTable(const nlohmann::json& table, const std::string& tableName,
                       const nlohmann::json& baseline, const std::string& baselineName) {
  try {
    return checkTableUnchecked(table, tableName, baseline, baselineName);
  } catch (const nlohmann::json::exception& error) {
    throw InputError(tableName + " or " + baselineName + ": " + error.what());
  }
}

namespace {

nlohmann::json makeBaselineUnchecked(const nlohmann::json& table, const std::string& tableName,
                            const std::vector<std::string>& rules, const nlohmann::json* existing,
                            const BaselineMargin& margin) {
  const auto classes = rulesByClass(table, tableName);
  const bool gold = scoredAgainstGold(*classes.begin()->second);
  nlohmann::json baseline = {
      {"schema", kSchema},
      {"_doc", "Regression bands of a study suite (radquad check; docs/cli.md, "
               "\"Regression bounds\"): per rule, class and metric, [low, high] = value -+ "
               "(relative margin x value + absolute margin)."},
      {"suite", suiteOf(table)},
      {"links", linksOf(table, tableName)},
      {"scored_against", gold ? "gold" : "the paper's reference"},
      {"margin", {{"relative", margin.relative}, {"absolute", margin.absolute}}},
      {"rules", nlohmann::json::object()}};
  if (existing != nullptr) {
    checkBaselineShape(*existing, "the existing baseline");
    const std::string difference = suiteDifference(*existing, table, tableName);
    if (!difference.empty()) {
      throw InputError(tableName + ": a different suite from the existing baseline's: " +
                       difference);
    }
    baseline["rules"] = (*existing)["rules"];
  }
  std::vector<std::string> found;
  for (const auto& [className, list] : classes) {
    for (const auto& rule : *list) {
      const std::string name = ruleName(rule, tableName);
      if (!rules.empty() && std::find(rules.begin(), rules.end(), name) == rules.end()) continue;
      found.push_back(name);
      nlohmann::json bands = nlohmann::json::object();
      for (const auto& [metric, value] : metricsOf(rule, gold, tableName)) {
        if (!std::isfinite(value)) {
          throw InputError(tableName + ": " + name + " (" + className + ") " + metric +
                           " is not finite: no band can be made of it");
        }
        const double half = margin.relative * std::abs(value) + margin.absolute;
        bands[metric] = {{"value", value}, {"low", value - half}, {"high", value + half}};
      }
      baseline["rules"][name][className] = std::move(bands);
    }
  }
  for (const std::string& name : rules) {
    if (std::find(found.begin(), found.end(), name) == found.end()) {
      throw InputError("--rules: '" + name + "' is not in " + tableName);
    }
  }
  return baseline;
}

}  // namespace

bool CheckReport::holds() const {
  if (!missing.empty() || !unbaselined.empty()) return false;
  return std::all_of(checks.begin(), checks.end(), [](const BoundCheck& c) { return c.holds; });
}

std::string CheckReport::summary() const {
  std::ostringstream out;
  std::size_t failed = 0;
  for (const BoundCheck& c : checks) {
    if (c.holds) continue;
    ++failed;
    out << "FAIL " << c.rule << " (" << c.className << ") " << c.metric;
    if (std::isnan(c.value)) {
      out << ": not in the table, or not finite";
    } else {
      out << " = " << format(c.value)
          << (c.value > c.high ? " above its bound " + format(c.high)
                               : " below its bound " + format(c.low));
    }
    out << " (band [" << format(c.low) << ", " << format(c.high) << "])\n";
  }
  for (const std::string& name : missing) out << "FAIL " << name << ": baselined, not in the table\n";
  for (const std::string& name : unbaselined) {
    out << "FAIL " << name << ": in the table, not baselined (radquad baseline --rules " << name
        << ")\n";
  }
  if (holds()) out << "all " << checks.size() << " bounds hold\n";
  else out << failed << " of " << checks.size() << " bounds do not hold\n";
  return out.str();
}

namespace {

// Every band of the baseline is checked: a rule of the baseline absent from the table is
// `missing`; a class or metric of a present rule absent from the table fails its band (a
// score that disappeared is no score that holds).
CheckReport checkTableUnchecked(const nlohmann::json& table, const std::string& tableName,
                                const nlohmann::json& baseline, const std::string& baselineName) {
  checkBaselineShape(baseline, baselineName);
  const auto classes = rulesByClass(table, tableName);
  const std::string difference = suiteDifference(baseline, table, tableName);
  if (!difference.empty()) {
    throw InputError(tableName + ": not the suite of " + baselineName + ": " + difference +
                     "; its scores cannot be compared (re-baseline if the suite is meant)");
  }
  const bool gold = scoredAgainstGold(*classes.begin()->second);
  // The table's scores: rule -> class -> metric -> value.
  std::map<std::string, std::map<std::string, std::map<std::string, double>>> scores;
  CheckReport report;
  for (const auto& [className, list] : classes) {
    for (const auto& rule : *list) {
      const std::string name = ruleName(rule, tableName);
      for (const auto& [metric, value] : metricsOf(rule, gold, tableName)) {
        scores[name][className][metric] = value;
      }
      if (!baseline["rules"].contains(name) &&
          std::find(report.unbaselined.begin(), report.unbaselined.end(), name) ==
              report.unbaselined.end()) {
        report.unbaselined.push_back(name);
      }
    }
  }
  for (const auto& [name, perClass] : baseline["rules"].items()) {
    const auto found = scores.find(name);
    if (found == scores.end()) {
      report.missing.push_back(name);
      continue;
    }
    if (!perClass.is_object()) throw InputError(baselineName + ": " + name + ": not an object");
    for (const auto& [className, bands] : perClass.items()) {
      if (!bands.is_object()) {
        throw InputError(baselineName + ": " + name + " (" + className + "): not an object");
      }
      for (const auto& [metric, band] : bands.items()) {
        if (!band.is_object() || !band.contains("low") || !band["low"].is_number() ||
            !band.contains("high") || !band["high"].is_number()) {
          throw InputError(baselineName + ": " + name + " (" + className + ") " + metric +
                           ": a band needs numbers low and high");
        }
        BoundCheck check{name, className, metric, std::numeric_limits<double>::quiet_NaN(),
                         band["low"].get<double>(), band["high"].get<double>(), false};
        const auto inClass = found->second.find(className);
        if (inClass != found->second.end()) {
          const auto value = inClass->second.find(metric);
          if (value != inClass->second.end()) check.value = value->second;
        }
        check.holds = std::isfinite(check.value) && check.value >= check.low &&
                      check.value <= check.high;
        report.checks.push_back(check);
      }
    }
  }
  return report;
}

}  // namespace

std::string junitXml(const CheckReport& report, const std::string& suiteName) {
  std::size_t failures = report.missing.size() + report.unbaselined.size();
  for (const BoundCheck& c : report.checks) failures += c.holds ? 0 : 1;
  const std::size_t tests = report.checks.size() + report.missing.size() + report.unbaselined.size();
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuite name=\"" << escapeXml(suiteName) << "\" tests=\"" << tests
      << "\" failures=\"" << failures << "\">\n";
  for (const BoundCheck& c : report.checks) {
    out << "  <testcase classname=\"" << escapeXml(c.rule + "." + c.className) << "\" name=\""
        << escapeXml(c.metric) << "\"";
    if (c.holds) {
      out << "/>\n";
    } else {
      out << ">\n    <failure message=\"" << escapeXml(format(c.value) + " outside [" + format(c.low) +
                                                      ", " + format(c.high) + "]")
          << "\"/>\n  </testcase>\n";
    }
  }
  for (const std::string& name : report.missing) {
    out << "  <testcase classname=\"" << escapeXml(name) << "\" name=\"present\">\n"
        << "    <failure message=\"baselined, not in the table\"/>\n  </testcase>\n";
  }
  for (const std::string& name : report.unbaselined) {
    out << "  <testcase classname=\"" << escapeXml(name) << "\" name=\"baselined\">\n"
        << "    <failure message=\"in the table, not baselined\"/>\n  </testcase>\n";
  }
  out << "</testsuite>\n";
  return out.str();
}

}  // namespace radquad
