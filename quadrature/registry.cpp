#include "quadrature/registry.h"

#include <functional>

#include "kernel/input_error.h"
#include "quadrature/rules/gauss_product.h"
#include "quadrature/rules/monte_carlo.h"
#include "quadrature/rules/n_rook.h"
#include "quadrature/rules/stratified.h"
#include "quadrature/rules/stroud.h"

namespace radquad {
namespace {

struct NamedRule {
  const char* name;
  std::function<std::shared_ptr<const Rule>()> make;
};

struct ParametrisedFamily {
  const char* prefix;  // the text before the colon
  const char* form;    // how users write it
  std::function<std::shared_ptr<const Rule>(const std::string&)> make;
};

// The catalogue of docs/design.md, "The kernel and the rules".
const std::vector<NamedRule>& namedCatalogue() {
  static const std::vector<NamedRule> catalogue = {
      {"FullGauss",
       [] {
         return std::make_shared<GaussProductRule>(GaussPointCounts{3, 3, 3, 3}, "FullGauss");
       }},
      {"LinSrcGauss",
       [] {
         return std::make_shared<GaussProductRule>(GaussPointCounts{3, 3, 2, 2}, "LinSrcGauss");
       }},
      {"ConstSrcGauss",
       [] {
         return std::make_shared<GaussProductRule>(GaussPointCounts{3, 3, 1, 1}, "ConstSrcGauss");
       }},
      {"Stroud65", [] { return StroudRule::cn57(); }},
      {"HierStroud", [] { return StroudRule::hierarchicalCn31(); }},
      {"MonteCarlo", [] { return std::make_shared<MonteCarloRule>(81, "MonteCarlo"); }},
      {"NRook", [] { return std::make_shared<NRookRule>(81, "NRook"); }},
      {"Stratified", [] { return std::make_shared<StratifiedRule>(3, "Stratified"); }},
      {"Reference", [] { return std::make_shared<StratifiedRule>(10, "Reference"); }},
  };
  return catalogue;
}

const std::vector<ParametrisedFamily>& parametrisedCatalogue() {
  static const std::vector<ParametrisedFamily> catalogue = {
      {"Gauss", "Gauss:RsxRtxSuxSv", makeGaussProductRule},
      {"MonteCarlo", "MonteCarlo:n", makeMonteCarloRule},
      {"NRook", "NRook:n", makeNRookRule},
      {"Stratified", "Stratified:k", makeStratifiedRule},
  };
  return catalogue;
}

std::string validNames() {
  std::string text;
  for (const auto& rule : namedCatalogue())
    text += std::string(text.empty() ? "" : ", ") + rule.name;
  for (const auto& family : parametrisedCatalogue()) text += std::string(", ") + family.form;
  return text;
}

}  // namespace

std::shared_ptr<const Rule> findRule(std::string_view name) {
  for (const auto& rule : namedCatalogue()) {
    if (name == rule.name) return rule.make();
  }
  const auto colon = name.find(':');
  if (colon != std::string_view::npos) {
    const std::string_view prefix = name.substr(0, colon);
    for (const auto& family : parametrisedCatalogue()) {
      if (prefix == family.prefix) return family.make(std::string(name.substr(colon + 1)));
    }
  }
  throw InputError("unknown rule '" + std::string(name) + "'; valid rules: " + validNames());
}

std::vector<std::shared_ptr<const Rule>> namedRules() {
  std::vector<std::shared_ptr<const Rule>> rules;
  for (const auto& rule : namedCatalogue()) rules.push_back(rule.make());
  return rules;
}

std::vector<std::string> parametrisedRuleForms() {
  std::vector<std::string> forms;
  for (const auto& family : parametrisedCatalogue()) forms.push_back(family.form);
  return forms;
}

}  // namespace radquad
