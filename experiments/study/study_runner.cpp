#include "experiments/rule_file.h"
#include "experiments/study/study_runner.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "experiments/scenarios/random_stream.h"
#include "experiments/study/reference_estimate.h"
#include "experiments/study/scene_links.h"
#include "experiments/study/study_metrics.h"
#include "kernel/input_error.h"
#include "kernel/patch_intersection.h"
#include "quadrature/estimate.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"
#include "reference/exact_visibility.h"
#include "reference/gold_reference.h"

namespace radquad {
namespace {

struct Scorers {
  std::vector<PreparedRule> rules;
  std::vector<int> trials;
  ReferenceEstimator reference;
  bool gold = false;
  const SceneLinkPool* pool = nullptr;  // scene-derived links, or null: generated ones
  bool keepDetails = false;
};

// One candidate's geometry: generated from its seed, or taken from the scene's links.
struct CandidateGeometry {
  BuiltLink built;  // the link and its occluder scene
  Orientation orientation = Orientation::parallel;
  OccluderKind occluderKind = OccluderKind::none;
  std::string sceneName;  // scene-derived: the link's scene
};

double distanceFactorOf(const Patch& receiver, const Patch& source) {
  const double largest = std::max({receiver.edgeU.norm(), receiver.edgeV.norm(),
                                   source.edgeU.norm(), source.edgeV.norm()});
  return (receiver.centre() - source.centre()).norm() / largest;
}

Orientation orientationOf(const Patch& receiver, const Patch& source) {
  const double cosine = std::fabs(receiver.normal.dot(source.normal));
  if (cosine > 1.0 - 1e-9) return Orientation::parallel;
  if (cosine < 1e-9) return Orientation::perpendicular;
  return Orientation::tilted;
}

CandidateGeometry candidateGeometry(const StudyConfig& config, const Scorers& scorers,
                                    std::size_t classIndex, StudyClass linkClass,
                                    std::uint64_t index) {
  if (scorers.pool != nullptr) {
    const SceneLinkEntry entry = scorers.pool->entry(std::size_t(index));
    return {scorers.pool->geometry(entry).build(), orientationOf(entry.receiver, entry.source),
            OccluderKind::scene, scorers.pool->sceneNames().at(std::size_t(entry.scene))};
  }
  const GeneratedLink generated =
      generateLink(config.geometry, linkClass, deriveSeed(config.seed, {classIndex, index, 0}));
  return {generated.build(), generated.orientation, generated.occluderKind, {}};
}

struct Candidate {
  bool accepted = false;
  bool mostlyBlocked = false;
  bool occluderCrossesPatch = false;
  bool goldRefused = false;  // scene-derived: its gold did not converge (scoreLink)
  const char* ownClass = nullptr;  // scene-derived: sceneLinkClass
  std::uint64_t rays = 0;
  LinkIntegral draw;  // the reference's reported draw, kept for the scoring pass
  LinkRecord record;
};

void addInto(std::vector<double>& sum, const std::vector<double>& values, double scale) {
  sum.resize(values.size(), 0.0);
  for (std::size_t k = 0; k < values.size(); ++k) sum[k] += scale * values[k];
}

// sceneLinkClass in two steps: by geometry alone ("singular", "unoccluded", or null when an
// occluder meets the shaft), then an occluded link by its visible fraction.
const char* geometricClass(const Link& link) {
  if (singularLink(link)) return "singular";
  if (ExactVisibility(link).occludersInShaft() == 0) return "unoccluded";
  return nullptr;
}

const char* occludedClass(double visibleFraction, const StudyConfig& config) {
  if (visibleFraction <= config.minVisibleFraction) return "mostly_blocked";
  if (visibleFraction >= config.maxVisibleFraction) return "mostly_visible";
  return "partial";
}

// First pass over a candidate: its geometry and the reference's reported draw, whose rays
// decide whether a partial candidate qualifies (one draw; the replicates wait for the links
// that are kept).
void classifyCandidate(const StudyConfig& config, const Scorers& scorers, std::size_t classIndex,
                       StudyClass linkClass, std::uint64_t index, CouplingAccumulator& accumulator,
                       Candidate& out) {
  const CandidateGeometry generated =
      candidateGeometry(config, scorers, classIndex, linkClass, index);
  const Link& link = generated.built.link;
  // A generated occluder that passes through the receiver or the source is no physical
  // configuration (and its kernel is singular along the cut): such candidates are rejected
  // before anything is computed.
  if (scorers.pool == nullptr && generated.built.scene != nullptr) {
    for (const auto& polygon : generated.built.scene->polygons()) {
      if (polygonCrossesPatch(polygon, link.receiver) ||
          polygonCrossesPatch(polygon, link.source)) {
        out.record.candidate = index;
        out.occluderCrossesPatch = true;
        out.accepted = false;
        return;
      }
    }
  }
  // Scene-derived: singular and unoccluded links are known from their geometry; a candidate of
  // another class is counted without drawing its rays.
  const char* geometric = scorers.pool != nullptr ? geometricClass(link) : nullptr;
  if (geometric != nullptr && std::string(geometric) != studyClassName(linkClass)) {
    out.record.candidate = index;
    out.ownClass = geometric;
    out.accepted = false;
    return;
  }
  scorers.reference.draw(link, deriveSeed(config.seed, {classIndex, index, 1}), accumulator,
                         out.draw);
  out.rays = out.draw.raysCast;
  LinkRecord& record = out.record;
  record.candidate = index;
  record.orientation = generated.orientation;
  record.occluderKind = generated.occluderKind;
  record.scene = generated.sceneName;
  record.distanceFactor = distanceFactorOf(link.receiver, link.source);
  record.visibleFraction = out.draw.visibleFraction();
  out.accepted = true;
  if (scorers.pool != nullptr) {
    out.ownClass = geometric != nullptr ? geometric : occludedClass(record.visibleFraction, config);
    out.accepted = std::string(out.ownClass) == studyClassName(linkClass);
  } else if (linkClass == StudyClass::partial) {
    out.mostlyBlocked = record.visibleFraction <= config.minVisibleFraction;
    out.accepted = !out.mostlyBlocked && record.visibleFraction < config.maxVisibleFraction;
  }
}

// Second pass over a kept link: the reference's standard error, the gold, and every rule.
void scoreLink(const StudyConfig& config, const Scorers& scorers, std::size_t classIndex,
               StudyClass linkClass, CouplingAccumulator& accumulator, Candidate& candidate) {
  const std::uint64_t index = candidate.record.candidate;
  const CandidateGeometry generated =
      candidateGeometry(config, scorers, classIndex, linkClass, index);
  const Link& link = generated.built.link;
  const std::uint64_t referenceSeed = deriveSeed(config.seed, {classIndex, index, 1});
  LinkRecord& record = candidate.record;
  const ReferenceResult reference =
      scorers.reference.estimate(link, referenceSeed, candidate.draw, accumulator);
  const Eigen::MatrixXd& K = reference.integral.coupling;
  const double area = link.receiver.area;
  record.referenceRelativeStandardError = reference.standardError(0, 0) / K(0, 0);
  record.referenceL1StandardError = l1ErrorBound(reference.standardError, area);
  GoldReference gold;
  if (scorers.gold) {
    gold = goldReference(link, config.degree(), deriveSeed(config.seed, {classIndex, index, 2}),
                         config.gold);
    const Eigen::MatrixXd& G = gold.coupling;
    record.goldMethod = gold.method;
    record.goldOuterMethod = gold.outerMethod;
    record.goldRelativeError = gold.couplingError(0, 0) / G(0, 0);
    record.goldMaxRelativeError = gold.couplingError.maxCoeff() / G.cwiseAbs().maxCoeff();
    record.goldConverged = gold.converged;
    // A scene link whose gold cannot vouch for its error is refused, and the class takes the
    // next candidate of its own class instead (runClass); its rules are not scored. A
    // generated link keeps its unconverged gold: the table counts it and the run fails.
    if (!gold.converged && scorers.pool != nullptr) {
      candidate.goldRefused = true;
      return;
    }
    for (const double b : l1ErrorBound(gold.couplingError, area)) record.goldL1BoundTotal += b;
    record.goldFrobeniusError = gold.couplingError.norm() / G.norm();
    record.referenceRelativeErrorVsGold = relativeError(K, G);
    record.referenceFrobeniusErrorVsGold = relativeFrobeniusError(K, G);
    record.referenceL1BoundVsGold = l1ErrorBound(K - G, area);
  }
  std::shared_ptr<LinkDetail> detail;
  if (scorers.keepDetails) {
    detail = std::make_shared<LinkDetail>();
    detail->receiver = link.receiver;
    detail->source = link.source;
    if (generated.built.scene != nullptr) detail->occluders = generated.built.scene->polygons();
    detail->reference = K;
    detail->referenceStandardError = reference.standardError;
    if (scorers.gold) {
      detail->gold = gold.coupling;
      detail->goldError = gold.couplingError;
    }
  }
  LinkIntegral estimate;
  for (std::size_t r = 0; r < scorers.rules.size(); ++r) {
    const int trials = scorers.trials[r];
    const double share = 1.0 / trials;
    double relative = 0.0, relativeGold = 0.0, frobenius = 0.0, frobeniusGold = 0.0;
    std::vector<double> bound, boundGold;
    EntrywiseMoments moments;
    for (int t = 0; t < trials; ++t) {
      scorers.rules[r].integrate(link,
                                 deriveSeed(config.seed, {classIndex, index, 3, std::uint64_t(t)}),
                                 accumulator, estimate, std::size_t(t));
      if (detail) moments.add(estimate.coupling);
      relative += share * relativeError(estimate.coupling, K);
      frobenius += share * relativeFrobeniusError(estimate.coupling, K);
      addInto(bound, l1ErrorBound(estimate.coupling - K, area), share);
      if (scorers.gold) {
        relativeGold += share * relativeError(estimate.coupling, gold.coupling);
        frobeniusGold += share * relativeFrobeniusError(estimate.coupling, gold.coupling);
        addInto(boundGold, l1ErrorBound(estimate.coupling - gold.coupling, area), share);
      }
    }
    if (detail) {
      detail->ruleMean.push_back(moments.mean());
      detail->ruleDeviation.push_back(moments.sampleDeviation());
    }
    record.relativeError.push_back(relative);
    record.frobeniusError.push_back(frobenius);
    record.l1Bound.push_back(std::move(bound));
    if (scorers.gold) {
      record.relativeErrorVsGold.push_back(relativeGold);
      record.frobeniusErrorVsGold.push_back(frobeniusGold);
      record.l1BoundVsGold.push_back(std::move(boundGold));
    }
  }
  record.detail = std::move(detail);
}

ClassRun runClass(const StudyConfig& config, const StudyOptions& options, const Scorers& scorers,
                  std::size_t classIndex, StudyClass linkClass, int wanted) {
  ClassRun run;
  run.linkClass = linkClass;
  std::uint64_t limit = std::uint64_t(wanted) * std::uint64_t(config.maxCandidatesPerLink);
  if (scorers.pool != nullptr) {
    // Scene-derived: the pool's links of the class, in sampling order; a class whose links the
    // pool runs out of holds all of them.
    run.available = scorers.pool->size();
    if (run.available <= limit) {
      limit = run.available;
      wanted = int(std::min<std::size_t>(std::size_t(wanted), run.available));
    }
  }
  run.wanted = wanted;
  tbb::enumerable_thread_specific<CouplingAccumulator> accumulators;
  std::vector<Candidate> candidates;
  while (run.links.size() < std::size_t(wanted)) {
    if (run.generated >= limit && scorers.pool != nullptr && limit == run.available) break;
    if (run.generated >= limit) {
      throw InputError(std::string("class '") + studyClassName(linkClass) + "': only " +
                       std::to_string(run.links.size()) + " of " + std::to_string(wanted) +
                       " links qualified in " + std::to_string(run.generated) +
                       " candidates (max_candidates_per_link = " +
                       std::to_string(config.maxCandidatesPerLink) + ")");
    }
    // Size the batch from the acceptance rate so far; the batch size only affects how many
    // candidates are classified in vain, never which links are kept.
    const std::size_t missing = std::size_t(wanted) - run.links.size();
    const double rate =
        run.generated == 0 ? 0.8 : std::max(0.02, double(run.links.size()) / double(run.generated));
    const std::uint64_t batch = std::min<std::uint64_t>(
        limit - run.generated,
        std::max<std::uint64_t>(16, std::uint64_t(1.2 * missing / rate) + 4));
    candidates.assign(batch, Candidate{});
    const std::uint64_t first = run.generated;
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, batch, 1),
                      [&](const tbb::blocked_range<std::uint64_t>& range) {
                        CouplingAccumulator& accumulator = accumulators.local();
                        for (std::uint64_t k = range.begin(); k < range.end(); ++k) {
                          classifyCandidate(config, scorers, classIndex, linkClass, first + k,
                                            accumulator, candidates[k]);
                        }
                      });
    std::vector<std::size_t> kept;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (run.links.size() + kept.size() == std::size_t(wanted)) break;
      const Candidate& candidate = candidates[k];
      ++run.generated;
      run.referenceRays += candidate.rays;
      if (candidate.ownClass != nullptr) ++run.candidatesByOwnClass[candidate.ownClass];
      if (candidate.accepted) {
        kept.push_back(k);
      } else if (candidate.ownClass != nullptr) {
        // Scene-derived: another class's link, counted by its own class above.
      } else if (candidate.occluderCrossesPatch) {
        ++run.rejectedOccluderCrossesPatch;
      } else if (candidate.mostlyBlocked) {
        ++run.rejectedMostlyBlocked;
      } else {
        ++run.rejectedMostlyVisible;
      }
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kept.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        CouplingAccumulator& accumulator = accumulators.local();
                        for (std::size_t k = range.begin(); k < range.end(); ++k) {
                          scoreLink(config, scorers, classIndex, linkClass, accumulator,
                                    candidates[kept[k]]);
                        }
                      });
    // Refused links leave their places to the next candidates of the class: the suite is the
    // first N qualifying candidates whose gold converged, whatever the batch sizes.
    for (const std::size_t k : kept) {
      if (candidates[k].goldRefused) {
        run.refusedGoldCandidates.push_back(candidates[k].record.candidate);
      } else {
        run.links.push_back(std::move(candidates[k].record));
      }
    }
    if (options.progress) {
      std::cerr << "radquad study: " << studyClassName(linkClass) << " links " << run.links.size()
                << "/" << wanted << " (" << run.generated << " candidates)\n";
    }
  }
  return run;
}

}  // namespace

