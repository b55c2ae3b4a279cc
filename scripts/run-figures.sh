#!/usr/bin/env bash
# The main job: installs what is missing, builds, and regenerates the committed results and
# plots: Figures 1 and 2 (results/fig1.json, results/fig2.json, plots/fig1.*, plots/fig2.*).
# Extra arguments go to `radquad figures` (e.g. --quick, --gold).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" release
cd "$root"
build/release/experiments/radquad figures "$@"
