#!/bin/bash
# Plots a synthetic study file (tests/analysis/make_synthetic_study.py, the
# "collide2d study 1" layout) with analysis/plot_study.py --print: the three
# PNGs must be real PNGs at least 800 px wide, the printed tables must hold the
# numbers written into the file, a study with only /query (or only /scene)
# must make the figures it can and exit 0, and bad input must exit 2 with one
# line on stderr. Exits non-zero on failure.
set -u
HERE="$(cd "$(dirname "$0")" && pwd)"
. "$HERE/harness.sh"
SCRIPT="$HERE/../../analysis/plot_study.py"
MAKE="$HERE/make_synthetic_study.py"
FIGS="study_speed_error.png study_failures_by_family.png study_step_vs_event.png"

# expect_stderr NAME TEXT: the last expect_exit2's message must mention TEXT.
expect_stderr() { grep -qF -- "$2" "$TMP/err" || fail "$1: message does not mention '$2': $(cat "$TMP/err")"; }

png_width() {
  $PY -c 'import struct, sys
d = open(sys.argv[1], "rb").read(24)
print(struct.unpack(">I", d[16:20])[0] if d[12:16] == b"IHDR" else 0)' "$1"
}

# check_png DIR NAME: DIR/NAME is a non-empty PNG at least 800 px wide.
check_png() {
  local f="$1/$2" w
  if [ ! -s "$f" ]; then fail "$2 is missing or empty"; return; fi
  if ! is_png "$f"; then fail "$2 does not start with the PNG signature"; return; fi
  w=$(png_width "$f")
  if [ "$w" -lt 800 ]; then fail "$2 is only $w px wide"; return; fi
  pass "$2: PNG, $w px wide, $(stat -c %s "$f") bytes"
}

# expect_line NAME REGEX: a line of $TMP/out matches the extended REGEX.
expect_line() { grep -Eq -- "$2" "$TMP/out" && pass "table: $1" || fail "table: no line for $1 (/$2/)"; }

if ! $PY -c 'import h5py, numpy, matplotlib' 2>/dev/null; then
  echo "FAIL: $PY lacks h5py, numpy or matplotlib (python3-h5py python3-matplotlib)" >&2
  exit 1
fi

# Both levels, --print, into an output directory that does not exist yet.
$PY "$MAKE" "$TMP/study.h5" || { echo "FAIL: make_synthetic_study.py failed" >&2; exit 1; }
if $PY "$SCRIPT" "$TMP/study.h5" -o "$TMP/figs" --print >"$TMP/out" 2>"$TMP/err"; then
  pass "both levels: exit 0"
  for fig in $FIGS; do
    check_png "$TMP/figs" "$fig"
    grep -qxF "$TMP/figs/$fig" "$TMP/out" || fail "the path of $fig is not printed"
  done
  [ -s "$TMP/err" ] && fail "stderr not empty: $(cat "$TMP/err")"
  # Figure 1: the "all" rows; the Pareto front is seed fixed, seed strict, analytic fixed.
  expect_line "analytic fixed (all), on the front" \
    '^analytic +fixed +3000 +1500 +0 +1 +0 +0 +140\.1 .* 0\.000e\+00 .* yes$'
  expect_line "analytic strict (all), dominated" '^analytic +strict +3000 +1500 +0 +0 .* 152\.3 .* no$'
  expect_line "bisection 1e-6 (all), 37 false negatives" \
    '^bisection 1e-6 +strict +3000 +1463 +37 +0 +0 +0 +2140 .* 3\.200e-07 .* no$'
  expect_line "seed strict (all), on the front" '^seed +strict +3000 +1498 +2 +0 .* 95\.5 .* 4\.100e-12 .* yes$'
  expect_line "seed fixed (all), on the front" '^seed +fixed +3000 +1495 +5 +0 .* 88 .* 7\.700e-10 .* yes$'
  expect_line "eigen companion (all), dominated" '^eigen companion +strict +3000 .* 610 .* 1\.200e-15 .* no$'
  # Figure 2: (FN + FP) / queries per family.
  expect_line "near_miss bisection" '^near_miss +bisection 1e-6 +strict +500 +25 +0 +25 +5\.000e-02 '
  expect_line "near_miss eigen companion (false positives)" \
    '^near_miss +eigen companion +strict +500 +0 +3 +3 +6\.000e-03 '
  expect_line "grazing analytic fixed" '^grazing +analytic +fixed +400 +0 +1 +1 +2\.500e-03 '
  expect_line "thin_fast seed fixed" '^thin_fast +seed +fixed +300 +5 +0 +5 +1\.667e-02 '
  expect_line "thin_fast analytic strict (zero)" '^thin_fast +analytic +strict +300 +0 +0 +0 +0\.000e\+00 '
  grep -Eq '^thin_fast +eigen companion' "$TMP/out" && fail "table: a thin_fast row for eigen companion, which has none"
  # Figure 3: one row per run, in file order.
  expect_line "run 2: gas step dt 1e-2" \
    '^ +2 gas step analytic strict +1e-2 +0\.05 +3\.400e-02 +5\.000e-01 +2\.9 +0\.5 +3\.654 +9000 +12 +201 '
  expect_line "run 1: gas event fixed, no energy error, no fit" \
    '^ +1 gas event analytic fixed +0 +0\.91 +0\.000e\+00 +0\.000e\+00 +nan +nan +nan +12000 +0 +201 '
  expect_line "run 6: abound step, not fitted, 4 missed" '^ +6 abound step seed strict +1e-3 +0\.3 +1\.100e-03 .* nan .* 4 +201 '
