#!/usr/bin/env bash
# The adaptive rules' accuracy target at the default ErrThres: every patch's mean radiosity,
# every channel, within 1% of the fixed rules' solution, with and without the
# partial-visibility step (radquad solve --compare, at the BF threshold of
# results/adaptive.json). The fixed solution is the yardstick: the two differ only in the
# source points each link gets. Label "accuracy" (.ci/run runs it on the release build).
# Usage: RADQUAD=PATH/TO/radquad adaptive_accuracy_cli_test.sh "" SCENE DEGREE
set -u
source "$(dirname "${BASH_SOURCE[0]}")/expect_status.sh"
scene="$2" degree="$3"
for rules in adaptive adaptive-novis; do
  expect_status 0 "solve $scene --degree $degree --rules $rules --compare" "" \
    solve "$scene" --degree "$degree" --rules "$rules" --bf-eps 0.1 --compare --quiet
  /usr/bin/python3 - "$work/out" "$scene" "$degree" "$rules" <<'PY' || failures=$((failures + 1))
import json, sys
out = json.load(open(sys.argv[1]))
if not out["converged"]:
    print(f"FAIL: {sys.argv[2]} degree {sys.argv[3]} {sys.argv[4]}: not converged")
    sys.exit(1)
comparison = out["comparison"]
worst = comparison["largest_patch_difference"]
print(f"{sys.argv[2]} degree {sys.argv[3]} {sys.argv[4]}: worst patch {worst['value']:+.4f} "
      f"({worst['patch']}, {worst['channel']}), L2 {comparison['relative_l2_difference']:.4f}, "
      f"{comparison['evaluation_ratio']:.2f}x fewer kernel evaluations")
if not abs(worst["value"]) < 0.01:
    print(f"FAIL: beyond 1% of the fixed rules")
    sys.exit(1)
PY
done
if [[ $failures -ne 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "adaptive accuracy check passed"
