#!/usr/bin/env bash
# plots/results_md.py on the committed results: docs/results.md is what it writes from them
# (so the committed file is not edited by hand), and its tables carry the JSON's values.
# Usage: results_md_test.sh SOURCE_DIR
set -u
root="$1"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
/usr/bin/python3 "$root/plots/results_md.py" --results "$root/results" --out "$scratch/results.md" || {
  echo "FAILED: results_md.py exited with $?"; exit 1; }
if ! cmp -s "$scratch/results.md" "$root/docs/results.md"; then
  echo "FAILED: docs/results.md differs from what plots/results_md.py writes from results/:"
  diff "$scratch/results.md" "$root/docs/results.md" | head -20
  exit 1
fi
/usr/bin/python3 - "$root/results" "$scratch/results.md" <<'PY'
import json, sys
results, text = sys.argv[1], open(sys.argv[2]).read()
fig1 = json.load(open(f"{results}/fig1.json"))
for rule in fig1["rules"]:
    row = f"| {rule['name']} | {rule['samples']} | {rule['relative_error']['mean']:.3g} |"
    assert row in text, row
fig2 = json.load(open(f"{results}/fig2.json"))
for rule in fig2["classes"]["partial"]["rules"]:
    row = f"| {rule['name']} | {rule['l1_error_bound']['total']:.3g} |"
    assert row in text, row
claims = json.load(open(f"{results}/claims.json"))
assert f"| Figure 1: Stratified best | {claims['fig1_stratified_best']['verdict']} |" in text
PY
status=$?
[ $status -eq 0 ] && echo "results_md: all checks passed"
exit $status
