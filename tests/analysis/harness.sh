# Shared by the analysis script tests (sourced): a temporary folder, a
# failure count, and the checks every script's test makes.
PY=/usr/bin/python3
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
failures=0

fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

# expect_exit2 NAME CMD...: CMD must exit 2 with exactly one line on stderr.
expect_exit2() {
  local name="$1"; shift
  "$@" >"$TMP/out" 2>"$TMP/err"
  local rc=$? lines
  lines=$(wc -l <"$TMP/err")
  if [ "$rc" -ne 2 ]; then fail "$name: expected exit 2, got $rc: $(cat "$TMP/err")"
  elif [ "$lines" -ne 1 ]; then fail "$name: expected one line on stderr, got $lines: $(cat "$TMP/err")"
  else pass "$name: exit 2: $(cat "$TMP/err")"; fi
}

is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }
