#!/usr/bin/env bash
# Command-line behaviour of the real `radquad` binary: good runs print the documented JSON,
# bad input prints a message naming the input on stderr and exits with status 2.
# Usage: RADQUAD=path/to/radquad cli_test.sh FIXTURE_DIR
set -u
fixtures="$1"
radquad="${RADQUAD:?set RADQUAD to the radquad binary}"
python=/usr/bin/python3
passed=0
failed=0
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

check() {  # check NAME CONDITION_STATUS
  if [ "$2" -eq 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAILED: $1"; fi
}

# expect_error NAME FRAGMENT ARGS... : exit status 2 and FRAGMENT on stderr.
expect_error() {
  local name="$1" fragment="$2"
  shift 2
  "$radquad" "$@" >"$scratch/out" 2>"$scratch/err"
  local status=$?
  if [ "$status" -ne 2 ]; then
    echo "$name: exit status $status, expected 2"; check "$name" 1; return
  fi
  if ! grep -qF -- "$fragment" "$scratch/err"; then
    echo "$name: stderr lacks '$fragment':"; cat "$scratch/err"; check "$name" 1; return
  fi
  if [ -s "$scratch/out" ]; then
    echo "$name: printed on stdout despite the error"; check "$name" 1; return
  fi
  check "$name" 0
}

# --version: the project's version from CMakeLists.txt, the commit (40 hex digits, possibly
# "-modified", or "unknown" outside a git checkout) and the build flavour; exit 0.
version_line=$("$radquad" --version)
check version $?
project_version=$(sed -n 's/^project(radquad VERSION \([0-9.]*\).*/\1/p' "$fixtures/../../CMakeLists.txt")
echo "$version_line" | grep -Eq "^radquad ${project_version//./\\.} \(commit ([0-9a-f]{40}(-modified)?|unknown), (native|portable) build\)$"
check "version line '$version_line' (project version $project_version)" $?

expect_error malformed_json "malformed.json: malformed JSON" link "$fixtures/malformed.json" --rule FullGauss
# Limits: input files are read up to a cap (RADQUAD_MAX_INPUT_BYTES, default 256 MiB), a
# device without end included; trials are capped.
RADQUAD_MAX_INPUT_BYTES=100 expect_error input_cap "larger than the input limit of 100 bytes" link "$fixtures/good_link.json" --rule FullGauss
RADQUAD_MAX_INPUT_BYTES=1000000 expect_error endless_input "/dev/zero: larger than the input limit" link /dev/zero --rule FullGauss
RADQUAD_MAX_INPUT_BYTES=-5 expect_error bad_input_cap "RADQUAD_MAX_INPUT_BYTES: expected a positive decimal integer" link "$fixtures/good_link.json" --rule FullGauss
expect_error trials_cap "--trials" link "$fixtures/good_link.json" --rule MonteCarlo --trials 2147483647
expect_error unknown_key "unknown key 'normal'" link "$fixtures/unknown_key.json" --rule FullGauss
expect_error wrong_length "receiver.origin: expected an array of 3 numbers" link "$fixtures/wrong_length.json" --rule FullGauss
expect_error non_finite "non_finite.json: non-finite number" link "$fixtures/non_finite.json" --rule FullGauss
expect_error zero_area "source: degenerate patch" link "$fixtures/zero_area.json" --rule FullGauss
# Beyond float range Embree cannot trace (found by link_integration_fuzz: an abort in Embree).
expect_error huge_coordinate "source: a corner lies beyond the coordinate limit of 1e15" link "$fixtures/huge_coordinate.json" --rule FullGauss
expect_error missing_key "missing key 'source'" link "$fixtures/missing_source.json" --rule FullGauss
expect_error bad_occluder "occluders[1]: degenerate patch" link "$fixtures/bad_occluders.json" --rule FullGauss
expect_error crossing_patches "crossing_patches.json: receiver and source cross each other" link "$fixtures/crossing_patches.json" --rule FullGauss --degree 1
expect_error coincident_patches "coincident_patches.json: receiver and source overlap" link "$fixtures/coincident_patches.json" --rule FullGauss
expect_error duplicate_key "duplicate_key.json: duplicate key 'source'" link "$fixtures/duplicate_key.json" --rule FullGauss
expect_error negative_seed "--seed -1: expected a decimal integer" link "$fixtures/good_link.json" --rule MonteCarlo --seed -1
expect_error seed_overflow "the last seed would pass 2^64 - 1" link "$fixtures/good_link.json" --rule MonteCarlo --seed 18446744073709551615 --trials 2
expect_error exponent_seed "--seed 1e3: expected a decimal integer" reference "$fixtures/good_link.json" --seed 1e3
expect_error unknown_command "unknown command 'frobnicate'" frobnicate
cp "$fixtures/good_link.json" "$scratch/config_copy.json"
expect_error study_over_its_config "is the input" study "$scratch/config_copy.json" --out "$scratch/config_copy.json"
if ! cmp -s "$fixtures/good_link.json" "$scratch/config_copy.json"; then
  echo "study_over_its_config: the input was changed"; check study_input_kept 1
fi
expect_error missing_file "no_such_file.json: cannot open" link "$fixtures/no_such_file.json" --rule FullGauss
expect_error unknown_rule "unknown rule 'NoSuchRule'; valid rules: FullGauss" link "$fixtures/good_link.json" --rule NoSuchRule
expect_error bad_gauss_form "expected Gauss:RsxRtxSuxSv" link "$fixtures/good_link.json" --rule Gauss:3x3
expect_error bad_degree "basis degree 9 is out of range" link "$fixtures/good_link.json" --rule FullGauss --degree 9
expect_error missing_rule "--rule is required" link "$fixtures/good_link.json"
expect_error unknown_option "--bogus" link "$fixtures/good_link.json" --rule FullGauss --bogus
expect_error no_command "subcommand" 
expect_error figures_unwritable "cannot create the folder" figures --quick --quiet --results /proc/radquad-results
expect_error adaptive_unwritable "cannot create the folder" adaptive --quiet --plots /proc/radquad-plots

# A near-singular link (opposed unit squares 0.01 apart): FullGauss's form factor is far above
# 1; the output says so in "warnings" and on stderr.
"$radquad" link "$fixtures/near_singular.json" --rule FullGauss >"$scratch/near.json" 2>"$scratch/err"
check near_singular_status $?
grep -q "near-singular link" "$scratch/err"; check near_singular_stderr $?
"$python" - "$scratch/near.json" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
assert out["form_factor"] > 1.0
assert any("near-singular" in w for w in out["warnings"]), out.get("warnings")
assert any("outside [0, 1]" in w for w in out["warnings"]), out.get("warnings")
PY
check near_singular_warnings $?
# The paper's reference on it: its standard error is flagged as unreliable (the kernel's
# variance is unbounded there), with the warning on stderr; on a link far from singular it
# is reliable and there is no warning.
"$radquad" reference "$fixtures/near_singular.json" >"$scratch/near_reference.json" 2>"$scratch/err"
check near_singular_reference_status $?
grep -q "near-singular link" "$scratch/err"; check near_singular_reference_stderr $?
"$radquad" reference "$fixtures/good_link.json" >"$scratch/good_reference.json" 2>/dev/null
"$python" - "$scratch/near_reference.json" "$scratch/good_reference.json" <<'PY'
import json, sys
near, good = (json.load(open(path)) for path in sys.argv[1:3])
assert near["standard_error"]["reliable"] is False
assert any("near-singular" in w for w in near["warnings"]), near.get("warnings")
assert good["standard_error"]["reliable"] is True and "warnings" not in good
PY
check near_singular_reference_flagged $?

# Options: an empty value is refused (not read as absent), numbers must be finite, outputs
# must be creatable (a virtual file system is refused before any work) and never replace a
# device or a pipe; the plotting interpreter is checked before any work.
expect_error empty_out "--out: an empty value" study "$fixtures/good_link.json" --out ""
expect_error empty_render "--render: an empty value" solve cornell --render ""
expect_error infinite_tolerance "--tolerance: not a finite number: inf" solve cornell --tolerance inf
expect_error nan_gold_tolerance "--gold-tolerance: not a finite number: nan" reference "$fixtures/good_link.json" --gold --gold-tolerance nan
expect_error out_in_sysfs "--out /sys/radquad.json: cannot write in /sys" trace cornell --samples 16 --out /sys/radquad.json
mkfifo "$scratch/fifo"
expect_error out_is_a_pipe "not a regular file (a device, a pipe or a socket)" trace cornell --samples 16 --out "$scratch/fifo"
[ -p "$scratch/fifo" ]; check pipe_kept $?
expect_error trace_threads "--threads: Value 99999 not in range" trace cornell --threads 99999
expect_error figures_python "--python /no/such/python: cannot run it" figures --quick --quiet --python /no/such/python --results "$scratch/fig_results" --plots "$scratch/fig_plots"
[ ! -e "$scratch/fig_results" ]; check figures_python_wrote_nothing $?
# A plot that fails in the background (an interpreter that imports matplotlib but fails on
# one table) fails the command, naming that table, once every suite is written.
cat >"$scratch/failing_python" <<'SH'
#!/bin/sh
[ "$1" = "-c" ] && exit 0
status=0
while read -r stem; do
  if [ "$stem" = fig2-scene ]; then echo "failed $stem"; status=1; else echo "drawn $stem"; fi
done
exit $status
SH
chmod +x "$scratch/failing_python"
expect_error figures_plot_fails "plots/figures.py failed on $scratch/fig_results/fig2-scene.json" figures --quick --quiet --no-gold --rules FullGauss,Stratified,MonteCarlo,NRook --python "$scratch/failing_python" --results "$scratch/fig_results" --plots "$scratch/fig_plots"
missing=0
for table in fig1 fig2 fig1-scene fig2-scene claims; do
  [ -s "$scratch/fig_results/$table.json" ] || { echo "figures_plot_fails: $table.json missing"; missing=1; }
done
check figures_plot_fails_kept_the_tables $missing
# An interpreter that stops before drawing anything (its matplotlib cannot draw) names the
# first table and says what to check.
cat >"$scratch/dying_python" <<'SH'
#!/bin/sh
[ "$1" = "-c" ] && exit 0
exit 1
SH
chmod +x "$scratch/dying_python"
expect_error figures_plot_dies "plots/figures.py failed on $scratch/fig_results2/fig1-scene.json (is matplotlib installed for $scratch/dying_python?)" figures --quick --quiet --no-gold --rules FullGauss,Stratified,MonteCarlo,NRook --python "$scratch/dying_python" --results "$scratch/fig_results2" --plots "$scratch/fig_plots2"
expect_error sample_budget "exceed the budget of 1e10 kernel evaluations per link" link "$fixtures/good_link.json" --rule MonteCarlo:10000000 --trials 100000
expect_error input_is_a_folder "is a folder" link "$fixtures" --rule FullGauss

# A good run: the documented keys, a 9x9 coupling at degree 2, half the rays blocked (the
# fixture's blocker covers half of the mid plane; Gauss:4x4x3x3 is symmetric about it).
"$radquad" link "$fixtures/good_link.json" --rule Gauss:4x4x3x3 --degree 2 >"$scratch/good.json" 2>"$scratch/err"
check good_run_status $?
"$python" - "$scratch/good.json" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
for key in ("rule", "samples", "degree", "kernel_evaluations", "form_factor", "coupling", "visible_fraction"):
    assert key in out, key
assert out["rule"] == "Gauss:4x4x3x3" and out["samples"] == 144 and out["degree"] == 2
assert out["kernel_evaluations"] == 144
assert len(out["coupling"]) == 9 and all(len(row) == 9 for row in out["coupling"])
assert out["visible_fraction"] == 0.5, out["visible_fraction"]
assert abs(out["coupling"][0][0] - out["form_factor"]) < 1e-15  # unit squares: K00 = F
PY
check good_run_json $?

"$radquad" rules --json >"$scratch/rules.json"
check rules_status $?
"$python" - "$scratch/rules.json" <<'PY'
import json, sys
rules = json.load(open(sys.argv[1]))
names = {r["name"]: r for r in rules}
for name, samples in (("FullGauss", 81), ("LinSrcGauss", 36), ("ConstSrcGauss", 9)):
    assert names[name]["samples"] == samples, name
for r in rules:
    assert set(r) >= {"name", "samples", "degree", "family", "citation"}, r
PY
check rules_json $?

# Trials of a random rule: T runs with seeds S..S+T-1, their mean and standard deviation.
"$radquad" link "$fixtures/good_link.json" --rule Stratified --trials 40 --seed 5 >"$scratch/trials.json"
check trials_status $?
"$python" - "$scratch/trials.json" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
assert out["trials"] == 40 and out["seeds"] == [5, 44], out["seeds"]
sd = out["standard_deviation"]["coupling"][0][0]
# Half of Howell's 0.1998249 gets through the fixture's symmetric half blocker; the mean of 40
# trials lies within 4 standard errors of it.
assert abs(out["mean_coupling"][0][0] - 0.1998249 / 2) < 4 * sd / 40 ** 0.5, out["mean_coupling"]
PY
check trials_json $?
expect_error zero_trials "--trials: Value 0 not in range 1 to 100000" link "$fixtures/good_link.json" --rule Stratified --trials 0

# The reference with its standard error.
"$radquad" reference "$fixtures/good_link.json" --degree 1 --seed 2 >"$scratch/reference.json"
check reference_status $?
"$python" - "$scratch/reference.json" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
assert out["samples"] == 10000
k, se = out["coupling"], out["standard_error"]["coupling"]
assert len(k) == 4 and len(se) == 4 and all(len(row) == 4 for row in se)
assert 0 < out["standard_error"]["form_factor"] < 0.01 * out["form_factor"]
assert abs(out["form_factor"] - 0.1998249 / 2) < 5 * out["standard_error"]["form_factor"]
PY
check reference_json $?
expect_error reference_bad_file "malformed.json: malformed JSON" reference "$fixtures/malformed.json"

# A triangle occluder (link files accept {"triangle": [a, b, c]} beside parallelograms): a
# huge triangle in the mid-plane z = 1/2 with an edge along x = 1/2 blocks every ray whose
# midpoint has x < 1/2, exactly half of the opposed unit squares' form factor by symmetry
# (x -> 1 - x); the exact gold against half of Howell's closed form (C-11, X = Y = 1).
"$radquad" reference "$fixtures/triangle_link.json" --gold >"$scratch/triangle.json" 2>/dev/null
check triangle_status $?
"$python" - "$scratch/triangle.json" <<'PY'
import json, math, sys
gold = json.load(open(sys.argv[1]))["gold"]
x = y = 1.0
closed = 2 / (math.pi * x * y) * (
    math.log(math.sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)))
    + x * math.sqrt(1 + y * y) * math.atan(x / math.sqrt(1 + y * y))
    + y * math.sqrt(1 + x * x) * math.atan(y / math.sqrt(1 + x * x))
    - x * math.atan(x) - y * math.atan(y))
