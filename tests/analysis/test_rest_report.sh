#!/bin/bash
# analysis/rest_report.py on synthetic run files (tests/analysis/make_rest_run.py):
# the clean run passes --check with the figures it was built with; each planted
# fault (an overlap with a wall, an overlap of two balls, an energy rise,
# chatter) fails --check naming that check and no other; an energy rise in a
# scene with restitution 1 passes, saying the energy check does not apply;
# --json is one JSON object; bad input exits 2 with one line on stderr.
# With COLLIDE2D given, also a short real run (newtons_cradle, elastic): the
# report must read it and agree with the file on frames and events.
#   test_rest_report.sh [COLLIDE2D]
set -u
EXE="${1:-}"
HERE="$(cd "$(dirname "$0")" && pwd)"
. "$HERE/harness.sh"
SCRIPT="$HERE/../../analysis/rest_report.py"
MAKE="$HERE/make_rest_run.py"

if ! $PY -c 'import h5py, numpy' 2>/dev/null; then
  echo "FAIL: $PY lacks h5py or numpy (python3-h5py python3-numpy)" >&2
  exit 1
fi

# json_field FILE EXPR: evaluates the Python expression EXPR on the JSON object o in FILE.
json_field() { $PY -c 'import json, sys; o = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$1" "$2"; }

# expect_check FAULT RC WORD: --check on a run with FAULT exits RC, and its
# "check FAILED" lines mention WORD ("" for none); the other checks stay quiet.
expect_check() {
  local fault="$1" want="$2" word="$3" rc failed
  $PY "$MAKE" "$TMP/$fault.h5" --fault "$fault" || { fail "make_rest_run.py --fault $fault"; return; }
  $PY "$SCRIPT" "$TMP/$fault.h5" --check >"$TMP/out" 2>"$TMP/err"
  rc=$?
  failed=$(grep "check FAILED" "$TMP/out")
  if [ "$rc" -ne "$want" ]; then fail "$fault: --check exit $rc, expected $want: $(cat "$TMP/out" "$TMP/err")"; return; fi
  if [ -n "$word" ]; then
    if ! grep -q "check FAILED: $word" <<<"$failed"; then fail "$fault: no failure of the $word check: $failed"; return; fi
    if [ "$(wc -l <<<"$failed")" -ne 1 ]; then fail "$fault: more than the $word check failed: $failed"; return; fi
  elif [ -n "$failed" ]; then fail "$fault: a check failed: $failed"; return; fi
  pass "$fault: --check exit $rc${word:+ (the $word check)}"
}

expect_check none 0 ""
expect_check overlap 1 overlap
expect_check ball_overlap 1 overlap
expect_check energy 1 energy
expect_check chatter 1 events
expect_check elastic_energy 0 ""
grep -q "energy check does not apply: restitution 1 in walls\[0\]" "$TMP/out" &&
  pass "elastic_energy: the energy check is said not to apply" ||
  fail "elastic_energy: no 'does not apply' note: $(cat "$TMP/out")"

# The clean run's figures (make_rest_run.py builds them): 6 s, 3 moving and
# 1 fixed, 4 events, 0.5 per ball per second over the last third (3 events in
# 2 s), no overlap beyond rounding, still from the landing at t = 0.5.
if $PY "$SCRIPT" "$TMP/none.h5" --json >"$TMP/none.json" 2>"$TMP/err"; then
  got=$(json_field "$TMP/none.json" '(o["duration"], o["balls_moving"], o["balls_fixed"], o["events"],
    o["events_per_ball_second"]["last_third"], o["overlap"]["deepest_relative"] < 1e-14,
    abs(o["still_from"] - 0.5) < 1e-12, o["energy"]["frames_rising"], o["check"]["passed"])')
  [ "$got" = "(6.0, 3, 1, 4, 0.5, True, True, 0, True)" ] && pass "clean run: figures as built" ||
    fail "clean run: figures $got"
else fail "--json: exit $?: $(cat "$TMP/err")"; fi

# The planted faults' sizes are reported: 1e-5 r_min of overlap, a rise of m g 1e-6.
$PY "$SCRIPT" "$TMP/ball_overlap.h5" --json --check >"$TMP/bo.json" 2>"$TMP/err"
got=$(json_field "$TMP/bo.json" 'round(o["overlap"]["deepest_relative"] / 1e-5, 6), o["overlap"]["where"]')
[ "$got" = "(1.0, {'time': 2.0, 'ball': 1, 'ball_b': 2})" ] && pass "ball_overlap: depth 1e-5 r_min, balls 1 and 2 at t = 2" ||
  fail "ball_overlap: $got"
grep -q "check FAILED: overlap" "$TMP/err" && pass "--json --check names the failure on stderr" ||
  fail "--json --check: nothing on stderr: $(cat "$TMP/err")"
$PY "$SCRIPT" "$TMP/energy.h5" --json >"$TMP/en.json"
got=$(json_field "$TMP/en.json" 'round(o["energy"]["max_rise"] / (0.5 * 9.81 * 1e-6), 6), o["energy"]["between"]')
[ "$got" = "(1.0, [1.98, 2.0])" ] && pass "energy: rise m g 1e-6 between t = 1.98 and 2" || fail "energy: $got"

# A real run, if the executable is given: an elastic scene (the energy check
# does not apply), frames and events as in the file.
if [ -n "$EXE" ]; then
  SCENE="$HERE/../../datasets/scenes/newtons_cradle.json"
  if "$EXE" run "$SCENE" -o "$TMP/cradle.h5" --until 2 >/dev/null 2>"$TMP/err"; then
    $PY "$SCRIPT" "$TMP/cradle.h5" --json --check >"$TMP/cradle.json" 2>"$TMP/err"
    rc=$?
    want=$($PY -c 'import h5py, sys; f = h5py.File(sys.argv[1], "r")
print((len(f["particles/balls/position/time"]), len(f["events/time"])))' "$TMP/cradle.h5")
    got=$(json_field "$TMP/cradle.json" '(o["frames"], o["events"])')
    if [ "$rc" -gt 1 ]; then fail "real run: exit $rc: $(cat "$TMP/err")"
    elif [ "$got" != "$want" ]; then fail "real run: frames and events $got, the file has $want"
    elif [ "$(json_field "$TMP/cradle.json" 'o["energy"]["check_applies"]')" != "False" ]; then
      fail "real run: the energy check applies to an elastic scene"
    else pass "real run (newtons_cradle, 2 s): $got frames and events, energy check not applied"; fi
  else fail "collide2d run newtons_cradle: $(cat "$TMP/err")"; fi
fi

# Bad input: exit 2, one line on stderr.
$PY "$SCRIPT" --help >/dev/null || fail "--help exited non-zero"
expect_exit2 "no file given" $PY "$SCRIPT"
expect_exit2 "missing input" $PY "$SCRIPT" "$TMP/no_such.h5"
echo "not hdf5" >"$TMP/text.h5"
expect_exit2 "not an HDF5 file" $PY "$SCRIPT" "$TMP/text.h5"
$PY -c 'import h5py, sys; h5py.File(sys.argv[1], "w").create_group("particles")' "$TMP/other.h5"
expect_exit2 "an HDF5 file of another kind" $PY "$SCRIPT" "$TMP/other.h5"
cp "$TMP/none.h5" "$TMP/noscene.h5"
$PY -c 'import h5py, sys; del h5py.File(sys.argv[1], "r+")["parameters/scene_json"]' "$TMP/noscene.h5"
expect_exit2 "no scene JSON" $PY "$SCRIPT" "$TMP/noscene.h5"

if [ "$failures" -ne 0 ]; then echo "$failures failure(s)" >&2; exit 1; fi
echo "all rest_report checks passed"
