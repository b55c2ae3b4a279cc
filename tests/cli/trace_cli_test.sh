#!/usr/bin/env bash
# `radquad trace` through the real binary: bad options and scenes exit with status 2 and a
# message naming the input; a good run prints the documented JSON, the patches of
# `radquad solve` in the same order, the same numbers for 1 and 2 threads, and --out writes
# the same object; `radquad solve --verify N` adds a verification object.
# Usage: RADQUAD=PATH/TO/radquad trace_cli_test.sh (or the path as the first argument)
set -u
source "$(dirname "${BASH_SOURCE[0]}")/expect_status.sh"
python=/usr/bin/python3

cat >"$work/squares.json" <<'JSON'
{"patches": [
  {"name": "emitter", "origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0],
   "reflectance": [0,0,0], "emission": [1,1,1]},
  {"name": "receiver", "origin": [0,0,1], "edge_u": [0,1,0], "edge_v": [1,0,0],
   "reflectance": [0.5,0.5,0.5]}]}
JSON

expect_status 2 "zero samples" "--samples 0: out of range" trace "$work/squares.json" --samples 0
expect_status 2 "too many samples" "--samples 1000000001: out of range" trace "$work/squares.json" --samples 1000000001
expect_status 2 "samples not a number" "--samples abc: expected a decimal integer" trace "$work/squares.json" --samples abc
expect_status 2 "negative seed" "--seed -1: expected a decimal integer" trace "$work/squares.json" --seed=-1
expect_status 2 "seed above 2^64-1" "--seed 18446744073709551616: out of range" trace "$work/squares.json" --seed 18446744073709551616
expect_status 2 "seed with an exponent" "--seed 1e3" trace "$work/squares.json" --seed 1e3
expect_status 2 "negative threads" "--threads: Value -1 not in range" trace "$work/squares.json" --threads=-1
expect_status 2 "unknown scene" "not a built-in scene" trace no_such_scene
expect_status 2 "unwritable --out" "/proc/radquad-trace.json" trace "$work/squares.json" --samples 4 --out /proc/radquad-trace.json

expect_status 0 "a good run" "" trace "$work/squares.json" --samples 1000 --seed 18446744073709551615 --threads 1 --quiet
cp "$work/out" "$work/one.json"
if [[ -s "$work/err" ]]; then echo "FAIL: --quiet printed on stderr"; failures=$((failures + 1)); fi
expect_status 0 "two threads" "" trace "$work/squares.json" --samples 1000 --seed 18446744073709551615 --threads 2 --quiet
cp "$work/out" "$work/two.json"
expect_status 0 "--out" "" trace "$work/squares.json" --samples 1000 --seed 18446744073709551615 --quiet --out "$work/file.json"
if [[ -s "$work/out" ]]; then echo "FAIL: --out also printed on stdout"; failures=$((failures + 1)); fi
expect_status 0 "solve for the patch order" "" solve "$work/squares.json" --quiet
cp "$work/out" "$work/solve.json"

if ! "$python" - "$work" <<'PY'; then failures=$((failures + 1)); fi
import json, sys
work = sys.argv[1]
load = lambda name: json.load(open(f"{work}/{name}"))
one, two, written, solve = load("one.json"), load("two.json"), load("file.json"), load("solve.json")
problems = []
for key in ["scene", "options", "elapsed_seconds", "paths", "rays", "truncated_paths", "patches"]:
    if key not in one:
        problems.append(f"no '{key}'")
if one.get("options") != {"samples": 1000, "seed": 18446744073709551615}:
    problems.append(f"options echoed as {one.get('options')}")
if one.get("paths") != 2000 or set(one.get("rays", {})) != {"hit", "shadow"}:
    problems.append("paths or rays")
for patch in one.get("patches", []):
    if set(patch) != {"name", "area", "mean_radiosity", "standard_error"}:
        problems.append(f"patch keys {sorted(patch)}")
if [p["name"] for p in one["patches"]] != [p["name"] for p in solve["patches"]]:
    problems.append("patch names or order differ from solve's")
receiver = one["patches"][1]
if not (0.09 < receiver["mean_radiosity"][0] < 0.11 and 0 < receiver["standard_error"][0] < 0.005):
    problems.append(f"receiver {receiver}")
strip = lambda d: {k: v for k, v in d.items() if k != "elapsed_seconds"}
if strip(one) != strip(two):
    problems.append("1 and 2 threads differ")
if strip(one) != strip(written):
    problems.append("--out differs from stdout")
for problem in problems:
    print("FAIL:", problem)
sys.exit(1 if problems else 0)
PY

# solve --verify: the solve JSON gains a verification object against a trace.
expect_status 2 "bad --verify" "--verify 0: out of range" solve cornell --degree 0 --verify 0
expect_status 2 "bad --verify-seed" "--verify-seed x" solve cornell --degree 0 --verify 10 --verify-seed x
expect_status 0 "solve --verify" "" solve cornell --degree 0 --verify 2000 --quiet
if ! "$python" - "$work/out" <<'PY'; then failures=$((failures + 1)); fi
import json, sys
solve = json.load(open(sys.argv[1]))
problems = []
verification = solve.get("verification")
if not isinstance(verification, dict):
    problems.append("no verification object")
    verification = {}
for key in ["samples", "seed", "patches", "worst_relative_difference",
            "worst_difference_in_standard_errors", "mean_absolute_relative_difference"]:
    if key not in verification:
        problems.append(f"verification lacks '{key}'")
if verification.get("samples") != 2000 or verification.get("seed") != 0:
    problems.append("samples or seed not echoed")
patches = verification.get("patches", [])
if [p.get("name") for p in patches] != [p["name"] for p in solve["patches"]]:
    problems.append("verification patches differ from the solve's")
for patch in patches:
    for key in ["mean_radiosity", "standard_error", "relative_difference",
                "difference_in_standard_errors"]:
        if len(patch.get(key, [])) != 3:
            problems.append(f"{patch.get('name')}: {key}")
    solved = next(p["mean_radiosity"] for p in solve["patches"] if p["name"] == patch["name"])
    for c in range(3):
        expected = solved[c] / patch["mean_radiosity"][c] - 1
        if abs(patch["relative_difference"][c] - expected) > 1e-12:
            problems.append(f"{patch['name']}: relative_difference {c}")
worst = verification.get("worst_relative_difference") or {}
largest = max(abs(v) for p in patches for v in p["relative_difference"])
if worst.get("patch") not in [p["name"] for p in patches] or abs(abs(worst.get("value", 0)) - largest) > 1e-15:
    problems.append(f"worst_relative_difference {worst}")
for problem in problems:
    print("FAIL:", problem)
sys.exit(1 if problems else 0)
PY

if [[ $failures -ne 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "all trace CLI checks passed"
