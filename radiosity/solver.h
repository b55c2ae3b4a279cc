// The hierarchical Galerkin multiwavelet radiosity solver (Gortler, Schroeder, Cohen and
// Hanrahan 1993, "Wavelet radiosity", with the multiwavelet (Legendre) bases of Alpert as
// used by Gershbein 1995): quadtree elements per patch, links between elements chosen by
// the BF oracle of Hanrahan, Salzman and Aupperle 1991, couplings integrated with Gauss
// product rules, Jacobi gather iterations with push/pull. See radiosity/README.md.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "quadrature/adaptive_gauss.h"
#include "radiosity/hierarchy.h"
#include "radiosity/huge_pages.h"
#include "radiosity/memory_budget.h"
#include "radiosity/scene.h"
#include "radiosity/source_projection.h"
#include "radiosity/visibility.h"

namespace radquad {

// How each link's Gauss rule (points per axis {Rs, Rt, Su, Sv}) is chosen.
enum class RuleChoice {
  kFixed,                 // (d+1) points on every axis
  kAdaptive,              // Gershbein 1995, Figure 4 (quadrature/adaptive_gauss.h)
  kAdaptiveNoVisibility,  // Figure 4 without the extra point for partially occluded links
};

// "fixed", "adaptive", "adaptive-novis".
const char* ruleChoiceName(RuleChoice rules);

// The default ErrThres of the adaptive rules: a coefficient is significant when its
// component's RMS radiosity over the source element exceeds this fraction of the scene's
// emitted radiosity scale (see radiosity/README.md, "Adaptive rules"). 0.05 keeps every
// patch's mean radiosity within 1% of the fixed rules' on the built-in scenes at degrees 1-3
// (0.1 did not: 1.05% on cubic cornell and 1.02% on linear slats without the visibility
// step); docs/study.md, "How to choose ErrThres", has the measurements.
inline constexpr double kDefaultErrThres = 0.05;

// The default kernel check of the adaptive rules (radiosity/kernel_curvature.h): a source
// axis left with one point gets two where the midpoint rule's estimated relative error along
// it exceeds this.
inline constexpr double kDefaultKernelCurvature = 0.01;

struct SolverOptions {
  int degree = 0;
  RuleChoice rules = RuleChoice::kFixed;
  // Adaptive rules: ErrThres, relative to the scene's radiosity scale (below).
  double errThres = kDefaultErrThres;
  // Adaptive rules: a one-point source axis whose estimated midpoint error (relative) exceeds
  // this gets two points (radiosity/kernel_curvature.h); 0 turns the check off, leaving
  // Figure 4's choice alone.
  double kernelCurvature = kDefaultKernelCurvature;
  // Adaptive rules: how the source orders a reduced rule does not keep are gathered
  // (radiosity/source_projection.h). Fixed rules keep every order; this changes nothing there.
  DroppedOrders droppedOrders = DroppedOrders::kTruncated;
  // BF oracle: refine a link when F_estimate * B_source (* partialFactor if partial) exceeds
  // bfEpsilon times the scene's radiosity scale, its emitted power over its total area
  // (sum_i max_c E_i,c A_i / sum_i A_i: the mean radiosity before any reflection) ...
  double bfEpsilon = 0.05;
  // ... and the larger element's area exceeds minArea (scene units squared); a value <= 0
  // means 1e-4 of the largest patch's area.
  double minArea = 0.0;
  // Beside the transfer, a link is split at its source when the part of the source's
  // radiosity that its polynomial cannot show, times the form factor and the receiver's
  // reflectance, exceeds this fraction of the receiver's radiosity in some channel
  // (Solver::sourceVariationMatters); 0 turns the check off.
  double variationEpsilon = 0.01;
  // Partially visible links are less certain: their transfer estimate is multiplied by this.
  double partialFactor = 4.0;
  // Iterations stop when the relative L2 change of the patch-level radiosity falls below
  // this and the last refinement pass split no link.
  double tolerance = 1e-4;
  int maxIterations = 200;
  int maxLevel = 12;  // deepest quadtree level an element may have
  // Budgets: refinement stops, and the solve fails with a message naming the budget, when
  // it would create more elements or links than these (about 0.3 KB per element and 0.15 KB
  // per link before couplings; the couplings' own store comes on top).
  std::size_t maxElements = 10000000;
  std::size_t maxLinks = 100000000;
  // The process's resident memory (radiosity/memory_budget.h), checked during the initial
  // linking (every 16 patches, every chunk of classification), after every wave of
  // refinement and after every integration pass; the solve fails with a message naming the
  // budget when it is exceeded.
  std::size_t maxMemoryBytes = defaultMemoryBudget();
  // Links between near elements (touching, cut by the other's plane, or closer than their
  // sizes) are integrated in the near field (near_field.h); false integrates them with their
  // product rules like the others, to measure what the near field changes.
  bool nearField = true;
  // The base seed of the links' own generators (adaptive rules on partial links).
  std::uint64_t seed = 0;
  // Called after every iteration (for progress reports); may be empty.
  std::function<void(const struct SolveProgress&)> progress;
  // Called during the initial linking (quadratic in the patches), at most about once a
  // second once it has run a second: patches linked so far of all, links so far; may be empty.
  std::function<void(const struct LinkingProgress&)> linkingProgress;
  // Called during a refinement pass, at most about once a second once the pass has run a
  // second: its wave, the links split so far in it, elements and links; may be empty.
  std::function<void(const struct RefinementProgress&)> refinementProgress;
};

struct RefinementProgress {
  int wave = 0;               // breadth-first waves of splits in this pass, from 1
  std::size_t splits = 0;     // links split in this pass so far
  std::size_t elements = 0, links = 0;
  double elapsedSeconds = 0.0;  // since the pass began
};

struct LinkingProgress {
  std::size_t patchesDone = 0, patches = 0;
  std::size_t links = 0;
  std::size_t classified = 0;  // links whose visibility is classified so far
  double elapsedSeconds = 0.0;
};

struct SolveProgress {
  int iteration = 0;
  std::size_t activeLinks = 0;
  std::size_t elements = 0;
  std::uint64_t kernelEvaluations = 0;
  double change = 0.0;
  double elapsedSeconds = 0.0;
};

// What the solver's coupling store holds for a link: the rule its coupling was integrated
// with and where it is kept.
struct LinkCoupling {
  bool computed = false;  // whether the link's coupling (in the solver's store) is this rule's
  int slot = -1;          // where the solver's store keeps its coupling (-1: none yet)
  GaussPointCounts rule = {1, 1, 1, 1};      // Gauss points on {Rs, Rt, Su, Sv}
  std::array<int, 2> sourcePoints = {0, 0};  // the source's {Su, Sv} when `rule` was chosen
  // The source points {pu, pv} whose columns the stored coupling keeps (source_projection.h):
  // min(Su, d+1), min(Sv, d+1) for a product rule, {d+1, d+1} (every column) for a
  // composite one. Its slot in the store is keptColumns() = pu pv columns wide.
  std::array<int, 2> gatherPoints = {0, 0};
  std::uint64_t kernelEvaluations = 0;  // of the last computation
};

// One link: energy from `source` element to `receiver` element; its place in the hierarchy
// (refinement.cpp) and, apart, its cached coupling (solver.cpp).
struct SolverLink {
  int receiver = 0;
  int source = 0;
  LinkClass visibility = LinkClass::kUnoccluded;
  // Whether the link carries energy now. Inactive: replaced by its children (split), or
  // occluded (every classification ray blocked: it carries nothing, but the refinement passes
  // still examine it and split it where its estimate, counted as partial, is too large).
  bool active = true;
  bool split = false;
  bool occlusionProven = false;  // occluded by one candidate (blocksShaft): never examined
  // The BF oracle's form-factor estimate (a function of the two elements alone), kept in
  // single precision once computed, so that later refinement passes only multiply it by the
  // source's radiosity; -1 until the oracle first examines the link (and where single
  // precision cannot hold it), 0 where the larger element may not be split
  // (Solver::oracleSaysRefine).
  float oracleFormFactor = -1.0f;
  // Whether the elements are near each other (link_integration.h, nearField): the coupling
  // is integrated in the near field, and the oracle estimates from exact point form factors.
  bool nearField = false;
  std::vector<int> candidates;   // candidate occluders (patch indices)
  LinkCoupling coupling;
};

// The leaves' receiver sums (form_factor_check.cpp): the mean irradiance the couplings deliver
// to a leaf from a radiosity of 1 everywhere, at most 1 for exact couplings and refinement.
// The solve refines a leaf above 1 + kFormFactorSumTolerance, and fails when it cannot.
inline constexpr double kFormFactorSumTolerance = 0.05;
struct FormFactorSums {
  double maximum = 0.0;
  int patch = -1;              // the patch of the leaf with the largest sum
  int element = -1;            // that leaf
  std::size_t violations = 0;  // leaves above 1 + kFormFactorSumTolerance
};

// The solver's links: millions of them at degree 2, in huge pages (huge_pages.h).
using LinkArray = HugePageVector<SolverLink>;

inline int keptColumns(const SolverLink& link) {
  return link.coupling.gatherPoints[0] * link.coupling.gatherPoints[1];
}

struct SolveStatistics {
  std::uint64_t kernelEvaluations = 0;         // over the whole solve, all computations
  std::uint64_t couplingComputations = 0;      // links integrated (first time or again)
  std::uint64_t recomputations = 0;            // links integrated again with a new rule
  std::uint64_t recomputationEvaluations = 0;  // kernel evaluations of those (included above)
  // Links integrated in the near field (touching, cut by the other's plane, or near:
  // near_field.h) and their receiver points, each with its exact inner integrals; not kernel
  // evaluations, which count the product rules' points.
  std::uint64_t nearFieldLinks = 0;
  std::uint64_t nearFieldPoints = 0;
  // Unoccluded kernel evaluations of the adaptive rules' kernel check (included above).
  std::uint64_t ruleCheckEvaluations = 0;
  std::uint64_t classificationRays = 0;
  std::uint64_t integrationRays = 0;
  std::size_t unoccludedLinks = 0, partialLinks = 0, occludedLinks = 0;  // final, by class
  std::size_t refinedLinks = 0;  // links split into sub-links
  int iterations = 0;
  bool converged = false;
  double finalChange = 0.0;
  // The estimated relative error of the patch-level radiosity when the iterations stopped
  // (iteration.cpp), and how often they were extrapolated along their slowest mode.
  double finalError = 0.0;
  int extrapolations = 0;
  double elapsedSeconds = 0.0;
  // Wall time spent choosing rules and integrating couplings (the part the rule choice
  // changes; the rest is refinement, visibility classification, the storage of the coupling
  // matrices, gathers and push/pull).
  double couplingSeconds = 0.0;
  // The coupling store's memory when the solve ended (it is then released).
  std::size_t couplingStoreBytes = 0;
  FormFactorSums formFactorSums;
  // Why the solve did not converge (empty when it did): the iteration cap, or divergence.
  std::string failure;
};

class Solver {
 public:
  Solver(const Scene& scene, SolverOptions options);
  ~Solver();