else
  fail "both levels: exit $?: $(cat "$TMP/err")"
fi

# Only /query: the first two figures, the third skipped with a line on stdout;
# no -o: the figures go next to the study file.
mkdir "$TMP/q"
$PY "$MAKE" "$TMP/q/study.h5" --levels query
if $PY "$SCRIPT" "$TMP/q/study.h5" >"$TMP/out" 2>"$TMP/err"; then
  pass "only /query: exit 0"
  check_png "$TMP/q" study_speed_error.png
  check_png "$TMP/q" study_failures_by_family.png
  [ -e "$TMP/q/study_step_vs_event.png" ] && fail "only /query: study_step_vs_event.png was written"
  grep -q "skipped study_step_vs_event.png" "$TMP/out" && pass "only /query: the skip is said on stdout" ||
    fail "only /query: no skip message on stdout: $(cat "$TMP/out")"
else
  fail "only /query: exit $?: $(cat "$TMP/err")"
fi

# Only /scene, and a run whose divergence group is missing: the third figure only.
$PY "$MAKE" "$TMP/s.h5" --levels scene
$PY -c 'import h5py, sys; del h5py.File(sys.argv[1], "r+")["scene/divergence/003"]' "$TMP/s.h5"
if $PY "$SCRIPT" "$TMP/s.h5" -o "$TMP/s" >"$TMP/out" 2>"$TMP/err"; then
  pass "only /scene: exit 0"
  check_png "$TMP/s" study_step_vs_event.png
  for fig in study_speed_error.png study_failures_by_family.png; do
    [ -e "$TMP/s/$fig" ] && fail "only /scene: $fig was written"
  done
  grep -q "skipped study_speed_error.png and study_failures_by_family.png" "$TMP/out" ||
    fail "only /scene: no skip message on stdout: $(cat "$TMP/out")"
  grep -q "no /scene/divergence/003" "$TMP/out" && pass "a missing divergence curve is said on stdout" ||
    fail "a missing divergence curve is not reported: $(cat "$TMP/out")"
else
  fail "only /scene: exit $?: $(cat "$TMP/err")"
fi

# Bad input: exit 2, one line on stderr naming the file or dataset.
$PY "$SCRIPT" --help >/dev/null || fail "--help exited non-zero"
expect_exit2 "no file given" $PY "$SCRIPT"
expect_exit2 "missing input" $PY "$SCRIPT" "$TMP/no_such.h5" -o "$TMP/x"
expect_stderr "missing input" "no_such.h5"
echo "not hdf5" >"$TMP/text.h5"
expect_exit2 "not an HDF5 file" $PY "$SCRIPT" "$TMP/text.h5" -o "$TMP/x"
$PY -c 'import h5py, sys; h5py.File(sys.argv[1], "w").create_group("particles")' "$TMP/other.h5"
expect_exit2 "an HDF5 file of another kind" $PY "$SCRIPT" "$TMP/other.h5" -o "$TMP/x"
expect_stderr "an HDF5 file of another kind" "format"
$PY -c 'import h5py, sys; h5py.File(sys.argv[1], "w").attrs["format"] = "collide2d study 1"' "$TMP/empty.h5"
expect_exit2 "neither /query nor /scene" $PY "$SCRIPT" "$TMP/empty.h5" -o "$TMP/x"
cp "$TMP/study.h5" "$TMP/short.h5"
$PY -c 'import h5py, sys
t = h5py.File(sys.argv[1], "r+")["query/table"]
v = t["threw"][:-1]; del t["threw"]; t["threw"] = v' "$TMP/short.h5"
expect_exit2 "a column of the wrong length" $PY "$SCRIPT" "$TMP/short.h5" -o "$TMP/x"
expect_stderr "a column of the wrong length" "/query/table/threw"
cp "$TMP/study.h5" "$TMP/nocol.h5"
$PY -c 'import h5py, sys; del h5py.File(sys.argv[1], "r+")["scene/table/growth_rate"]' "$TMP/nocol.h5"
expect_exit2 "a missing column" $PY "$SCRIPT" "$TMP/nocol.h5" -o "$TMP/x"
expect_stderr "a missing column" "/scene/table/growth_rate"
[ -e "$TMP/x" ] && fail "bad input left $TMP/x behind"

if [ "$failures" -ne 0 ]; then echo "$failures failure(s)" >&2; exit 1; fi
echo "all plot_study checks passed"
