#!/bin/bash
# Regression bounds in CI (docs/cli.md, "Regression bounds"): every registered rule, scored on
# the four quick suites, lies inside the committed bands of tests/baselines/quick/ (radquad
# check exits 0); a 5% bias in the weights, or one point moved by 0.05, of FullGauss,
# LinSrcGauss, Stroud65 or HierStroud makes the check fail (exit 1, naming the rule); bad
# input exits 2 (another suite's table, other links, not a table); JUnit XML is written;
# `baseline --rules` replaces only the named rules' bands.
set -u
radquad="$1"
root="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

all=$("$radquad" rules --json | /usr/bin/python3 -c "import json, sys; print(','.join(r['name'] for r in json.load(sys.stdin)))")
for suite in fig1 fig2 fig1-scene fig2-scene; do
  "$radquad" study "$root/experiments/configs/$suite-quick.json" --rules "$all" --out "$work/$suite.json" --quiet ||
    fail "$suite: study exit status $?"
  "$radquad" check "$work/$suite.json" --baseline "$root/tests/baselines/quick/$suite.json" \
    --junit "$work/$suite.xml" > "$work/$suite.check"
  status=$?
  if [[ $status -ne 0 ]]; then fail "$suite: check exit status $status"; cat "$work/$suite.check"; fi
  grep -q "bounds hold" "$work/$suite.check" || fail "$suite: no summary line"
  grep -q '<testsuite name="'"$suite"'"' "$work/$suite.xml" || fail "$suite: no JUnit XML"
done

# Injected faults, scored on fig2-quick's links: each faulty rule's entries replace the true
# rule's in the table (under its name), and the check must fail on that rule.
for rule in FullGauss LinSrcGauss Stroud65 HierStroud; do
  "$radquad" rules --dump "$rule" > "$work/$rule.rule.json" || fail "dump $rule"
done
/usr/bin/python3 - "$work" <<'PY' || fail "writing the faulty rules"
import json, sys
work = sys.argv[1]
def bias(part):   # the first half of the weights 5% up, the rest scaled to keep the sum 1
    w = part["weights"]; h = len(w) // 2
    up = [x * 1.05 for x in w[:h]]
    part["weights"] = up + [x * (1.0 - sum(up)) / sum(w[h:]) for x in w[h:]]
def move(part):   # one point moved by 0.05 along its first coordinate
    p = part["points"][0]; p[0] = p[0] + 0.05 if p[0] < 0.9 else p[0] - 0.05
for rule in ("FullGauss", "LinSrcGauss", "Stroud65", "HierStroud"):
    for kind, change in (("bias", bias), ("point", move)):
        d = json.load(open(f"{work}/{rule}.rule.json"))
        d["degree"] = None  # no longer exact to its degree
        change(d if "points" in d else d["source"])
        d["name"] = f"{rule}-{kind}"
        json.dump(d, open(f"{work}/{rule}-{kind}.json", "w"))
PY
faulty=""
for rule in FullGauss LinSrcGauss Stroud65 HierStroud; do
  for kind in bias point; do faulty="$faulty${faulty:+,}File:$work/$rule-$kind.json"; done
done
"$radquad" study "$root/experiments/configs/fig2-quick.json" --rules "$faulty" --out "$work/faulty.json" --quiet ||
  fail "faulty study: exit status $?"
/usr/bin/python3 - "$work" <<'PY' || fail "composing the faulty tables"
import copy, json, sys
work = sys.argv[1]
clean, faulty = json.load(open(f"{work}/fig2.json")), json.load(open(f"{work}/faulty.json"))
for rule in ("FullGauss", "LinSrcGauss", "Stroud65", "HierStroud"):
    for kind in ("bias", "point"):
        table = copy.deepcopy(clean)
        for name, part in table["classes"].items():
            bad = next(r for r in faulty["classes"][name]["rules"] if r["name"] == f"{rule}-{kind}")
            part["rules"] = [dict(bad, name=rule) if r["name"] == rule else r for r in part["rules"]]
        json.dump(table, open(f"{work}/{rule}-{kind}.table.json", "w"))
PY
for rule in FullGauss LinSrcGauss Stroud65 HierStroud; do
  for kind in bias point; do
    "$radquad" check "$work/$rule-$kind.table.json" --baseline "$root/tests/baselines/quick/fig2.json" \
      > "$work/$rule-$kind.check"
    status=$?
    [[ $status -eq 1 ]] || fail "$rule $kind: check exit status $status, expected 1"
    grep -q "^FAIL $rule " "$work/$rule-$kind.check" || fail "$rule $kind: the failure does not name $rule"
    if grep "^FAIL" "$work/$rule-$kind.check" | grep -qv "^FAIL $rule "; then
      fail "$rule $kind: another rule failed too"
    fi
  done
