// Rules from data files: `File:PATH` wherever a rule name is accepted (`radquad link --rule`,
// study configs' "rules"), and `radquad rules --dump NAME` writes any rule in the same format.
//
// The file is JSON, either a list of 4D points
//   {"name": N, "degree": D or null, "citation": C,
//    "points": [[s, t, u, v], ...], "weights": [w, ...]}
// or a product of a receiver and a source point set (integrated as a product)
//   {"name": N, "degree": D or null, "citation": C,
//    "receiver": {"points": [[u, v], ...], "weights": [...]},
//    "source":   {"points": [[u, v], ...], "weights": [...]}}
// with (s, t, u, v) = (receiver u, receiver v, source u, source v) on [0, 1]^4. "degree" and
// "citation" may be left out. A random rule is a list of draws, trial t using draw t:
//   {"name": N, "citation": C, "draws": [{"points": ..., "weights": ...}, ...]}
// (or draws of {"receiver", "source"}), every draw of the same form and size, no degree. A file whose name ends in .npz is NumPy's archive
// (experiments/npz_input.h; numpy.savez or savez_compressed) with the same content as arrays:
// points (N, 4) and weights (N,), or receiver_points (N, 2), receiver_weights, source_points,
// source_weights; optional name and citation (strings; the name defaults to the file's
// stem) and degree (an integer). Draws of a random rule stack on a first axis: points
// (T, N, 4) and weights (T, N), or receiver_points (T, N, 2) and so on. Loading checks what quadrature/rules/data_rule.h lists (values
// finite and in [0, 1], weights summing to 1, the declared degree) and names the file and the
// failed check (InputError, exit status 2). A rule of one point set is deterministic: the same
// points for every seed.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "quadrature/rule.h"

namespace radquad {

// Reads a rule file (above).
std::shared_ptr<const Rule> loadRuleFile(const std::filesystem::path& path);
std::shared_ptr<const Rule> parseRuleJson(const nlohmann::json& value, const std::string& where);

// `File:PATH` loads the file; any other name goes to the registry (quadrature/registry.h).
std::shared_ptr<const Rule> findAnyRule(std::string_view name);

// At most this many kernel evaluations per link for one rule over all its trials (a random
// rule's samples times the trials; 1e10 is minutes of one core).
inline constexpr double kMaxSamplesPerLink = 1e10;

// InputError naming `where`, the rule's samples and the trials when samples x trials exceeds
// kMaxSamplesPerLink.
void checkSampleBudget(const Rule& rule, int trials, const std::string& where);

// The registered rules as `radquad rules --json` lists them: {name, samples, degree (null for
// random rules), family, citation}.
nlohmann::json registeredRulesJson();

// A rule in the file format; a product rule stays a product. A random rule's draw for `seed`,
// or with `draws` > 0 its draws for seeds seed, seed + 1, ... (the seeds of `radquad link
// --seed S --trials T`, so the file's trials reproduce the rule's); a rule of listed draws
// whole.
nlohmann::json ruleToJson(const Rule& rule, std::uint64_t seed, int draws = 0);

}  // namespace radquad
