#!/usr/bin/env bash
# Installs missing Debian packages, then configures and builds one CMake preset.
# Usage: scripts/build.sh [PRESET]   (default: release; others: debug, asan)
set -euo pipefail
preset="${1:-release}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/install-deps.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j"$(nproc)"
