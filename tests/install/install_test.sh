#!/usr/bin/env bash
# The installed, relocated radquad: `cmake --install BUILD --prefix P`, the tree moved to
# another folder, then
#   - a separate CMake project finds it (find_package(radquad), radquad::experiments) and
#     integrates a form factor that matches its closed form (tests/install/consumer);
#   - the same program builds with `pkg-config --cflags --libs radquad`;
#   - the installed command finds its study configs from wherever the tree now is, writes
#     nothing into the current folder when it fails, and names a missing config when told to
#     look elsewhere (RADQUAD_DATA_DIR);
#   - the Python module imports from PREFIX/lib/python3/dist-packages (when it was built).
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -uo pipefail
build="$1"
source_dir="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

if ! cmake --install "$build" --prefix "$work/first" >"$work/install.log" 2>&1; then
  cat "$work/install.log"; echo "FAIL: cmake --install"; exit 1
fi
mv "$work/first" "$work/prefix"
prefix="$work/prefix"
for file in bin/radquad lib/cmake/radquad/radquadConfig.cmake lib/cmake/radquad/radquadTargets.cmake \
            lib/pkgconfig/radquad.pc include/radquad/kernel/coupling.h \
            include/radquad/quadrature/prepared_rule.h share/radquad/experiments/configs/fig1.json \
            share/radquad/plots/figures.py; do
  [[ -e "$prefix/$file" ]] || fail "not installed: $file"
done
[[ -z "$(ls "$prefix"/lib/libradquad_*.a 2>/dev/null)" ]] && fail "no library installed"

# find_package from a separate project, against the moved tree.
if cmake -S "$source_dir/tests/install/consumer" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
     -DCMAKE_PREFIX_PATH="$prefix" >"$work/consumer.log" 2>&1 &&
   cmake --build "$work/consumer" >>"$work/consumer.log" 2>&1; then
  "$work/consumer/consumer" || fail "the find_package consumer's form factor"
else
  tail -30 "$work/consumer.log"; fail "find_package(radquad) project did not build"
fi

# pkg-config, against the moved tree.
if flags="$(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs radquad)"; then
  # shellcheck disable=SC2086
  if c++ -O1 "$source_dir/tests/install/consumer/main.cpp" -o "$work/pc-consumer" $flags \
       >"$work/pc.log" 2>&1; then
    "$work/pc-consumer" || fail "the pkg-config consumer's form factor"
  else
    tail -30 "$work/pc.log"; fail "pkg-config build"
  fi
else
  fail "pkg-config --cflags --libs radquad"
fi

# The installed command reads its configs from share/radquad wherever the tree is: an unknown
# rule is named (every config was read first); nothing is written into the current folder.
mkdir -p "$work/cwd"
(cd "$work/cwd" && "$prefix/bin/radquad" figures --quick --quiet --rules Nope) 2>"$work/figures.err"
status=$?
[[ $status -eq 2 ]] || fail "installed figures with an unknown rule: exit status $status"
grep -q "Nope" "$work/figures.err" || { cat "$work/figures.err"; fail "the unknown rule is not named"; }
[[ -z "$(ls -A "$work/cwd")" ]] || fail "a failed figures run wrote into the current folder"
# ... and it is the moved tree's configs it reads (not the source tree's): without one, it
# names the moved path.
mv "$prefix/share/radquad/experiments/configs/fig1-quick.json" "$work/fig1-quick.json"
(cd "$work/cwd" && "$prefix/bin/radquad" figures --quick --quiet) 2>"$work/moved.err"
status=$?
[[ $status -eq 2 ]] || fail "installed figures without its config: exit status $status"
grep -q "$prefix/share/radquad/experiments/configs/fig1-quick.json" "$work/moved.err" ||
  { cat "$work/moved.err"; fail "the installed command does not read the moved tree's configs"; }
mv "$work/fig1-quick.json" "$prefix/share/radquad/experiments/configs/fig1-quick.json"
(cd "$work/cwd" && RADQUAD_DATA_DIR="$work/nowhere" "$prefix/bin/radquad" figures --quick --quiet \
   --rules Nope) 2>"$work/nowhere.err"
status=$?
[[ $status -eq 2 ]] || fail "figures with RADQUAD_DATA_DIR elsewhere: exit status $status"
grep -qF "nowhere/experiments/configs/fig1-scene-quick.json: cannot open" "$work/nowhere.err" ||
  { cat "$work/nowhere.err"; fail "a missing config is not named"; }

# The installed command runs from any folder.
(cd "$work/cwd" && "$prefix/bin/radquad" rules >/dev/null) || fail "installed radquad rules"

# The Python module, when it was built.
if [[ -d "$build/python/radquad" ]]; then
  PYTHONPATH="$prefix/lib/python3/dist-packages" /usr/bin/python3 -c \
    "import radquad; assert any(r['name'] == 'FullGauss' for r in radquad.rules())" ||
    fail "the installed Python module"
fi

if [[ $failures -ne 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "install test passed"
