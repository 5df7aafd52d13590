#!/bin/bash
# analysis/summarise_properties.py on outcome files written by the property
# executable itself (its hidden "[.outcome_demo]" case records two fake
# outcomes into $COLLIDE2D_PROPERTY_RECORD): two processes appending to one
# file at once, a second file, the table and the comparison, and exit 2 with
# one line on stderr for bad input. Usage: test_summarise_properties.sh PROPERTIES_EXE
set -u
EXE="$1"
HERE="$(cd "$(dirname "$0")" && pwd)"
. "$HERE/harness.sh"
SCRIPT="$HERE/../../analysis/summarise_properties.py"

record() { COLLIDE2D_PROPERTY_RECORD="$1" "$EXE" "[.outcome_demo]" >/dev/null 2>&1; }

# Two processes at once into one file (the lock file serialises them), then a second file.
record "$TMP/a.h5" & record "$TMP/a.h5" & wait
record "$TMP/b.h5" || fail "the property executable failed to record"

runs=$($PY -c 'import h5py, sys; print(len(h5py.File(sys.argv[1], "r")["runs"]))' "$TMP/a.h5" 2>&1)
[ "$runs" = "2" ] && pass "two concurrent processes made two runs" || fail "expected 2 runs in a.h5, got: $runs"

if $PY "$SCRIPT" "$TMP/a.h5" >"$TMP/one" 2>"$TMP/err"; then
  grep -q "energy is kept in elastic scenes" "$TMP/one" && grep -q "60% ball-wall, hit" "$TMP/one" &&
    grep -q "counterexample: ball_wall" "$TMP/one" && pass "table of one file" ||
    fail "table lacks a property, its tags or its counterexample: $(cat "$TMP/one")"
  # Judged and discarded apart, with the reasons for the discards.
  grep -Eq "energy is kept in elastic scenes +strict +100 +37 +0 " "$TMP/one" &&
    grep -q "discarded, not applicable: 30 x restitution; 7 x no collision to judge" "$TMP/one" &&
    pass "judged and discarded counts, discard reasons" ||
    fail "judged/discarded columns or discard reasons missing: $(cat "$TMP/one")"
else fail "one file: $(cat "$TMP/err")"; fi

if $PY "$SCRIPT" "$TMP/a.h5" "$TMP/b.h5" >"$TMP/two" 2>"$TMP/err"; then
  grep -q "== comparison" "$TMP/two" && grep -Eq "bisection misses are classified +fixed +12/0/1 +12/0/1" "$TMP/two" &&
    grep -Eq "energy is kept in elastic scenes +strict +100/37/0 +100/37/0" "$TMP/two" &&
    pass "comparison of two files" || fail "comparison missing or wrong: $(cat "$TMP/two")"
else fail "two files: $(cat "$TMP/err")"; fi

# A record written before discards were counted (no judged/discarded, no
# discard datasets) still reads: judged = cases, discarded "-".
$PY - "$TMP/old.h5" <<'PYEOF' || fail "could not write an old-style record"
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "w") as f:
    f.attrs["format"] = "collide2d property outcomes 1"
    run = f.create_group("runs/000000")
    run.attrs["started"] = "2026-01-01T00:00:00Z"
    g = run.create_group("000000")
    for k, v in {"property": "old property", "mode": "strict", "recorded": "2026-01-01T00:00:00Z", "counterexample": ""}.items():
        g.attrs[k] = v
    for k, v in {"seed": 1, "max_success": 100, "max_size": 100, "cases": 100, "failures": 0, "gave_up": 0}.items():
        g.attrs[k] = np.int32(v)
    g.attrs["seconds"] = 1.0
    g.create_dataset("distribution_tags", data=np.array([], dtype=h5py.string_dtype()))
    g.create_dataset("distribution_counts", data=np.array([], dtype=np.int64))
PYEOF
if $PY "$SCRIPT" "$TMP/old.h5" >"$TMP/old" 2>"$TMP/err"; then
  grep -Eq "old property +strict +100 +- +0 " "$TMP/old" && pass "an old record: judged = cases, discarded -" ||
    fail "old record shown wrong: $(cat "$TMP/old")"
else fail "old record: $(cat "$TMP/err")"; fi

$PY "$SCRIPT" --help >/dev/null || fail "--help exited non-zero"
expect_exit2 "missing file" $PY "$SCRIPT" "$TMP/no_such.h5"
echo "not hdf5" >"$TMP/text.h5"
expect_exit2 "not an HDF5 file" $PY "$SCRIPT" "$TMP/a.h5" "$TMP/text.h5"
$PY -c 'import h5py, sys; h5py.File(sys.argv[1], "w").create_group("particles")' "$TMP/other.h5"
expect_exit2 "an HDF5 file of another kind" $PY "$SCRIPT" "$TMP/other.h5"
expect_exit2 "no file given" $PY "$SCRIPT"

if [ "$failures" -ne 0 ]; then echo "$failures failure(s)" >&2; exit 1; fi
echo "all summarise_properties checks passed"
