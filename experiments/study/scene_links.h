// Scene-derived links for the study (docs/study.md): the links a hierarchical solve
// of a scene ends with, as the report's Figure 2 measured them ("the links in a scene that
// used a quadratic multiwavelet basis"), rather than synthetic pairs.
//
// A study config's "links": {"scene": NAME or PATH or [NAME or PATH, ...], "degree": D,
// "bf_eps": E} solves each scene with fixed Gauss rules at basis degree D and BF threshold E
// (other solver options at their defaults), and takes its final active links: receiver and
// source elements as patches, every other patch of that scene as an occluder. Links the solver
// classifies occluded carry nothing and are not scored; every other one, whatever the
// solver's class (a conservative one: its "partial" holds links no occluder touches), is in
// one pool, and the study decides each link's class by the link's own geometry and visibility
// (study_runner.h). The links of several scenes form one pool. Candidate k is the link at
// position k of the pool in a fixed pseudo-random order drawn from the study's seed, so the
// first N candidates of a class are a uniform sample without replacement of the pool's links
// of that class, the same for any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/scenarios/scenario.h"
#include "kernel/link_geometry.h"
#include "radiosity/scene.h"

namespace radquad {

struct SceneLinkOptions {
  std::vector<std::string> scenes;  // built-in names or paths, at least one
  int degree = 2;
  double bfEps = 0.05;
};

SceneLinkOptions parseSceneLinkOptions(const nlohmann::json& value, const std::string& where);
nlohmann::json sceneLinkOptionsToJson(const SceneLinkOptions& options);

struct SceneLinkEntry {
  int scene = 0;  // index in SceneLinkOptions::scenes
  Patch receiver;
  Patch source;
  int receiverPatch = 0;
  int sourcePatch = 0;
  int receiverLevel = 0;
  int sourceLevel = 0;
};

class SceneLinkPool {
 public:
  // Solves every scene; throws InputError for a bad scene, ComputationError when a solve
  // fails.
  SceneLinkPool(const SceneLinkOptions& options, std::uint64_t seed);

  // The pool's links in sampling order.
  std::size_t size() const { return links_.size(); }
  SceneLinkEntry entry(std::size_t k) const;
  // The link with every patch of its scene but its own two as occluders.
  LinkGeometry geometry(const SceneLinkEntry& entry) const;
  std::size_t totalLinks() const { return total_; }
  std::size_t occludedLinks() const { return occluded_; }
  // The solver's classes of the pool's links (for the table; the study reclassifies).
  std::size_t solverUnoccludedLinks() const { return solverUnoccluded_; }
  std::size_t solverPartialLinks() const { return links_.size() - solverUnoccluded_; }
  const std::vector<std::string>& sceneNames() const { return names_; }

 private:
  // A link as its scene and its two elements (the pool holds a solve's million links or
  // more: the elements' geometry is kept once per scene, not once per link).
  struct CompactLink {
    int scene = 0, receiver = 0, source = 0;
  };
  struct ElementRecord {
    Patch geometry;
    int patch = 0, level = 0;
  };
  std::vector<std::string> names_;
  std::vector<Scene> scenes_;
  std::vector<std::vector<ElementRecord>> elements_;  // per scene, by element index
  std::vector<CompactLink> links_;
  std::size_t total_ = 0, occluded_ = 0, solverUnoccluded_ = 0;
};

}  // namespace radquad
