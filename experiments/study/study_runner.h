// The study runner: draws candidate links class by class, keeps those that qualify (partial
// links: the reference's visible fraction inside the config's range), and scores every rule
// on them against the reference (and, on request, the gold reference).
//
// Scene-derived links are classed by their own geometry and visibility, not by the solver's
// conservative class (sceneLinkClass): singular when the patches touch or one crosses the
// other's plane (singularLink, reference/gold_reference.h: the kernel is not smooth, product
// rules do not apply, and the solver integrates such links with composite rules); otherwise
// unoccluded when no occluder meets the link's shaft (ExactVisibility::occludersInShaft,
// exact: the gold's own choice); otherwise partial when the reference's visible fraction lies
// inside the config's range, and "mostly_blocked" or "mostly_visible" (not scored) beyond it,
// as for generated links.
//
// Determinism: candidate k of class c is drawn from deriveSeed(seed, {c, k, 0}); its
// reference uses deriveSeed(seed, {c, k, 1}), its gold deriveSeed(seed, {c, k, 2}), and trial
// t of a random rule deriveSeed(seed, {c, k, 3, t}) (a rule of listed draws: its draw t, on
// every link). Candidates are scored in parallel
// (oneTBB) and stored by index; the first N qualifying candidates in index order form the
// suite, so the output does not depend on the thread count. A scene-derived link whose gold
// does not converge is refused (ClassRun::refusedGoldCandidates) and the next qualifying
// candidate takes its place; a generated one keeps its unconverged gold (the run fails).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "kernel/patch.h"

#include "experiments/study/study_config.h"

namespace radquad {

struct StudyOptions {
  bool gold = false;        // also score against the gold reference
  bool progress = false;    // progress lines on stderr
  bool keepDetails = false;  // keep every link's geometry and couplings (LinkDetail)
};

// Everything about one scored link that the per-link table (`--links-out`) writes: its
// geometry and every coupling it was scored with.
struct LinkDetail {
  Patch receiver, source;
  std::vector<std::vector<Eigen::Vector3d>> occluders;  // polygons (triangles for soups)
  Eigen::MatrixXd reference, referenceStandardError;
  Eigen::MatrixXd gold, goldError;  // empty without gold
  // Per rule: the coupling (the mean over its trials for a random rule) and the entrywise
  // sample standard deviation over the trials (zeros for one trial).
  std::vector<Eigen::MatrixXd> ruleMean, ruleDeviation;
};

// The scores of one accepted link. Random rules: means over the trials.
struct LinkRecord {
  std::uint64_t candidate = 0;
  Orientation orientation = Orientation::parallel;
  OccluderKind occluderKind = OccluderKind::none;
  std::string scene;  // scene-derived links: the name of the link's scene (empty otherwise)
  double visibleFraction = 1.0;                  // by the reference's rays
  double distanceFactor = 0.0;  // centre distance / the longest side of the two patches
  double referenceRelativeStandardError = 0.0;   // NaN when the reference gives none
  std::vector<double> referenceL1StandardError;  // per source function; empty when none
  std::vector<double> relativeError;             // per rule
  std::vector<double> frobeniusError;            // per rule: relativeFrobeniusError
  std::vector<std::vector<double>> l1Bound;      // per rule, per source function
  // With gold: the same against gold, and the reference's own error against gold.
  std::vector<double> relativeErrorVsGold;
  std::vector<double> frobeniusErrorVsGold;
  std::vector<std::vector<double>> l1BoundVsGold;
  double referenceRelativeErrorVsGold = 0.0;
  double referenceFrobeniusErrorVsGold = 0.0;
  std::string goldMethod;  // "gauss product", "exact visibility" or "dense stratified"
  // Exact visibility: its outer integration, "critical lines", "jump lines" or "genz-malik".
  std::string goldOuterMethod;
  double goldRelativeError = 0.0;  // the gold's own error estimate of K[0][0] / K[0][0]
  // The gold's largest error estimate over the largest |K| entry, and whether it met its
  // tolerance.
  double goldMaxRelativeError = 0.0;
  bool goldConverged = true;
  // The gold's own error in the two other metrics: its error estimates put through the L1
  // bound (summed over source functions), and their Frobenius norm over the gold's.
  double goldL1BoundTotal = 0.0;
  double goldFrobeniusError = 0.0;
  std::vector<double> referenceL1BoundVsGold;
  std::shared_ptr<const LinkDetail> detail;  // with StudyOptions::keepDetails
};

struct ClassRun {
  StudyClass linkClass = StudyClass::partial;
  int wanted = 0;
  std::uint64_t generated = 0;
  std::uint64_t rejectedMostlyVisible = 0;  // visible fraction >= high
  std::uint64_t rejectedMostlyBlocked = 0;  // visible fraction <= low
  std::uint64_t rejectedOccluderCrossesPatch = 0;  // an occluder passes through a patch
  std::vector<LinkRecord> links;            // accepted, in candidate order
  std::uint64_t referenceRays = 0;          // over every candidate drawn
  std::size_t available = 0;                // scene-derived: the links in the pool
  // Scene-derived: the candidates drawn, by their own class (sceneLinkClass).
  std::map<std::string, std::uint64_t> candidatesByOwnClass;
  // Scene-derived, with gold: the candidates of the class refused because their gold did not
  // converge (each replaced by the next candidate of the class), in candidate order.
  std::vector<std::uint64_t> refusedGoldCandidates;
};

struct RuleInfo {
  std::string name;
  std::size_t samples = 0;
  bool random = false;
  int trials = 1;
};

struct StudyRun {
  std::vector<RuleInfo> rules;
  std::string referenceName;
  std::size_t referenceSamples = 0;
  std::vector<ClassRun> classes;
  // Scene-derived links: the solve's final active links, the occluded ones among them, and
  // the solver's classes of the others (the pool).
  std::size_t sceneLinks = 0, sceneOccludedLinks = 0;
  std::size_t sceneSolverUnoccluded = 0, sceneSolverPartial = 0;
};

// The class of a scene-derived link by its own geometry and visibility (above): "singular",
// "unoccluded", "partial", "mostly_blocked" or "mostly_visible"; `visibleFraction` is the
// reference's.
const char* sceneLinkClass(const Link& link, double visibleFraction, const StudyConfig& config);

// Throws InputError when a class cannot be filled within max_candidates_per_link.
StudyRun runStudy(const StudyConfig& config, const StudyOptions& options);

// The error table (the JSON contract of docs/cli.md, "The tables"); the commit and the elapsed
// time go to the run record beside it (experiments/study/study_output.h).
nlohmann::json studyTable(const StudyConfig& config, const StudyOptions& options,
                          const StudyRun& run);

// The per-link table: one JSON object per line for every scored link (docs/cli.md, "Per-link
// tables"); needs a run with StudyOptions::keepDetails.
std::string linkTableLines(const StudyConfig& config, const StudyRun& run);

}  // namespace radquad
