// The command-line side of the Monte Carlo path tracer (radiosity/path_tracer.h), shared by
// `radquad trace` and `radquad solve --verify`: strict parsing of its counts and seeds, a
// run with progress on stderr, and the JSON of its estimates and of a solution's
// comparison with them.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "radiosity/path_tracer.h"
#include "radiosity/scene.h"

namespace radquad {

// Samples per patch when --samples is not given: cornell takes 33 s of CPU (17 s on two idle
// cores) and its worst relative standard error is 0.19% (radiosity/README.md, "The Monte
// Carlo reference").
inline constexpr std::uint64_t kDefaultTraceSamples = 2097152;  // 2^21

// A decimal integer in [minimum, maximum] (digits only: no sign, space or exponent); throws
// InputError naming `option` otherwise.
std::uint64_t parseDecimalOption(const std::string& text, const std::string& option,
                                 std::uint64_t minimum, std::uint64_t maximum);

// Runs the tracer; unless `quiet`, reports progress on stderr after the first second,
// prefixed by `label` ("radquad trace").
TraceResult runTrace(const Scene& scene, const TraceOptions& options, bool quiet,
                     const std::string& label);

// [{name, area, mean_radiosity [r,g,b], standard_error [r,g,b]}] in scene order (a standard
// error is null when there is one sample per patch).
nlohmann::json tracePatchesJson(const Scene& scene, const TraceResult& trace);

// The counts of a run: {"paths", "rays": {"hit", "shadow"}, "truncated_paths"}.
nlohmann::json traceCountsJson(const TraceResult& trace);

// A solution's per-patch mean radiosity (scene order) against a trace: per patch {name,
// mean_radiosity (the trace's), standard_error, relative_difference (solve / trace - 1),
// difference_in_standard_errors ((solve - trace) / standard error)}, the largest
// |relative_difference| and |difference_in_standard_errors| with their patch and channel, and
// the mean |relative_difference| over patches and channels. A ratio with a zero denominator
// is 0 when the numerator is 0 too, otherwise null, left out of the summary and counted in
// `undefined_differences`.
nlohmann::json verificationJson(const Scene& scene, const std::vector<Eigen::Vector3d>& solved,
                                const TraceResult& trace);

// `radquad solve --verify N`: traces the scene with `options` (progress on stderr unless
// `quiet`) and returns verificationJson with the samples and seed echoed.
nlohmann::json verifySolution(const Scene& scene, const std::vector<Eigen::Vector3d>& solved,
                              const TraceOptions& options, bool quiet);

}  // namespace radquad
