#!/bin/bash
# `radquad study` on bad input: a message naming the file and the problem, exit status 2, and
# no output file. On good input: a table with the contract's fields, written whole.
set -u
radquad="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

expect_input_error() {  # name, config text, text the message must contain
  printf '%s' "$2" > "$work/$1.json"
  "$radquad" study "$work/$1.json" --out "$work/$1.out" --quiet 2> "$work/$1.err"
  local status=$?
  if [[ $status -ne 2 ]]; then echo "FAIL $1: exit status $status, expected 2"; failures=$((failures + 1)); fi
  if ! grep -q -- "$3" "$work/$1.err"; then echo "FAIL $1: message lacks '$3':"; cat "$work/$1.err"; failures=$((failures + 1)); fi
  if ! grep -q -- "$1.json" "$work/$1.err"; then echo "FAIL $1: message does not name the file"; failures=$((failures + 1)); fi
  if [[ -e "$work/$1.out" ]]; then echo "FAIL $1: wrote an output file"; failures=$((failures + 1)); fi
}

expect_input_error unknown_key '{"figure": "fig1", "seed": 1, "classes": {"partial": 2}, "rules": ["FullGauss"], "colour": 3}' "unknown key 'colour'"
expect_input_error unknown_rule '{"figure": "fig1", "seed": 1, "classes": {"partial": 2}, "rules": ["Nope"]}' "unknown rule 'Nope'"
expect_input_error missing_seed '{"figure": "fig1", "classes": {"partial": 2}, "rules": ["FullGauss"]}' "missing key 'seed'"
expect_input_error malformed '{"figure": ' "malformed JSON"

printf '%s' '{"figure": "fig2", "seed": 4, "classes": {"unoccluded": 2, "partial": 2}, "rules": ["FullGauss", "MonteCarlo"], "trials": 2, "reference": {"replicates": 2}}' > "$work/good.json"
if ! "$radquad" study "$work/good.json" --out "$work/good.out" --quiet; then
  echo "FAIL good: nonzero exit status"; failures=$((failures + 1))
else
  for field in '"schema"' '"options"' '"reference"' '"classes"' '"per_source_function"' '"l1_error_bound"'; do
    grep -q -- "$field" "$work/good.out" || { echo "FAIL good: no $field"; failures=$((failures + 1)); }
  done
  # What changes from run to run is in the run record beside the table, not in the table.
  for field in '"git_commit"' '"elapsed_seconds"'; do
    grep -q -- "$field" "$work/good.out" && { echo "FAIL good: $field in the table"; failures=$((failures + 1)); }
    grep -q -- "$field" "$work/good.run.json" || { echo "FAIL good: no $field in the run record"; failures=$((failures + 1)); }
  done
fi
# Scored against the gold by default (its options and the gold scores in the table, the
# study's gold defaults where the config gives none); --no-gold scores against the paper's
# reference only.
"$radquad" study "$work/good.json" --out "$work/nogold.out" --no-gold --quiet ||
  { echo "FAIL --no-gold: exit status $?"; failures=$((failures + 1)); }
/usr/bin/python3 - "$work/good.out" "$work/nogold.out" <<'PY' || failures=$((failures + 1))
import json, sys
gold, plain = (json.load(open(path)) for path in sys.argv[1:3])
assert gold["gold"]["options"]["exact_tolerance"] == 3e-4, gold["gold"]["options"]
assert gold["gold"]["noise_check"]["holds"] in (True, False)
assert "l1_error_bound_vs_gold" in gold["classes"]["partial"]["rules"][0], "no gold scores by default"
assert "gold" not in plain, "--no-gold still scored against the gold"
assert "l1_error_bound_vs_gold" not in plain["classes"]["partial"]["rules"][0]
PY
# The per-link table: one JSON line per scored link (4 here), written beside the table.
if ! "$radquad" study "$work/good.json" --out "$work/links.out" --links-out "$work/links.jsonl" --quiet; then
  echo "FAIL links-out: nonzero exit status"; failures=$((failures + 1))
else
  lines=$(wc -l < "$work/links.jsonl")
  [[ $lines -eq 4 ]] || { echo "FAIL links-out: $lines lines, expected 4"; failures=$((failures + 1)); }
  for field in '"receiver"' '"source"' '"occluders"' '"reference"' '"rules"' '"standard_deviation"'; do
    grep -q -- "$field" "$work/links.jsonl" || { echo "FAIL links-out: no $field"; failures=$((failures + 1)); }
  done
fi
"$radquad" study "$work/good.json" --out "$work/same.out" --links-out "$work/same.out" --quiet 2> "$work/same.err"
status=$?
if [[ $status -ne 2 ]] || ! grep -q -- "--links-out" "$work/same.err"; then
  echo "FAIL links-out over --out: exit status $status"; cat "$work/same.err"; failures=$((failures + 1))
fi
[[ -e "$work/same.out" ]] && { echo "FAIL links-out over --out: wrote a file"; failures=$((failures + 1)); }

# Overrides: --rules and --seed replace the config's (and the table's options say so); the
# table is the same for one thread and two; an unknown rule is refused before any work.
for threads in 1 2; do
  "$radquad" study "$work/good.json" --out "$work/over$threads.out" --rules FullGauss,Stratified \
    --seed 77 --threads $threads --quiet || { echo "FAIL overrides: exit status $?"; failures=$((failures + 1)); }
done
/usr/bin/python3 - "$work/over1.out" "$work/over2.out" <<'PY' || failures=$((failures + 1))
import json, sys
one, two = (json.load(open(path)) for path in sys.argv[1:3])
assert one["options"]["seed"] == 77 and one["options"]["rules"] == ["FullGauss", "Stratified"], one["options"]
assert [rule["name"] for rule in one["classes"]["partial"]["rules"]] == ["FullGauss", "Stratified"]
assert one == two, "the table depends on the thread count"
PY
cmp -s "$work/over1.out" "$work/over2.out" ||
  { echo "FAIL overrides: the table files differ between 1 and 2 threads"; failures=$((failures + 1)); }
"$radquad" study "$work/good.json" --out "$work/nope.out" --rules FullGauss,Nope --quiet 2> "$work/nope.err"
status=$?
if [[ $status -ne 2 ]] || ! grep -q "unknown rule 'Nope'" "$work/nope.err"; then
  echo "FAIL unknown override rule: exit status $status"; cat "$work/nope.err"; failures=$((failures + 1))
fi
[[ -e "$work/nope.out" ]] && { echo "FAIL unknown override rule: wrote a file"; failures=$((failures + 1)); }
"$radquad" figures --quick --rules Nope --results "$work/figures" --plots "$work/plots" --quiet 2> "$work/figures.err"
status=$?
if [[ $status -ne 2 ]] || [[ -e "$work/figures" ]]; then
  echo "FAIL figures with an unknown rule: exit status $status, or it made its folders"; failures=$((failures + 1))
fi

[[ $failures -eq 0 ]] && echo "study CLI: all checks passed"
exit $((failures > 0))
