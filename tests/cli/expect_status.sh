# Shared by the command-line test scripts (sourced): the binary under test, a scratch
# folder, and expect_status, which runs the binary and checks its exit status and stderr.
radquad="${RADQUAD:-${1:-}}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0

expect_status() {  # expected-status description expected-stderr-text args...
  local expected="$1" description="$2" text="$3"
  shift 3
  "$radquad" "$@" >"$work/out" 2>"$work/err"
  local status=$?
  if [[ $status -ne $expected ]]; then
    echo "FAIL: $description: exit status $status, expected $expected"; cat "$work/err"
    failures=$((failures + 1))
  elif [[ -n "$text" ]] && ! grep -q -- "$text" "$work/err"; then
    echo "FAIL: $description: stderr lacks '$text'"; cat "$work/err"
    failures=$((failures + 1))
  fi
}