assert gold["converged"], gold
assert abs(gold["form_factor"] - closed / 2) < 1e-7 * closed, (gold["form_factor"], closed / 2)
# The blocker's edge seen from the source's corners gives two critical segments, along the
# receiver's edges s = 0 and s = 1; one analytic cell: the critical lines are taken.
assert gold["outer_method"] == "critical lines", gold["outer_method"]
assert gold["critical_segments"] >= 2, gold["critical_segments"]
PY
check triangle_half_blocked $?
# Progress of a slow gold (three overlapping blockers at degree 2 and a tight tolerance,
# about 3.4 s on two cores, 1.9 million receiver points; at degree 0 it took under a second,
# too close to the first progress line): lines on stderr about once a second after the first
# second, none with --quiet; stdout the same.
"$radquad" reference "$fixtures/three_blockers_link.json" --gold --degree 2 \
  --gold-tolerance 1e-11 >"$scratch/slow.json" 2>"$scratch/slow.err"
check slow_gold_status $?
grep -q "radquad reference: gold: [0-9]* receiver points, [0-9.]* s" "$scratch/slow.err"
check slow_gold_progress $?
"$radquad" reference "$fixtures/three_blockers_link.json" --gold --degree 2 \
  --gold-tolerance 1e-11 --quiet >"$scratch/slow_quiet.json" 2>"$scratch/slow_quiet.err"
