#include "experiments/study/scene_links.h"

#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <iterator>
#include <utility>

#include "experiments/json_input.h"
#include "experiments/scenarios/random_stream.h"
#include "experiments/scene_input.h"
#include "kernel/input_error.h"
#include "radiosity/hierarchy.h"
#include "radiosity/solver.h"

namespace radquad {

SceneLinkOptions parseSceneLinkOptions(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where, {"scene", "degree", "bf_eps"}, {"scene"});
  SceneLinkOptions options;
  const auto& scene = value["scene"];
  const auto addScene = [&](const nlohmann::json& name) {
    if (!name.is_string() || name.get<std::string>().empty()) {
      throw InputError(where + ": scene must be a built-in scene name or a path, or a list of them");
    }
    options.scenes.push_back(name.get<std::string>());
  };
  if (scene.is_array()) {
    if (scene.empty()) throw InputError(where + ": scene: the list is empty");
    for (const auto& name : scene) addScene(name);
  } else {
    addScene(scene);
  }
  if (value.contains("degree")) {
    const auto& degree = value["degree"];
    if (!degree.is_number_integer() || degree.get<long long>() < 0 || degree.get<long long>() > 3) {
      throw InputError(where + ": degree must be an integer in [0, 3]");
    }
    options.degree = degree.get<int>();
  }
  if (value.contains("bf_eps")) {
    options.bfEps = finiteNumber(value["bf_eps"], where + ": bf_eps");
    if (!(options.bfEps > 0.0)) throw InputError(where + ": bf_eps must be positive");
  }
  return options;
}

nlohmann::json sceneLinkOptionsToJson(const SceneLinkOptions& options) {
  const nlohmann::json scene =
      options.scenes.size() == 1 ? nlohmann::json(options.scenes.front()) : nlohmann::json(options.scenes);
  return {{"scene", scene}, {"degree", options.degree}, {"bf_eps", options.bfEps}};
}

SceneLinkPool::SceneLinkPool(const SceneLinkOptions& options, std::uint64_t seed)
    : names_(options.scenes) {
  for (const std::string& name : options.scenes) scenes_.push_back(loadScene(name));
  // The scenes are solved side by side (a solve keeps about 1.3 cores busy); each one's links
  // are then appended in scene order, so the pool does not depend on which finished first.
  struct Solved {
    std::vector<ElementRecord> elements;
    std::vector<CompactLink> unoccluded, partial;
    std::size_t total = 0, occluded = 0;
  };
  std::vector<Solved> solved(scenes_.size());
  tbb::parallel_for(std::size_t(0), scenes_.size(), [&](std::size_t index) {
    SolverOptions solverOptions;
    solverOptions.degree = options.degree;
    solverOptions.bfEpsilon = options.bfEps;
    solverOptions.rules = RuleChoice::kFixed;
    Solver solver(scenes_[index], solverOptions);
    solver.solve();
    Solved& out = solved[index];
    const Hierarchy& hierarchy = solver.hierarchy();
    out.elements.reserve(hierarchy.size());
    for (std::size_t e = 0; e < hierarchy.size(); ++e) {
      const Element& element = hierarchy[int(e)];
      out.elements.push_back(ElementRecord{element.geometry, element.patch, element.level});
    }
    for (const SolverLink& link : solver.links()) {
      if (link.split) continue;  // replaced by its children
      if (link.visibility == LinkClass::kOccluded) {  // inactive: carries nothing
        ++out.total;
        ++out.occluded;
        continue;
      }
      if (!link.active) continue;
      ++out.total;
      (link.visibility == LinkClass::kPartial ? out.partial : out.unoccluded)
          .push_back(CompactLink{int(index), link.receiver, link.source});
    }
  }, tbb::simple_partitioner());
  for (Solved& scene : solved) {
    total_ += scene.total;
    occluded_ += scene.occluded;
    solverUnoccluded_ += scene.unoccluded.size();
    elements_.push_back(std::move(scene.elements));
    links_.insert(links_.end(), scene.unoccluded.begin(), scene.unoccluded.end());
    links_.insert(links_.end(), scene.partial.begin(), scene.partial.end());
  }
  // A seeded Fisher-Yates shuffle: candidate k is the k-th of a uniform sample.
  ScenarioRandom random(deriveSeed(seed, {7}));
  for (std::size_t k = links_.size(); k > 1; --k) {
    std::swap(links_[k - 1], links_[std::size_t(random.index(k))]);
  }
}

SceneLinkEntry SceneLinkPool::entry(std::size_t k) const {
  const CompactLink& link = links_.at(k);
  const std::vector<ElementRecord>& elements = elements_[std::size_t(link.scene)];
  const ElementRecord& receiver = elements[std::size_t(link.receiver)];
  const ElementRecord& source = elements[std::size_t(link.source)];
  return SceneLinkEntry{link.scene,     receiver.geometry, source.geometry, receiver.patch,
                        source.patch,   receiver.level,    source.level};
}

LinkGeometry SceneLinkPool::geometry(const SceneLinkEntry& entry) const {
  LinkGeometry geometry;
  geometry.receiver = entry.receiver;
  geometry.source = entry.source;
  const Scene& own = scenes_.at(std::size_t(entry.scene));
  for (std::size_t p = 0; p < own.patches.size(); ++p) {
    if (int(p) == entry.receiverPatch || int(p) == entry.sourcePatch) continue;
    geometry.parallelograms.push_back(own.patches[p].patch);
  }
  return geometry;
}

}  // namespace radquad
