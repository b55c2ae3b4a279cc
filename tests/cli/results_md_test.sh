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
# Tables scored against the gold (the default) are shown against it.
fig1 = json.load(open(f"{results}/fig1.json"))
key = "relative_error_vs_gold" if "relative_error_vs_gold" in fig1["rules"][0] else "relative_error"
for rule in fig1["rules"]:
    row = f"| {rule['name']} | {rule['samples']} | {rule[key]['mean']:.3g} |"
    assert row in text, row
fig2 = json.load(open(f"{results}/fig2.json"))
key = "l1_error_bound_vs_gold" if "l1_error_bound_vs_gold" in fig2["classes"]["partial"]["rules"][0] else "l1_error_bound"
for rule in fig2["classes"]["partial"]["rules"]:
    row = f"| {rule['name']} | {rule[key]['total']:.3g} |"
    assert row in text, row
claims = json.load(open(f"{results}/claims.json"))
assert f"| Figure 1: Stratified best | {claims['fig1_stratified_best']['verdict']} |" in text
PY
status=$?
[ $status -eq 0 ] && echo "results_md: all checks passed"
exit $status
