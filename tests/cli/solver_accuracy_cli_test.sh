#!/usr/bin/env bash
# The solver's accuracy on the built-in scenes at default settings, against radquad trace
# (2^21 paths per patch, standard errors at most 0.2%): every patch's mean radiosity, every
# channel, within 1% at degrees 2 and 3 and 2% at degree 1 (radquad solve --verify). A ctest
# label of its own, "accuracy" (a few minutes on 2 cores); .ci/run runs it on the release build.
# Usage: RADQUAD=PATH/TO/radquad solver_accuracy_cli_test.sh SCENE DEGREE TOLERANCE
set -u
source "$(dirname "${BASH_SOURCE[0]}")/expect_status.sh"
scene="$2" degree="$3" tolerance="$4"
expect_status 0 "solve $scene --degree $degree --verify" "" \
  solve "$scene" --degree "$degree" --verify 2097152 --quiet
/usr/bin/python3 - "$work/out" "$tolerance" "$scene" "$degree" <<'PY' || failures=$((failures + 1))
import json, sys
out = json.load(open(sys.argv[1]))
tolerance = float(sys.argv[2])
verification = out["verification"]
worst = verification["worst_relative_difference"]
print(f"{sys.argv[3]} degree {sys.argv[4]}: worst {worst['value']:+.4f} ({worst['patch']}, "
      f"{worst['channel']}), mean {verification['mean_absolute_relative_difference']:.4f}, "
      f"solve {out['elapsed_seconds']:.1f} s")
bad = [(p["name"], c, d) for p in verification["patches"]
       for c, d in enumerate(p["relative_difference"]) if d is not None and abs(d) > tolerance]
for name, channel, difference in bad:
    print(f"FAIL: {name} channel {channel}: {difference:+.4f} beyond {tolerance}")
sys.exit(1 if bad else 0)
PY
if [[ $failures -ne 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "accuracy check passed"
