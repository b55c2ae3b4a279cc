// The compiled half of the Python module `radquad` (python/radquad/__init__.py is the other):
// the command line's own computations (experiments/link_reports.h, the study runner, the rule
// loader), taking and returning JSON text, so that Python gets the command line's numbers bit
// for bit (doubles are written with 17 significant digits and read back exactly). InputError
// becomes ValueError with the command line's message; ComputationError, ArithmeticError.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <vector>

#include "experiments/json_input.h"
#include "experiments/link_reports.h"
#include "experiments/rule_file.h"
#include "experiments/study/study_output.h"
#include "kernel/input_error.h"
#include "reference/gold_reference.h"

namespace py = pybind11;

namespace radquad {
namespace {

// A rule given as a name (registry or File:PATH) or as rule-file JSON text ("{...}").
std::shared_ptr<const Rule> ruleFrom(const std::string& rule) {
  if (!rule.empty() && rule.front() == '{') return parseRuleJson(parseJsonText(rule, "rule"), "rule");
  return findAnyRule(rule);
}

std::string rulesJson() { return registeredRulesJson().dump(); }

std::string checkRule(const std::string& ruleJson) {
  const auto rule = ruleFrom(ruleJson);
  return ruleToJson(*rule, 0).dump();
}

std::string integrate(const std::string& linkJson, const std::string& rule, int degree,
                      std::uint64_t seed, int trials) {
  if (trials < 1 || trials > 100000) throw InputError("trials must lie in 1..100000");
  const LinkGeometry description = parseLink(parseJsonText(linkJson, "link"), "link");
  LinkReportOptions options;
  options.degree = degree;
  options.seed = seed;
  options.trials = trials;
  return linkReport(description, ruleFrom(rule), options, "link", nullptr).dump();
}

std::string reference(const std::string& linkJson, int degree, std::uint64_t seed,
                      int replicates, bool gold, const std::string& goldMethod,
                      double goldTolerance) {
  if (replicates < 2 || replicates > 100000) throw InputError("replicates must lie in 2..100000");
  if (!(goldTolerance >= 1e-15 && goldTolerance <= 0.5)) {
    throw InputError("gold_tolerance must lie in [1e-15, 0.5]");
  }
  const LinkGeometry description = parseLink(parseJsonText(linkJson, "link"), "link");
  ReferenceReportOptions options;
  options.degree = degree;
  options.seed = seed;
  options.replicates = replicates;
  options.gold = gold;
  options.goldOptions.method = parseGoldMethod(goldMethod, "gold_method");
  options.goldOptions.exactTolerance = goldTolerance;
  return referenceReport(description, options, "link").dump();
}

std::string study(const std::string& configJson, const std::vector<std::string>& rules,
                  bool overrideSeed, std::uint64_t seed, bool gold) {
  StudyConfig config = parseStudyConfig(parseJsonText(configJson, "config"), "config");
  if (!rules.empty()) {
    for (const std::string& name : rules) findAnyRule(name);  // InputError naming it
    config.rules = rules;
  }
  if (overrideSeed) config.seed = seed;
  StudyOptions options;
  options.gold = gold;
  options.progress = false;
  py::gil_scoped_release release;
  return runStudyTable(config, options).dump();
}

}  // namespace
}  // namespace radquad

PYBIND11_MODULE(_radquad, module) {
  module.doc() = "radquad's computations, JSON in and out (use the radquad package)";
  py::register_exception<radquad::InputError>(module, "InputError", PyExc_ValueError);
  py::register_exception<radquad::ComputationError>(module, "ComputationError",
                                                    PyExc_ArithmeticError);
  module.def("rules_json", &radquad::rulesJson);
  module.def("check_rule", &radquad::checkRule, py::arg("rule_json"));
  module.def("integrate", &radquad::integrate, py::arg("link_json"), py::arg("rule"),
             py::arg("degree"), py::arg("seed"), py::arg("trials"),
             py::call_guard<py::gil_scoped_release>());
  module.def("reference", &radquad::reference, py::arg("link_json"), py::arg("degree"),
             py::arg("seed"), py::arg("replicates"), py::arg("gold"), py::arg("gold_method"),
             py::arg("gold_tolerance"), py::call_guard<py::gil_scoped_release>());
  module.def("study", &radquad::study, py::arg("config_json"), py::arg("rules"),
             py::arg("override_seed"), py::arg("seed"), py::arg("gold"));
}
