// Rules from data (quadrature/rules/data_rule.h, experiments/rule_file.h): every registered
// rule written in the file format and read back integrates a link to the same coupling (bit
// for bit for the deterministic ones: their points survive the round trip exactly); the checks at loading reject points
// outside [0, 1], weights that do not sum to 1 and an overstated degree, naming the file; the
// midpoint rule is accepted as exact to degree 1 and refused at degree 2 (its closed form).
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/npz_input.h"
#include "experiments/rule_file.h"
#include "kernel/input_error.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

Link testLink() {
  static const Patch receiver = Patch::make(Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), "r");
  static const Patch source = Patch::make(Vec(0.2, 1.1, 1.3), Vec(0.9, 0, 0.1), Vec(0, -1.2, 0.2), "s");
  return Link{receiver, source, nullptr};
}

TEST(RuleFile, EveryRegisteredRuleSurvivesTheRoundTrip) {
  for (const auto& rule : namedRules()) {
    const nlohmann::json written = ruleToJson(*rule, 7);
    const auto read = parseRuleJson(nlohmann::json::parse(written.dump()), rule->name());
    EXPECT_EQ(read->name(), rule->name());
    EXPECT_EQ(read->sampleCount(), rule->sampleCount());
    EXPECT_EQ(read->samples(0).isProduct, rule->samples(7).isProduct);
    // A random rule's draw becomes a fixed rule: no degree.
    EXPECT_EQ(read->degree(), rule->isRandom() ? std::nullopt : rule->degree());
    for (int degree : {0, 2}) {
      const LinkIntegral original = PreparedRule(rule, degree).integrate(testLink(), 7);
      const LinkIntegral again = PreparedRule(read, degree).integrate(testLink(), 0);
      // The same points and weights; random rules of equal weights integrate through their
      // point stream, in another summation order than a list of points: equal to rounding.
      EXPECT_LE((again.coupling - original.coupling).cwiseAbs().maxCoeff(),
                1e-14 * original.coupling.cwiseAbs().maxCoeff())
          << rule->name() << " degree " << degree;
      if (!rule->isRandom()) {
        EXPECT_EQ(again.coupling, original.coupling) << rule->name();
      }
    }
  }
}

nlohmann::json midpoint(int degree) {
  return {{"name", "Midpoint"}, {"degree", degree}, {"points", {{0.5, 0.5, 0.5, 0.5}}},
          {"weights", {1.0}}};
}

TEST(RuleFile, TheMidpointRuleIsExactToDegreeOneAndNoMore) {
  EXPECT_EQ(parseRuleJson(midpoint(1), "midpoint")->degree(), 1);
  try {
    parseRuleJson(midpoint(2), "midpoint.json");
    FAIL() << "an overstated degree was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("midpoint.json: the rule is declared exact to degree 2"),
              std::string::npos)
        << error.what();
  }
}

TEST(RuleFile, BadPointsAndWeightsAreRefusedNamingTheFile) {
  const auto refused = [](nlohmann::json value, const char* fragment) {
    try {
      parseRuleJson(value, "bad.json");
      ADD_FAILURE() << "accepted: " << value.dump();
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("bad.json"), std::string::npos) << message;
      EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  };
  nlohmann::json outside = midpoint(0);
  outside["points"] = {{0.5, 1.5, 0.5, 0.5}};
  refused(outside, "is not in [0, 1]");
  nlohmann::json heavy = midpoint(0);
  heavy["weights"] = {0.9};
  refused(heavy, "weights sum to");
  nlohmann::json mismatched = midpoint(0);
  mismatched["weights"] = {0.5, 0.5};
  refused(mismatched, "1 points but 2 weights");
  nlohmann::json both = midpoint(0);
  both["receiver"] = {{"points", {{0.5, 0.5}}}, {"weights", {1.0}}};
  refused(both, "either points and weights, or receiver and source");
  refused({{"name", "P"}, {"receiver", {{"points", {{0.5, 0.5}}}, {"weights", {1.0}}}}},
          "needs both receiver and source");
  nlohmann::json short_point = midpoint(0);
  short_point["points"] = {{0.5, 0.5, 0.5}};
  refused(short_point, "expected 4 coordinates");
}


// A .npy member in NumPy's format 1.0: magic, version, header length, header, data.
std::string npy(const std::string& header, const std::string& data) {
  std::string padded = header;
  while ((10 + padded.size() + 1) % 16 != 0) padded += ' ';
  padded += '\n';
  std::string out = "\x93NUMPY";
  out += char(1);
  out += char(0);
  out += char(padded.size() & 0xff);
  out += char(padded.size() >> 8);
  return out + padded + data;
}

