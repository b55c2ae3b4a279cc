#!/usr/bin/env bash
# The main job: installs what is missing, builds, and regenerates every committed result:
# Figures 1 and 2 (`radquad figures`: results/fig1.json, results/fig2.json, plots/fig1.*,
# plots/fig2.*) and the adaptive method's savings and Plate 1 (`radquad adaptive`:
# results/adaptive.json, results/plate1.png, plots/adaptive.png), and the solver's accuracy
# against the path tracer on the built-in scenes (scripts/solver_accuracy.py:
# results/solver_accuracy.json), and docs/results.md, every table of these results
# (plots/results_md.py). About 6 minutes on 2 cores once built.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" release
cd "$root"
build/release/experiments/radquad figures
build/release/experiments/radquad adaptive
/usr/bin/python3 scripts/solver_accuracy.py
/usr/bin/python3 plots/results_md.py --results results --out docs/results.md