  // Runs refinement and iterations to convergence, once per solver. The coupling matrices
  // are released at the end (the links keep their rules and counts; their slots become -1).
  void solve();

  const Hierarchy& hierarchy() const { return *hierarchy_; }
  const LinkArray& links() const { return links_; }
  const SolveStatistics& statistics() const { return statistics_; }
  const SolverOptions& options() const { return options_; }
  double minArea() const { return minArea_; }
  // The scene's emitted power over its total area (the BF oracle's and ErrThres's scale).
  double radiosityScale() const { return radiosityScale_; }

 private:
  struct Impl;

  void createInitialLinks();
  // Fills statistics_.formFactorSums from the couplings (form_factor_check.cpp).
  void checkFormFactorSums();
  // Per element, the mean over it of the irradiance the couplings deliver from a radiosity of
  // 1 on every surface (form_factor_check.cpp).
  std::vector<double> receiverSums() const;
  // Marks, in forcedSplit_, the active links received by the ancestors of every leaf whose
  // receiver sum exceeds 1 + kFormFactorSumTolerance (the next refinement pass splits them at
  // their receivers) and the leaf's own links (split at their sources where those can be
  // split, else at the leaf); returns how many it marked.
  std::size_t markSumViolations();
  std::vector<char> forcedSplit_;  // 0, kSplitReceiver or kSplitSource per link
  static constexpr char kSplitReceiver = 1, kSplitSource = 2;
  // Fails a converged solve whose leaves still create energy, or with a negative patch mean.
  void checkSolution();
  // The patch of element e (describePatch) and where the element lies on it.
  std::string describeElement(int e) const;
  // A description of the first patch whose mean radiosity is not finite or far beyond the
  // physical bound; empty when there is none.
  std::string divergence() const;
  // The element of a link to split: 0 receiver, 1 source (solver.cpp).
  int splitSide(const SolverLink& link) const;
  bool refinementPass();
  // Sets budgetExceeded_ when the resident memory exceeds the budget; returns whether it did.
  bool memoryExceeded(const char* phase);
  std::string budgetExceeded_;  // set when a budget stops the solve
  void classifyLinks(HugePageVector<int>& created);
  // Which element of a link the oracle splits: -1 none, 0 the receiver, 1 the source.
  // Records the link's form-factor estimate (link.oracleFormFactor) on its first examination.
  int oracleChoice(SolverLink& link) const;
  bool oracleSaysRefine(SolverLink& link) const;
  // Whether the part of the source's radiosity that its polynomial cannot show
  // (sourceVariation_) can move the receiver's by more than variationEpsilon of its own.
  bool sourceVariationMatters(const SolverLink& link, double formFactor) const;
  // Per element, per channel: the largest RMS over its children of their radiosity less the
  // element's polynomial pushed onto them (0 for a leaf); measured at each refinement pass.
  void measureSourceVariation();
  std::vector<Eigen::Vector3f> sourceVariation_;
  // The area at or below which neither element of the link is split: the smallest area,
  // or less for a near link across a gap narrower than the smallest element (refinement.cpp).
  double smallestArea(const SolverLink& link) const;
  // Whether an element may be split, where elements at or below `smallest` may not.
  bool splittable(const Element& element, double smallest) const {
    return element.geometry.area > smallest && element.level < options_.maxLevel;
  }
  // The oracle's form-factor estimate, in double precision (0 where the link's larger element
  // may not be split).
  double oracleFormFactor(const SolverLink& link) const;
  // The adaptive rules' input for a source element; `magnitudes` holds (d+1)^2 values.
  AdaptiveGaussInput adaptiveInput(int sourceElement, double* magnitudes) const;
  // The link's rule, from link.coupling.sourcePoints (the source's Figure 4 points of this pass, set
  // by computeCouplings); adds the kernel check's evaluations to *checkEvaluations.
  GaussPointCounts chooseRule(const SolverLink& link, std::uint64_t* checkEvaluations) const;
  void updateSourcePoints();
  // Returns the number of links integrated (0: the system is unchanged).
  std::size_t computeCouplings();
  void layOutProjections();
  void projectSources();
  void gather();
  void buildGatherTable();
  // Jacobi's step, error estimate and extrapolation (iteration.cpp).
  void snapshotRadiosity();
  std::array<double, 3> pushPull();
  // Records a step's change per channel; returns the estimated relative error of the
  // patch-level radiosity (infinity while it cannot be estimated), after extrapolating along
  // the slowest mode where its rate has settled.
  double settleEstimate(const std::array<double, 3>& change);
  void restartIterationHistory();
  // The absolute patch-level change per channel of each step since the system last changed.
  std::vector<std::array<double, 3>> iterationChanges_;
  std::array<double, 3> lastAbsoluteChange_{};
  std::array<double, 3> largestReflectance_{};  // per channel, over the patches
  // Set by settleEstimate when the slowest mode decays more slowly than any reflectance
  // allows: couplings that create energy.
  bool energyCreated_ = false;
  std::vector<double> previousRadiosity_;  // every element's radiosity before the last step
  // The elements' lists of active links (Element::links, in link order), brought up to date
  // after the initial linking or a refinement pass (the links it split leave their receivers'
  // lists, the active links it created join theirs).
  void updateElementLinks();
  void countLinks();

  const Scene& scene_;
  SolverOptions options_;
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<Hierarchy> hierarchy_;
  LinkArray links_;
  // The links the element lists were last built from (links_[0, listedLinks_)) and the links
  // split since (refinementPass), for updateElementLinks.
  std::size_t listedLinks_ = 0;
  std::vector<int> splitSinceListed_;
  std::vector<std::array<int, 2>> sourcePoints_;  // per element, see updateSourcePoints
  // gather(): the sources' projections Bhat, at projectionOffset_[element * (d+1)^2 + shape]
  // (shape (pu - 1) * (d+1) + pv - 1; -1 where no link gathers through it).
  std::vector<std::ptrdiff_t> projectionOffset_;
  std::vector<double> projections_;
  SolveStatistics statistics_;
  double minArea_ = 0.0;
  double radiosityScale_ = 0.0;  // the emitted power over the total area
};

}  // namespace radquad
