#!/usr/bin/env bash
# plots/figures.py on the committed results: the committed plots/*.svg are what it draws from
# results/ (so they are never stale), `--only NAME` draws that table's figures alone, and an
# unknown table is refused.
# Usage: figures_py_test.sh SOURCE_DIR
set -u
root="$1"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0
fail() { echo "FAILED: $*"; failures=$((failures + 1)); }

# The committed SVGs are compared byte for byte only with the matplotlib that drew them (its
# version is in each SVG): another version lays text out differently.
drawn_with=$(sed -n 's|.*<dc:title>Matplotlib v\([^,]*\),.*|\1|p' "$root/plots/fig1.svg" | head -1)
installed=$(/usr/bin/python3 -c 'import matplotlib; print(matplotlib.__version__)')
same_matplotlib=no
if [ -n "$drawn_with" ] && [ "$drawn_with" = "$installed" ]; then
  same_matplotlib=yes
else
  echo "note: plots/*.svg were drawn with matplotlib '$drawn_with', this is '$installed': not compared"
fi
/usr/bin/python3 "$root/plots/figures.py" --results "$root/results" --plots "$scratch/all" ||
  fail "figures.py exited with $?"
for stem in fig1 fig2 fig1-scene fig2-scene; do
  for kind in "" -breakdown; do
    for extension in png svg; do
      [ -s "$scratch/all/$stem$kind.$extension" ] || fail "$stem$kind.$extension not drawn"
    done
    if [ "$same_matplotlib" = yes ]; then
      cmp -s "$scratch/all/$stem$kind.svg" "$root/plots/$stem$kind.svg" ||
        fail "plots/$stem$kind.svg differs from what figures.py draws from results/"
    fi
  done
done
[ "$(ls "$scratch/all" | wc -l)" -eq 16 ] || fail "expected the 16 files alone: $(ls "$scratch/all" | tr '\n' ' ')"
! ls "$scratch/all" | grep -q '\.tmp\.' || fail "temporary files left: $(ls "$scratch/all" | tr '\n' ' ')"

/usr/bin/python3 "$root/plots/figures.py" --results "$root/results" --plots "$scratch/one" --only fig2 ||
  fail "figures.py --only fig2 exited with $?"
[ "$(ls "$scratch/one" | tr '\n' ' ')" = "fig2-breakdown.png fig2-breakdown.svg fig2.png fig2.svg " ] ||
  fail "--only fig2 drew: $(ls "$scratch/one" | tr '\n' ' ')"
cmp -s "$scratch/one/fig2.svg" "$scratch/all/fig2.svg" || fail "--only fig2 drew another fig2.svg"

/usr/bin/python3 "$root/plots/figures.py" --results "$root/results" --plots "$scratch/bad" --only fig3 \
  2>"$scratch/bad.err"
status=$?
[ "$status" -eq 2 ] || fail "--only fig3: exit status $status, expected 2"
grep -q "fig3" "$scratch/bad.err" || fail "--only fig3: the error does not name it: $(cat "$scratch/bad.err")"

# --serve (how radquad figures draws while it computes): the stems on standard input drawn in
# turn, each answered on standard output; an unknown stem and a table that cannot be read are
# answered "failed" without stopping the others, and the exit status is then 1.
printf 'fig2\nfig3\nfig1-scene\n\nfig1\n' |
  /usr/bin/python3 "$root/plots/figures.py" --results "$root/results" --plots "$scratch/served" --serve \
  >"$scratch/served.out" 2>"$scratch/served.err"
status=$?
[ "$status" -eq 1 ] || fail "--serve: exit status $status, expected 1 (fig3 failed)"
[ "$(tr '\n' ' ' <"$scratch/served.out")" = "drawn fig2 failed fig3 drawn fig1-scene drawn fig1 " ] ||
  fail "--serve answered: $(tr '\n' ' ' <"$scratch/served.out")"
grep -q "fig3" "$scratch/served.err" || fail "--serve: the error does not name fig3: $(cat "$scratch/served.err")"
for stem in fig2 fig1-scene fig1; do
  cmp -s "$scratch/served/$stem.svg" "$scratch/all/$stem.svg" || fail "--serve drew another $stem.svg"
  cmp -s "$scratch/served/$stem-breakdown.png" "$scratch/all/$stem-breakdown.png" ||
    fail "--serve drew another $stem-breakdown.png"
done
mkdir -p "$scratch/missing"
echo fig1 | /usr/bin/python3 "$root/plots/figures.py" --results "$scratch/missing" --plots "$scratch/served2" \
  --serve >"$scratch/served2.out" 2>"$scratch/served2.err"
status=$?
[ "$status" -eq 1 ] && [ "$(cat "$scratch/served2.out")" = "failed fig1" ] ||
  fail "--serve on a missing table: status $status, answer $(cat "$scratch/served2.out")"
grep -q "cannot read .*fig1.json" "$scratch/served2.err" ||
  fail "--serve on a missing table: $(cat "$scratch/served2.err")"

[ "$failures" -eq 0 ] && echo "figures.py: all checks passed"
exit $((failures > 0))
