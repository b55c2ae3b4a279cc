#!/usr/bin/env bash
# `radquad solve --rules adaptive --compare` through the real binary on a small scene: exit 0,
# the comparison fields, a small difference from the fixed solution, fewer kernel
# evaluations, the ratios recomputed from the counts; the adaptive table reports the same
# statistics; bad rule options exit with status 2 and say which option; `radquad adaptive`'s
# timing repeats on a tiny table.
# Usage: RADQUAD=PATH/TO/radquad adaptive_cli_test.sh (or the path as the first argument)
set -u
source "$(dirname "${BASH_SOURCE[0]}")/expect_status.sh"

# Two opposed unit squares, a black emitter and a grey receiver, and a small blocker between.
cat >"$work/squares.json" <<'JSON'
{"patches": [
  {"name": "emitter", "origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0],
   "reflectance": [0,0,0], "emission": [1,1,1]},
  {"name": "receiver", "origin": [0,0,1], "edge_u": [0,1,0], "edge_v": [1,0,0],
   "reflectance": [0.6,0.6,0.6]},
  {"name": "blocker", "origin": [0.3,0.3,0.5], "edge_u": [0,0.3,0], "edge_v": [0.3,0,0],
   "reflectance": [0.5,0.5,0.5]}]}
JSON

expect_status 2 "negative threshold" "--threshold" solve "$work/squares.json" --rules adaptive --threshold -1
expect_status 2 "unknown rule choice" "adaptive-novis" solve "$work/squares.json" --rules adaptiv

for rules in adaptive adaptive-novis; do
  expect_status 0 "$rules --compare" "" solve "$work/squares.json" --degree 2 --rules "$rules" \
    --compare --bf-eps 0.05 --quiet
  if ! /usr/bin/python3 - "$work/out" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
c = out["comparison"]
assert out["options"]["rules"] in ("adaptive", "adaptive-novis"), out["options"]
assert set(c) >= {"fixed_kernel_evaluations", "fixed_elapsed_seconds", "relative_l2_difference"}
assert 0 <= c["relative_l2_difference"] < 0.01, c
assert out["kernel_evaluations"] < c["fixed_kernel_evaluations"], (out["kernel_evaluations"], c)
# The ratios, recomputed from the reported counts.
def close(a, b): return abs(a - b) <= 1e-12 * abs(b)
assert close(c["evaluation_ratio"], c["fixed_kernel_evaluations"] / out["kernel_evaluations"]), c
# Near-field links are integrated alike whatever the rule choice: the same points either way
# when the hierarchy is the same, and never counted as product-rule kernel evaluations.
assert out["near_field_points"] >= 0 and c["fixed_near_field_points"] >= 0, c
assert (out["near_field_links"] > 0) == (out["near_field_points"] > 0), out
assert out["converged"] is True and out["failure"] == "", out
PY
  then
    echo "FAIL: $rules --compare output"; failures=$((failures + 1))
  fi
  cp "$work/out" "$work/solve-$rules.json"
done

# `radquad adaptive` on a tiny table with two timing repeats: every run listed, the fastest
# reported, the ratios from the fastest; a repeat count of 0 is refused.
expect_status 2 "no timing repeats" "--timing-repeats" adaptive --timing-repeats 0
expect_status 2 "unknown sweep scene, before any solve" "--sweep-scene foo" adaptive --sweep-scene foo --quiet --results "$work/results" --plots "$work/plots"
if [[ -e "$work/results/adaptive.json" ]]; then
  echo "FAIL: a rejected adaptive run wrote results"; failures=$((failures + 1))
fi
mkdir -p "$work/adaptive"
expect_status 0 "adaptive, two timing repeats" "" adaptive --scenes cornell --degrees 1 \
  --bf-eps 1 --sweep 1 --sweep-bf-eps 1 --sweep-degree 1 --timing-repeats 2 \
  --results "$work/adaptive" --plots "$work/adaptive" --quiet
if ! /usr/bin/python3 - "$work/adaptive/adaptive.json" "$work/adaptive/adaptive.run.json" \
    "$work/solve-adaptive.json" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
assert out["options"]["timing_repeats"] == 2, out["options"]
text = open(sys.argv[1]).read()
assert "seconds" not in text and "time_ratio" not in text and "commit" not in text, "times in the result"
assert "per_second" not in text, "a rate in the result"
# A run of the table reports what `radquad solve --compare` reports, but for times.
solved = json.load(open(sys.argv[3]))
statistics = set(solved) - {"scene", "options", "patches", "comparison", "elapsed_seconds",
                            "coupling_seconds", "kernel_evaluations_per_second"}
comparison = set(solved["comparison"]) - {"fixed_elapsed_seconds", "fixed_coupling_seconds"}
run = out["table"][0]["adaptive"]
assert set(run) >= statistics | comparison, (statistics | comparison) - set(run)
record = json.load(open(sys.argv[2]))  # the times, in the result's shape
assert record["result"] == "adaptive.json" and "git_commit" in record, record.keys()
assert set(out["table"][0]) >= set(record["table"][0]) - {"scene", "degree"}
row = record["table"][0]
for choice in ("fixed", "adaptive", "adaptive-novis"):
    run = row[choice]
    assert len(run["elapsed_seconds_runs"]) == 2, run
    assert run["elapsed_seconds"] == min(run["elapsed_seconds_runs"]), run
    assert run["coupling_seconds"] == min(run["coupling_seconds_runs"]), run
for choice in ("adaptive", "adaptive-novis"):
    ratio = row["fixed"]["elapsed_seconds"] / row[choice]["elapsed_seconds"]
    assert abs(row[choice]["time_ratio"] - ratio) <= 1e-12 * ratio, (row[choice], ratio)
PY
then
  echo "FAIL: adaptive timing repeats"; failures=$((failures + 1))
fi

if [[ $failures -ne 0 ]]; then
  echo "$failures failure(s)"; exit 1
fi
echo "adaptive CLI checks passed"
