#include "experiments/trace_report.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "kernel/input_error.h"

namespace radquad {
namespace {

const char* const kChannelNames[3] = {"red", "green", "blue"};

nlohmann::json channelsJson(const Eigen::Vector3d& v) {
  nlohmann::json out = nlohmann::json::array();
  for (int c = 0; c < 3; ++c) {
    out.push_back(std::isfinite(v[c]) ? nlohmann::json(v[c]) : nlohmann::json(nullptr));
  }
  return out;
}

// numerator / denominator, 0 when both are 0, nullopt when only the denominator is 0 (or the
// denominator is not a number: the standard error of a single sample).
std::optional<double> ratio(double numerator, double denominator) {
  if (std::isnan(denominator)) return std::nullopt;
  if (denominator != 0.0) return numerator / denominator;
  if (numerator == 0.0) return 0.0;
  return std::nullopt;
}

// The largest |value| seen, with where it was.
struct Worst {
  double magnitude = -1.0;
  double value = 0.0;
  std::size_t patch = 0;
  int channel = 0;

  void offer(double candidate, std::size_t p, int c) {
    if (std::abs(candidate) > magnitude) {
      magnitude = std::abs(candidate);
      value = candidate;
      patch = p;
      channel = c;
    }
  }
  nlohmann::json json(const Scene& scene) const {
    if (magnitude < 0.0) return nullptr;
    return {{"patch", scene.patches[patch].name},
            {"channel", kChannelNames[channel]},
            {"value", value}};
  }
};

}  // namespace

std::uint64_t parseDecimalOption(const std::string& text, const std::string& option,
                                 std::uint64_t minimum, std::uint64_t maximum) {
  const std::string range = std::to_string(minimum) + ".." + std::to_string(maximum);
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [next, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || text[0] < '0' || text[0] > '9' || error == std::errc::invalid_argument ||
      next != end) {
    throw InputError(option + " " + text + ": expected a decimal integer in " + range);
  }
  if (error == std::errc::result_out_of_range || value < minimum || value > maximum) {
    throw InputError(option + " " + text + ": out of range (" + range + ")");
  }
  return value;
}

TraceResult runTrace(const Scene& scene, const TraceOptions& options, bool quiet,
                     const std::string& label) {
  TraceOptions run = options;
  if (!quiet) {
    run.progress = [label](const TraceProgress& progress) {
      if (progress.elapsedSeconds < 1.0) return;
      std::fprintf(stderr, "%s: %llu of %llu samples (%.0f%%), %.1f s\n", label.c_str(),
                   static_cast<unsigned long long>(progress.samplesDone),
                   static_cast<unsigned long long>(progress.samplesTotal),
                   100.0 * double(progress.samplesDone) / double(progress.samplesTotal),
                   progress.elapsedSeconds);
    };
  }
  return tracePatches(scene, run);
}

nlohmann::json tracePatchesJson(const Scene& scene, const TraceResult& trace) {
  nlohmann::json patches = nlohmann::json::array();
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    patches.push_back({{"name", scene.patches[p].name},
                       {"area", scene.patches[p].patch.area},
                       {"mean_radiosity", channelsJson(trace.patches[p].meanRadiosity)},
                       {"standard_error", channelsJson(trace.patches[p].standardError)}});
  }
  return patches;
}

nlohmann::json traceCountsJson(const TraceResult& trace) {
  return {{"paths", trace.paths},
          {"rays", {{"hit", trace.hitRays}, {"shadow", trace.shadowRays}}},
          {"truncated_paths", trace.truncatedPaths}};
}

nlohmann::json verificationJson(const Scene& scene, const std::vector<Eigen::Vector3d>& solved,
                                const TraceResult& trace) {
  nlohmann::json patches = nlohmann::json::array();
  Worst worstRelative, worstInErrors;
  double sumRelative = 0.0;
  std::size_t definedRelative = 0, undefined = 0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    const PatchTrace& traced = trace.patches[p];
    Eigen::Vector3d relative, inErrors;
    for (int c = 0; c < 3; ++c) {
      const double difference = solved[p][c] - traced.meanRadiosity[c];
      const std::optional<double> r = ratio(difference, traced.meanRadiosity[c]);
      const std::optional<double> s = ratio(difference, traced.standardError[c]);
      relative[c] = r.value_or(nan);
      inErrors[c] = s.value_or(nan);
      undefined += !r + !s;
      if (r) {
        worstRelative.offer(*r, p, c);
        sumRelative += std::abs(*r);
        ++definedRelative;
      }
      if (s) worstInErrors.offer(*s, p, c);
    }
    patches.push_back({{"name", scene.patches[p].name},
                       {"mean_radiosity", channelsJson(traced.meanRadiosity)},
                       {"standard_error", channelsJson(traced.standardError)},
                       {"relative_difference", channelsJson(relative)},
                       {"difference_in_standard_errors", channelsJson(inErrors)}});
  }
  nlohmann::json out = traceCountsJson(trace);
  out["elapsed_seconds"] = trace.elapsedSeconds;
  out["patches"] = patches;
  out["worst_relative_difference"] = worstRelative.json(scene);
  out["worst_difference_in_standard_errors"] = worstInErrors.json(scene);
  out["mean_absolute_relative_difference"] =
      definedRelative > 0 ? nlohmann::json(sumRelative / double(definedRelative)) : nullptr;
  out["undefined_differences"] = undefined;
  return out;
}

nlohmann::json verifySolution(const Scene& scene, const std::vector<Eigen::Vector3d>& solved,
                              const TraceOptions& options, bool quiet) {
  const TraceResult trace = runTrace(scene, options, quiet, "radquad solve --verify");
  nlohmann::json out = {{"samples", options.samples}, {"seed", options.seed}};
  out.update(verificationJson(scene, solved, trace));
  return out;
}

}  // namespace radquad
