#!/usr/bin/env bash
# The libFuzzer harnesses (tests/fuzz/README.md): builds the `fuzz` preset with clang and
# runs every harness for a fixed number of inputs from a fixed seed, on a scratch copy of its
# committed corpus, so a run is reproducible. Any crash, sanitizer report, non-finite result
# or unexpected exception fails the run (libFuzzer writes the input to crash-*).
# Usage: scripts/run-fuzz.sh [RUNS] [HARNESS...]   (RUNS per harness, default 300000)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs="${1:-300000}"
shift || true
harnesses=("$@")
if [ "${#harnesses[@]}" -eq 0 ]; then
  harnesses=(link_loader scene_loader study_config rule_name link_integration rule_file npy_array)
fi
if ! command -v clang++ >/dev/null; then
  echo "run-fuzz: clang++ not found; the fuzz harnesses need clang (Debian package clang)" >&2
  exit 2
fi
"$root/scripts/install-deps.sh"
cd "$root"
cmake --preset fuzz >/dev/null
cmake --build build/fuzz -j"$(nproc)"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
for harness in "${harnesses[@]}"; do
  corpus="$root/tests/fuzz/corpus/$harness"
  work="$scratch/$harness"
  mkdir -p "$work"
  cp -r "$corpus/." "$work/"
  echo "== fuzz $harness: $runs inputs, seed 1 =="
  status=0
  (cd "$scratch" && "$root/build/fuzz/tests/fuzz/${harness}_fuzz" -runs="$runs" -seed=1 \
     -max_len=4096 -timeout=10 -rss_limit_mb=4096 -max_total_time="${RADQUAD_FUZZ_SECONDS:-120}" \
     -print_final_stats=1 "$work") \
    >"$scratch/$harness.log" 2>&1 || status=$?
  grep -E "^(Done|stat::number_of_executed_units|stat::average_exec_per_sec|==[0-9]+==ERROR|SUMMARY)" \
    "$scratch/$harness.log" || true
  if [ "$status" -ne 0 ]; then
    tail -40 "$scratch/$harness.log" >&2
    echo "run-fuzz: $harness failed (status $status); the input is in $scratch/crash-*" >&2
    trap - EXIT
    exit 1
  fi
done