[ ! -s "$scratch/slow_quiet.err" ] && cmp -s "$scratch/slow.json" "$scratch/slow_quiet.json"
check slow_gold_quiet $?
# A gold that cannot reach its tolerance within its budget (1e-15 on the same link, about a
# second on two cores): its JSON, converged false, on stdout for diagnosis, the failure on
# stderr, status 3.
"$radquad" reference "$fixtures/three_blockers_link.json" --gold --gold-tolerance 1e-15 --quiet \
  >"$scratch/unconverged.json" 2>"$scratch/unconverged.err"
[ $? -eq 3 ] && grep -q "three_blockers_link.json: the gold did not reach its tolerance (1e-15)" \
  "$scratch/unconverged.err" &&
  "$python" -c 'import json, sys; assert json.load(open(sys.argv[1]))["gold"]["converged"] is False' \
  "$scratch/unconverged.json"
check unconverged_gold $?
# A study whose exact golds are asked for 1e-9 within 1,000 receiver points: the table is
# written (complete, the short golds counted), the failure named on stderr, status 3.
cat >"$scratch/short_gold.json" <<'JSON'
{"figure": "fig1", "seed": 3, "classes": {"partial": 2}, "rules": ["FullGauss"],
 "geometry": {"occluders": ["one_blocker"]},
 "gold": {"max_evaluations": 1000, "exact_tolerance": 1e-9}}
