#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs every named rule on the sample
# links of experiments/links/, printing one line per rule and link.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" release
radquad="$root/build/release/experiments/radquad"
"$radquad" rules
for link in "$root"/experiments/links/*.json; do
  echo
  echo "$(basename "$link"):"
  for rule in $("$radquad" rules --json | /usr/bin/python3 -c 'import json,sys; print(" ".join(r["name"] for r in json.load(sys.stdin)))'); do
    "$radquad" link "$link" --rule "$rule" --degree 2 --seed 1 | /usr/bin/python3 -c '
import json, sys
out = json.load(sys.stdin)
print("  %-14s %6d evaluations  form factor %.7f  visible %.3f" % (
    out["rule"], out["kernel_evaluations"], out["form_factor"], out["visible_fraction"]))'
  done
done
