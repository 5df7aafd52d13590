#!/bin/bash
# analysis/paired_time.py: times two commands in turn. Checks what it prints
# (each figure's row, the ratio rows only with --vs), that the peak memory
# is the child's own (a command that writes 200 MiB peaks above 190 MiB,
# one that writes nothing far below), a failing command noted on stderr,
# and bad use exiting 2 with one line on stderr. Nothing here is a timing:
# no speed is asserted. Exits non-zero on failure.
set -u
HERE="$(cd "$(dirname "$0")" && pwd)"
. "$HERE/harness.sh"
TOOL="$HERE/../../analysis/paired_time.py"

big='b = b"x" * (200 * 2**20)'
if ! $PY "$TOOL" -n 2 --warmup 0 --vs "$PY -c pass" -- $PY -c "$big" >"$TMP/out" 2>"$TMP/err"; then
  fail "a paired run exited non-zero: $(cat "$TMP/err")"
fi
for label in "A cpu s" "A wall s" "A peak MiB" "B cpu s" "B wall s" "B peak MiB" "A/B cpu" "A/B wall"; do
  grep -q "^$label " "$TMP/out" && pass "row '$label'" || fail "no row '$label' in: $(cat "$TMP/out")"
done
peak() { awk -v k="$1" '$0 ~ "^"k" peak MiB" { print $5 }' "$TMP/out"; }  # the median column
a_peak=$(peak A) b_peak=$(peak B)
if awk -v a="$a_peak" -v b="$b_peak" 'BEGIN { exit !(a > 190 && b < 100) }'; then
  pass "peaks: A $a_peak MiB (writes 200 MiB), B $b_peak MiB"
else
  fail "peaks A $a_peak MiB and B $b_peak MiB: expected A > 190 (it writes 200 MiB) and B < 100"
fi

$PY "$TOOL" -n 1 --warmup 0 -- true >"$TMP/out" 2>"$TMP/err" || fail "one command alone exited non-zero"
grep -q "^A/B" "$TMP/out" && fail "ratio rows without --vs" || pass "no ratio rows without --vs"
$PY "$TOOL" -n 2 --warmup 0 -- false >"$TMP/out" 2>"$TMP/err"
grep -q "2 of 2 runs of A exited with a non-zero status" "$TMP/err" && pass "a failing command is noted" ||
  fail "a failing command was not noted: $(cat "$TMP/err")"

expect_exit2 "no command" $PY "$TOOL" -n 2
expect_exit2 "no runs" $PY "$TOOL" -n 0 -- true
expect_exit2 "a command that does not exist" $PY "$TOOL" -n 1 --warmup 0 -- /nonexistent/command
$PY "$TOOL" --help >/dev/null || fail "--help exited non-zero"

if [ "$failures" -ne 0 ]; then echo "$failures failure(s)" >&2; exit 1; fi
echo "all paired_time checks passed"