JSON
"$radquad" study "$scratch/short_gold.json" --out "$scratch/short_gold_table.json" --quiet \
  2>"$scratch/short_gold.err"
[ $? -eq 3 ] && grep -q "short_gold_table.json: the gold of [0-9]* links\? did not reach its tolerance" \
  "$scratch/short_gold.err" &&
  "$python" -c 'import json, sys; assert json.load(open(sys.argv[1]))["gold"]["unconverged_links"] >= 1' \
  "$scratch/short_gold_table.json"
check study_unconverged_gold $?
expect_error bad_triangle "occluders[0].triangle: expected an array of 3 points" link "$fixtures/bad_triangle.json" --rule FullGauss

# Rules from files: `rules --dump` writes a rule, `File:PATH` reads it back, and the link's
# coupling is the registered rule's, digit for digit; a bad file is named with exit status 2.
"$radquad" rules --dump FullGauss >"$scratch/fullgauss_rule.json"
check dump_status $?
"$radquad" link "$fixtures/good_link.json" --rule FullGauss --degree 1 >"$scratch/registered.json"
"$radquad" link "$fixtures/good_link.json" --rule "File:$scratch/fullgauss_rule.json" --degree 1 >"$scratch/from_file.json"
"$python" - "$scratch/registered.json" "$scratch/from_file.json" <<'PY'
import json, sys
a, b = (json.load(open(path)) for path in sys.argv[1:3])
assert a["coupling"] == b["coupling"], (a["coupling"], b["coupling"])
PY
check file_rule_round_trip $?
printf '{"name": "Half", "points": [[0.5, 0.5, 0.5, 0.5]], "weights": [0.5]}' >"$scratch/half_rule.json"
expect_error file_rule_weights "half_rule.json: weights sum to" link "$fixtures/good_link.json" --rule "File:$scratch/half_rule.json"
expect_error file_rule_missing "no_such_rule.json" link "$fixtures/good_link.json" --rule "File:$scratch/no_such_rule.json"

