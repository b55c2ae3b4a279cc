// The registry: the paper's rule names and sample counts (docs/design.md, "The kernel and the rules"),
// parametrised forms, and the message for unknown names.
#include <gtest/gtest.h>

#include <set>

#include "kernel/input_error.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

TEST(Registry, PaperGaussRulesHaveTheirSampleCounts) {
  EXPECT_EQ(findRule("FullGauss")->sampleCount(), 81u);
  EXPECT_EQ(findRule("LinSrcGauss")->sampleCount(), 36u);
  EXPECT_EQ(findRule("ConstSrcGauss")->sampleCount(), 9u);
  EXPECT_EQ(findRule("Gauss:2x3x4x5")->sampleCount(), 120u);
  EXPECT_EQ(findRule("Gauss:2x3x4x5")->name(), "Gauss:2x3x4x5");
}

TEST(Registry, ParametrisedFormEqualsNamedRule) {
  const RuleSamples named = findRule("LinSrcGauss")->samples(0);
  const RuleSamples parametrised = findRule("Gauss:3x3x2x2")->samples(0);
  EXPECT_EQ(named.receiver.u, parametrised.receiver.u);
  EXPECT_EQ(named.receiver.weight, parametrised.receiver.weight);
  EXPECT_EQ(named.source.v, parametrised.source.v);
  EXPECT_EQ(named.source.size(), 4u);
}

TEST(Registry, NamedRulesAreUniqueAndFindable) {
  std::set<std::string> seen;
  for (const auto& rule : namedRules()) {
    EXPECT_TRUE(seen.insert(rule->name()).second) << "duplicate " << rule->name();
    EXPECT_EQ(findRule(rule->name())->name(), rule->name());
    EXPECT_FALSE(rule->citation().empty()) << rule->name();
    EXPECT_EQ(rule->samples(7).size(), rule->sampleCount()) << rule->name();
  }
}

TEST(Registry, UnknownNameListsTheValidOnes) {
  try {
    findRule("FulGauss");
    FAIL() << "an unknown rule was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("FulGauss"), std::string::npos) << message;
    for (const auto& rule : namedRules()) {
      EXPECT_NE(message.find(rule->name()), std::string::npos) << message;
    }
    EXPECT_NE(message.find("Gauss:RsxRtxSuxSv"), std::string::npos) << message;
  }
}

TEST(Registry, MalformedParametersAreInputErrors) {
  for (const char* bad : {"Gauss:3x3", "Gauss:3x3x3x", "Gauss:0x1x1x1", "Gauss:3x3x3x3x3",
                          "Gauss:axbxcxd", "Gauss:65x1x1x1", "Gauss:"}) {
    EXPECT_THROW(findRule(bad), InputError) << bad;
  }
}

}  // namespace
}  // namespace radquad
