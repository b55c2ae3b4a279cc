// Regression bounds on study tables: `radquad baseline` and `radquad check` (docs/cli.md,
// "Regression bounds"), for the project's own CI and for anyone's rule or table.
//
// A baseline records, for one suite (the table's options but for its rule list and the
// config's path, and the candidates it scored), a band [low, high] around every scored value of every rule: per class
// (Figure 1's links are one class, "partial") and metric (each metric's mean, median and p90,
// and Figure 2's summed L1 bound), against the gold when the table was scored against it,
// otherwise against the paper's reference. A table of the same suite is checked against the
// bands: every value must lie inside its band.
//
// Why a band this narrow is right: the study is deterministic. Links, reference draws and
// random rules' trials all derive from the config's seed, and the tables are the same bits
// whatever the thread count; what can move a value on another machine is rounding (a
// visibility ray grazing an edge, a last bit in a sum), far below the 2% margin. A rule whose
// weights are biased by 5%, or one of whose points is moved, moves its scores by far more
// (docs/cli.md, "Regression bounds", gives the measurements), and so does any change of the
// rule's code: the band is two-sided, so an unexpected improvement is reported too
// (re-baseline the rule with `radquad baseline --rules NAME` once it is understood).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace radquad {

struct BaselineMargin {
  double relative = 0.02;   // of the baseline value, either side
  // Added, so that values near 0 (a Gauss rule exact to rounding on smooth links, an error
  // of 1e-8 against an adaptive gold) have a band wider than what another CPU's rounding or
  // one more subdivision of the gold can move; a faulty rule moves them by 1e-5 and more.
  double absolute = 1e-6;
};

// A baseline of `table` (a study table as `radquad study` writes it, named `tableName` in
// messages). With `rules` empty, every rule of the table; otherwise only these, which must be
// in the table, and the other rules' bands are kept from `existing` (which must describe the
// same suite), when given. Throws InputError on a table that is not a study table.
nlohmann::json makeBaseline(const nlohmann::json& table, const std::string& tableName,
                            const std::vector<std::string>& rules, const nlohmann::json* existing,
                            const BaselineMargin& margin = {});

struct BoundCheck {
  std::string rule, className, metric;
  double value = 0.0, low = 0.0, high = 0.0;
  bool holds = false;
};

struct CheckReport {
  std::vector<BoundCheck> checks;
  std::vector<std::string> missing;      // baselined rules the table does not have
  std::vector<std::string> unbaselined;  // rules of the table the baseline does not have
  bool holds() const;
  // One line per failure (rule, class, metric, value and band) and per missing or unbaselined
  // rule; "all N bounds hold" when there is none.
  std::string summary() const;
};

// Throws InputError when the baseline is malformed or describes another suite (the message
// names the first option that differs, or says that the links differ).
CheckReport checkTable(const nlohmann::json& table, const std::string& tableName,
                       const nlohmann::json& baseline, const std::string& baselineName);

// JUnit XML: one test case per rule, class and metric (and per missing or unbaselined rule),
// with a failure element where the bound does not hold.
std::string junitXml(const CheckReport& report, const std::string& suiteName);

}  // namespace radquad