# --degree-check measures the degree the dumped points integrate exactly: FullGauss (3 Gauss
# points per axis) is exact to degree 5 and not 6, as declared (exit 0); the same points
# declared exact to degree 1 only (true, so the file loads) are reported as understated (exit
# 1); without --dump the option is refused (exit 2).
"$radquad" rules --dump FullGauss --degree-check >/dev/null 2>"$scratch/degree.err"
status=$?
[[ $status -eq 0 ]] && grep -q "exact to degree 5, not to degree 6" "$scratch/degree.err"
check degree_check_holds $?
"$python" - "$scratch" <<'PY'
import json, sys
rule = json.load(open(sys.argv[1] + "/fullgauss_rule.json"))
rule["degree"], rule["name"] = 1, "Understated"
json.dump(rule, open(sys.argv[1] + "/understated_rule.json", "w"))
PY
"$radquad" rules --dump "File:$scratch/understated_rule.json" --degree-check >/dev/null 2>"$scratch/understated.err"
status=$?
[[ $status -eq 1 ]] && grep -q "exact to degree 5, not to degree 6 .*declared 1" "$scratch/understated.err"
check degree_check_understated $?
expect_error degree_check_needs_dump "--degree-check: needs --dump NAME" rules --degree-check

# NumPy archives: a product rule (FullGauss, numpy.savez) and a 4D point set (Stroud65,
# numpy.savez_compressed) written by numpy from the dumped JSON give the registered rules'
# couplings digit for digit; an archive with a wrongly shaped array, or that is no archive, is
# named with exit status 2.
"$radquad" rules --dump Stroud65 >"$scratch/stroud_rule.json"
"$python" - "$scratch" <<'PY'
import json, sys
import numpy as np
scratch = sys.argv[1]
full = json.load(open(scratch + "/fullgauss_rule.json"))
np.savez(scratch + "/fullgauss.npz", name=np.array(full["name"]),
         receiver_points=np.array(full["receiver"]["points"]),
         receiver_weights=np.array(full["receiver"]["weights"]),
         source_points=np.asfortranarray(np.array(full["source"]["points"])),
         source_weights=np.array(full["source"]["weights"]),
         degree=np.array(full["degree"], dtype=np.int32))