TEST(NpyArrays, LittleEndianNumbersInCAndFortranOrder) {
  std::string data;
  for (double value : {1.0, 2.0, 3.0, 4.0, 5.0, 6.0}) {
    data.append(reinterpret_cast<const char*>(&value), 8);
  }
  // The same six numbers as a 2 x 3 array in C order, and as its Fortran-order reading.
  const NpyArray c = parseNpy(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", data), "c");
  ASSERT_EQ(c.shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(c.numbers, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  const NpyArray f = parseNpy(npy("{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }", data), "f");
  EXPECT_EQ(f.numbers, (std::vector<double>{1, 3, 5, 2, 4, 6}));
  const std::int16_t small[3] = {-2, 0, 7};
  const NpyArray i = parseNpy(npy("{'descr': '<i2', 'fortran_order': False, 'shape': (3,), }",
                                  std::string(reinterpret_cast<const char*>(small), 6)), "i");
  EXPECT_EQ(i.numbers, (std::vector<double>{-2, 0, 7}));
}

TEST(NpyArrays, BadMembersAreRefusedNamingThem) {
  const std::string eight(8, '\0');
  const auto refused = [](const std::string& bytes, const std::string& fragment) {
    try {
      parseNpy(bytes, "rule.npz: points");
      ADD_FAILURE() << "accepted; expected " << fragment;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("rule.npz: points"), std::string::npos);
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    }
  };
  refused("not numpy at all", "magic");
  refused(npy("{'descr': '>f8', 'fortran_order': False, 'shape': (1,), }", eight), "big-endian");
  refused(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2,), }", eight), "truncated");
  refused(npy("{'descr': '|O', 'fortran_order': False, 'shape': (1,), }", eight), "dtype");
  refused(npy("{'descr': '<f8', 'shape': (1,), }", eight), "fortran_order");
}

// A random rule's draws for seeds S..S+T-1, written as a rule of listed draws and read back:
// trial t integrates exactly what the built-in rule gives for seed S + t (product and
// scattered rules; Stratified streams its points, so equal to rounding there).
TEST(RuleFile, ListedDrawsReproduceTheRandomRulesTrials) {
  for (const std::string name : {"MonteCarlo:40", "NRook:30", "Stratified:2"}) {
    const auto rule = findRule(name);
    const nlohmann::json written = ruleToJson(*rule, 1000, 3);
    ASSERT_TRUE(written.contains("draws")) << name;
    const auto read = parseRuleJson(nlohmann::json::parse(written.dump()), name);
    EXPECT_TRUE(read->isRandom());
    EXPECT_EQ(read->drawCount(), 3u);
    EXPECT_EQ(read->degree(), std::nullopt);
    const PreparedRule original(rule, 2), listed(read, 2);
    for (std::size_t t = 0; t < 3; ++t) {
      const LinkIntegral a = original.integrate(testLink(), 1000 + t);
      const LinkIntegral b = listed.integrate(testLink(), 12345, t);  // the seed plays no part
      EXPECT_LE((a.coupling - b.coupling).cwiseAbs().maxCoeff(),
                1e-14 * a.coupling.cwiseAbs().maxCoeff())
          << name << " trial " << t;
      if (name != std::string("Stratified:2")) {
        EXPECT_EQ(a.coupling, b.coupling) << name;
      }
    }
    EXPECT_THROW(listed.integrate(testLink(), 0, 3), InputError);
    EXPECT_THROW(checkDrawCount(*read, 4, "trials"), InputError);
    EXPECT_NO_THROW(checkDrawCount(*read, 3, "trials"));
    // Written again, the listed rule is the same file.
    EXPECT_EQ(ruleToJson(*read, 0).dump(), written.dump()) << name;
  }
}

TEST(RuleFile, ListedDrawsAreCheckedDrawByDraw) {
  const nlohmann::json one = {{"points", {{0.5, 0.5, 0.5, 0.5}}}, {"weights", {1.0}}};
  const nlohmann::json two = {{"points", {{0.25, 0.5, 0.5, 0.5}, {0.75, 0.5, 0.5, 0.5}}},
                              {"weights", {0.5, 0.5}}};
  const nlohmann::json outside = {{"points", {{0.5, 1.5, 0.5, 0.5}}}, {"weights", {1.0}}};
  auto message = [](const nlohmann::json& rule) {
    try {
      parseRuleJson(rule, "draws.json");
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({{"name", "D"}, {"draws", {one, two}}}).find("draws[1]"), std::string::npos);
  EXPECT_NE(message({{"name", "D"}, {"draws", {one, outside}}}).find("draws[1]"),
            std::string::npos);
  EXPECT_NE(message({{"name", "D"}, {"draws", nlohmann::json::array()}}).find("non-empty"),
            std::string::npos);
  EXPECT_NE(message({{"name", "D"}, {"degree", 1}, {"draws", {one}}}).find("declares no degree"),
            std::string::npos);
  nlohmann::json both = one;
  both["name"] = "D";
  both["draws"] = {one};
  EXPECT_NE(message(both).find("not both"), std::string::npos);
  EXPECT_EQ(message({{"name", "D"}, {"draws", {one, one}}}), "accepted");
}

}  // namespace
}  // namespace radquad
