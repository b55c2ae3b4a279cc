#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs the default test suite
# (ctest label "unit"; a few minutes at most).
# Usage: scripts/run-tests.sh [PRESET]   (default: release; .ci/run also uses asan)
set -euo pipefail
preset="${1:-release}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" "$preset"
ctest --preset "$preset" -L unit -j"$(nproc)"