stroud = json.load(open(scratch + "/stroud_rule.json"))
np.savez_compressed(scratch + "/stroud.npz", points=np.array(stroud["points"]),
                    weights=np.array(stroud["weights"]))
np.savez(scratch + "/bad_shape.npz", points=np.zeros((3, 3)), weights=np.ones(3) / 3)
PY
check npz_written $?
"$radquad" link "$fixtures/good_link.json" --rule "File:$scratch/fullgauss.npz" --degree 1 >"$scratch/from_npz.json"
check npz_product_status $?
"$radquad" link "$fixtures/good_link.json" --rule Stroud65 --degree 1 >"$scratch/stroud_registered.json"
"$radquad" link "$fixtures/good_link.json" --rule "File:$scratch/stroud.npz" --degree 1 >"$scratch/stroud_npz.json"
check npz_points_status $?
"$python" - "$scratch" <<'PY'
import json, sys
scratch = sys.argv[1]
for registered, loaded in (("registered", "from_npz"), ("stroud_registered", "stroud_npz")):
    a, b = (json.load(open(f"{scratch}/{name}.json")) for name in (registered, loaded))
    assert a["coupling"] == b["coupling"], (registered, a["coupling"], b["coupling"])
PY
check npz_round_trip $?
expect_error npz_bad_shape "bad_shape.npz: points: shape (3, 3) where (N, 4) is expected" link "$fixtures/good_link.json" --rule "File:$scratch/bad_shape.npz"
cp "$fixtures/good_link.json" "$scratch/not_an_archive.npz"
expect_error npz_not_zip "not_an_archive.npz: not a readable .npz (zip) archive" link "$fixtures/good_link.json" --rule "File:$scratch/not_an_archive.npz"

for command in "" link rules reference; do
  "$radquad" $command --help >/dev/null 2>&1
  check "help_$command" $?
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
