#!/usr/bin/env bash
# `radquad solve` through the real binary: bad scenes exit with status 2 and a message that
# names the patch; a good scene exits 0 with the documented JSON fields.
# Usage: RADQUAD=PATH/TO/radquad solve_cli_test.sh (or the path as the first argument)
set -u
source "$(dirname "${BASH_SOURCE[0]}")/expect_status.sh"

square='"origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0]'
printf '{"patches": [{%s, "reflectance": [0.5,0.5,0.5]' "$square" >"$work/truncated.json"
printf '{"patches": [{%s, "reflectance": [0.5,1.5,0.5], "name": "lamp"}]}' "$square" >"$work/reflectance.json"
printf '{"patches": [{%s, "reflectance": [0.5,0.5,0.5], "emission": [-1,0,0]}]}' "$square" >"$work/emission.json"
printf '{"patches": [{%s}]}' "$square" >"$work/no_reflectance.json"
printf '{"patches": [{"origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [2,0,0], "reflectance": [0,0,0], "name": "flat"}]}' >"$work/degenerate.json"
printf '{"patches": [{%s, "reflectance": [0.5,0.5,0.5], "colour": 1}]}' "$square" >"$work/unknown_key.json"
printf '{"patches": []}' >"$work/empty.json"

expect_status 2 "truncated JSON" "malformed JSON" solve "$work/truncated.json"
expect_status 2 "reflectance above 1" "patches\[0\] (lamp): reflectance" solve "$work/reflectance.json"
expect_status 2 "negative emission" "patches\[0\]" solve "$work/emission.json"
expect_status 2 "missing reflectance" "missing key 'reflectance'" solve "$work/no_reflectance.json"
expect_status 2 "degenerate patch" "patches\[0\] (flat)" solve "$work/degenerate.json"
expect_status 2 "unknown key" "unknown key 'colour'" solve "$work/unknown_key.json"
expect_status 2 "no patches" "no patches" solve "$work/empty.json"
expect_status 2 "no such scene" "not a built-in scene" solve "$work/missing.json"
expect_status 2 "degree out of range" "--degree" solve cornell --degree 4
expect_status 2 "unknown rule choice" "--rules" solve cornell --rules magic
expect_status 2 "no iterations" "--max-iterations" solve cornell --max-iterations 0
expect_status 2 "negative threads" "--threads" solve cornell --threads -1
expect_status 2 "unknown dropped-order treatment" "--dropped-orders alias: unknown" solve cornell --rules adaptive --dropped-orders alias
expect_status 2 "negative kernel curvature" "--kernel-curvature" solve cornell --rules adaptive --kernel-curvature -1
printf '{"patches": [{%s, "reflectance": [0.5,0.5,0.5], "emission": [1,1,1]}]}' "$square" >"$work/lamp.json"
cp "$work/lamp.json" "$work/lamp_copy.json"
expect_status 2 "render over the scene" "is the input" solve "$work/lamp_copy.json" --render "$work/lamp_copy.json"
if ! cmp -s "$work/lamp.json" "$work/lamp_copy.json"; then
  echo "FAIL: --render over the scene changed the scene"; failures=$((failures + 1))
fi
expect_status 2 "render into a missing folder" "does not exist" solve cornell --render "$work/no/such/folder.png"

# Two patches facing the same way that overlap in one plane are refused, naming both (the
# solver would light both); back to back, or side by side, they are legal.
lamp='{"name": "lamp", "origin": [0,0,2], "edge_u": [0,1,0], "edge_v": [1,0,0], "reflectance": [0,0,0], "emission": [1,1,1]}'
floor='{"name": "floor", "origin": [0,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0], "reflectance": [0.5,0.5,0.5]}'
printf '{"patches": [%s, %s, {"name": "floor copy", "origin": [0.5,0.5,0], "edge_u": [1,0,0], "edge_v": [0,1,0], "reflectance": [0.5,0.5,0.5]}]}' "$lamp" "$floor" >"$work/overlap.json"
printf '{"patches": [%s, %s, {"name": "underside", "origin": [0,1,0], "edge_u": [1,0,0], "edge_v": [0,-1,0], "reflectance": [0.5,0.5,0.5]}, {"name": "beside", "origin": [1,0,0], "edge_u": [1,0,0], "edge_v": [0,1,0], "reflectance": [0.5,0.5,0.5]}]}' "$lamp" "$floor" >"$work/legal_neighbours.json"
expect_status 2 "overlapping patches facing the same way" "patches\[1\] (floor) and patches\[2\] (floor copy) face the same way and overlap" solve "$work/overlap.json"
expect_status 0 "back to back and side by side" "" solve "$work/legal_neighbours.json" --degree 0

expect_status 0 "built-in scene with a render" "" solve cornell --degree 0 --render "$work/cornell.png"
for field in kernel_evaluations links elements iterations elapsed_seconds patches mean_radiosity; do
  if ! grep -q "\"$field\"" "$work/out"; then
    echo "FAIL: solve output lacks \"$field\""; failures=$((failures + 1))
  fi
done
if [[ "$(head -c 8 "$work/cornell.png" | od -An -tx1 | tr -d ' \n')" != "89504e470d0a1a0a" ]]; then
  echo "FAIL: --render did not write a PNG"; failures=$((failures + 1))
fi

# A solve that fails ends with exit status 3, the reason on stderr, "converged": false in the
# JSON, and no render: two strips meeting along their long edge integrated without the near
# field create energy; any scene cut off after two iterations has not converged.
cat >"$work/strips.json" <<'JSON'
{"patches": [
 {"name": "strip a", "origin": [0,0,0], "edge_u": [0,0,0.05], "edge_v": [2,0,0], "reflectance": [0.7,0.7,0.7]},
 {"name": "strip b", "origin": [0,0,0], "edge_u": [2,0,0], "edge_v": [0,0.05,0], "reflectance": [0.7,0.7,0.7]},
 {"name": "lamp", "origin": [0,1,0], "edge_u": [2,0,0], "edge_v": [0,0,1], "reflectance": [0,0,0], "emission": [1,1,1]}
]}
JSON
expect_status 3 "energy-creating solve" "computation failed" solve "$work/strips.json" --no-near-field --render "$work/diverged.png"
if ! grep -q '"converged": false' "$work/out"; then
  echo "FAIL: a diverged solve's JSON lacks \"converged\": false"; failures=$((failures + 1))
fi
if [[ -e "$work/diverged.png" ]]; then
  echo "FAIL: a diverged solve wrote its render"; failures=$((failures + 1))
fi
expect_status 3 "iteration cap" "no convergence within 2 iterations" solve cornell --max-iterations 2
# Refinement budgets: the solve stops with a message naming the budget (exit 3).
expect_status 3 "element budget" "element budget (200 elements) was reached" solve cornell --max-elements 200
expect_status 3 "link budget" "link budget (500 links) was reached" solve cornell --max-links 500
expect_status 2 "zero element budget" "--max-elements" solve cornell --max-elements 0
expect_status 3 "initial link budget" "link budget (100 links) was reached during the initial linking (patch 9 of 17)" solve cornell --max-links 100
# The memory budget: any process holds more than 1 MiB once the scene is linked.
expect_status 3 "memory budget" "memory budget (1 MiB) was reached during the initial linking" solve cornell --max-memory 1
expect_status 2 "zero memory budget" "--max-memory" solve cornell --max-memory 0
expect_status 0 "strips in the near field" "" solve "$work/strips.json" --degree 2

if [[ $failures -ne 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "all solve CLI checks passed"