const char* sceneLinkClass(const Link& link, double visibleFraction, const StudyConfig& config) {
  const char* geometric = geometricClass(link);
  return geometric != nullptr ? geometric : occludedClass(visibleFraction, config);
}

StudyRun runStudy(const StudyConfig& config, const StudyOptions& options) {
  const int degree = config.degree();
  Scorers scorers{{}, {}, ReferenceEstimator(config.reference, degree), options.gold};
  scorers.keepDetails = options.keepDetails;
  StudyRun run;
  // The rules first (a rule file, the sample budget), before the scene solves.
  for (const std::string& name : config.rules) {
    scorers.rules.emplace_back(findAnyRule(name), degree);
    const Rule& rule = scorers.rules.back().rule();
    const int trials = rule.isRandom() ? config.trials : 1;
    checkSampleBudget(rule, trials, "rule " + rule.name());
    checkDrawCount(rule, trials, "study trials");
    scorers.trials.push_back(trials);
    run.rules.push_back({rule.name(), rule.sampleCount(), rule.isRandom(), trials});
  }
  std::unique_ptr<SceneLinkPool> pool;
  if (config.sceneLinks) {
    pool = std::make_unique<SceneLinkPool>(*config.sceneLinks, config.seed);
    scorers.pool = pool.get();
    run.sceneLinks = pool->totalLinks();
    run.sceneOccludedLinks = pool->occludedLinks();
    run.sceneSolverUnoccluded = pool->solverUnoccludedLinks();
    run.sceneSolverPartial = pool->solverPartialLinks();
  }
  run.referenceName = scorers.reference.name();
  run.referenceSamples = scorers.reference.samples();
  for (std::size_t c = 0; c < config.classes.size(); ++c) {
    const auto [linkClass, wanted] = config.classes[c];
    // The class index in the seed is the class's fixed number (unoccluded 0, partial 1), so a
    // suite's partial links do not change when an unoccluded class is added or removed.
    run.classes.push_back(
        runClass(config, options, scorers, std::size_t(linkClass), linkClass, wanted));
  }
  return run;
}

}  // namespace radquad