done

# Scores that disappear fail their bands (exit 1): a rule dropped from one class only, a
# metric dropped from one rule, a score that was not finite (written as null).
/usr/bin/python3 - "$work" <<'PY' || fail "writing the tables with missing scores"
import json, sys
work = sys.argv[1]
table = json.load(open(f"{work}/fig2.json"))
one_class = json.loads(json.dumps(table))
one_class["classes"]["partial"]["rules"] = [
    r for r in one_class["classes"]["partial"]["rules"] if r["name"] != "HierStroud"]
json.dump(one_class, open(f"{work}/one_class.json", "w"))
no_metric = json.loads(json.dumps(table))
del no_metric["classes"]["unoccluded"]["rules"][0]["relative_frobenius_error_vs_gold"]
json.dump(no_metric, open(f"{work}/no_metric.json", "w"))
not_finite = json.loads(json.dumps(table))
not_finite["classes"]["partial"]["rules"][1]["l1_error_bound_vs_gold"]["total"] = None
json.dump(not_finite, open(f"{work}/not_finite.json", "w"))
PY
for case in one_class:HierStroud no_metric:FullGauss not_finite:LinSrcGauss; do
  name=${case%%:*}; rule=${case#*:}
  "$radquad" check "$work/$name.json" --baseline "$root/tests/baselines/quick/fig2.json" > "$work/$name.check"
  status=$?
  [[ $status -eq 1 ]] || fail "$name: check exit status $status, expected 1"
  grep -q "^FAIL $rule .*not in the table, or not finite" "$work/$name.check" || {
    fail "$name: no failure naming $rule's missing score"; cat "$work/$name.check"; }
done

# Bad input: another suite's table, other links, not a table (exit 2, naming the problem).
expect_input_error() {  # name, table, baseline, text the message must contain
  "$radquad" check "$2" --baseline "$3" > /dev/null 2> "$work/$1.err"
  local status=$?
  [[ $status -eq 2 ]] || fail "$1: exit status $status, expected 2"
  grep -q -- "$4" "$work/$1.err" || { fail "$1: message lacks '$4'"; cat "$work/$1.err"; }
}
expect_input_error other_suite "$work/fig1.json" "$root/tests/baselines/quick/fig2.json" "not the suite of"
/usr/bin/python3 -c "
import json, sys
t = json.load(open(sys.argv[1])); t['classes']['partial']['per_link'][0]['candidate'] += 100000
json.dump(t, open(sys.argv[2], 'w'))" "$work/fig2.json" "$work/other_links.json"
expect_input_error other_links "$work/other_links.json" "$root/tests/baselines/quick/fig2.json" "the links"
/usr/bin/python3 -c "
import json, sys
t = json.load(open(sys.argv[1])); t['classes']['partial']['per_link'][0] = 5
json.dump(t, open(sys.argv[2], 'w'))" "$work/fig2.json" "$work/bad_per_link.json"
expect_input_error bad_per_link "$work/bad_per_link.json" "$root/tests/baselines/quick/fig2.json" "no integer candidate"
printf '[1, 2]' > "$work/array.json"
expect_input_error not_a_table "$work/array.json" "$root/tests/baselines/quick/fig2.json" "not a study table"
expect_input_error not_a_baseline "$work/fig2.json" "$work/fig2.json" "not a radquad baseline"

# baseline --rules: only the named rule's bands change; the table must be of the same suite.
cp "$root/tests/baselines/quick/fig2.json" "$work/partial.json"
"$radquad" baseline "$work/FullGauss-bias.table.json" --out "$work/partial.json" --rules FullGauss ||
  fail "baseline --rules: exit status $?"
/usr/bin/python3 - "$root/tests/baselines/quick/fig2.json" "$work/partial.json" <<'PY' || fail "baseline --rules changed other rules or not FullGauss"
import json, sys
before, after = (json.load(open(p)) for p in sys.argv[1:3])
assert after["rules"]["FullGauss"] != before["rules"]["FullGauss"]
for name in before["rules"]:
    if name != "FullGauss":
        assert after["rules"][name] == before["rules"][name], name
PY
"$radquad" check "$work/FullGauss-bias.table.json" --baseline "$work/partial.json" > /dev/null ||
  fail "check after re-baselining FullGauss: exit status $?"
"$radquad" baseline "$work/fig1.json" --out "$work/partial.json" --rules FullGauss 2> "$work/mixed.err"
[[ $? -eq 2 ]] && grep -q "different suite" "$work/mixed.err" || fail "baseline --rules over another suite's baseline"

[[ $failures -eq 0 ]] && echo "check CLI: all checks passed"
exit $((failures > 0))
