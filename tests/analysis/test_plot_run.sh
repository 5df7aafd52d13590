#!/bin/bash
# Plots a synthetic run (analysis/make_demo_run.py) with analysis/plot_run.py:
# a PNG and a short GIF must come out non-empty, the PNG must be a real PNG,
# and bad input must exit 2 with one line on stderr. Exits non-zero on failure.
set -u
HERE="$(cd "$(dirname "$0")" && pwd)"
. "$HERE/harness.sh"
ANALYSIS="$HERE/../../analysis"

is_gif() { [ "$(head -c 4 "$1")" = "GIF8" ]; }

if ! $PY -c 'import h5py, numpy, matplotlib, PIL' 2>/dev/null; then
  echo "FAIL: $PY lacks h5py, numpy, matplotlib or PIL (python3-h5py python3-matplotlib python3-pil)" >&2
  exit 1
fi

# Every /parameters form: scene as attribute, as dataset, radii only in the JSON.
for form in attr dataset json; do
  run="$TMP/demo_$form.h5"
  if ! $PY "$ANALYSIS/make_demo_run.py" "$run" --form "$form" 2>"$TMP/err"; then
    fail "make_demo_run.py --form $form: $(cat "$TMP/err")"; continue
  fi
  if ! $PY "$ANALYSIS/plot_run.py" "$run" -o "$TMP/$form.png" 2>"$TMP/err"; then
    fail "plot_run.py ($form): $(cat "$TMP/err")"
  elif [ ! -s "$TMP/$form.png" ]; then fail "$form.png is missing or empty"
  elif ! is_png "$TMP/$form.png"; then fail "$form.png does not start with the PNG signature"
  else pass "PNG from the '$form' layout ($(stat -c %s "$TMP/$form.png") bytes)"; fi
done

run="$TMP/demo_attr.h5"
if $PY "$ANALYSIS/plot_run.py" "$run" -o "$TMP/a.png" --animate "$TMP/a.gif" --max-frames 30 --fps 10 \
     2>"$TMP/err"; then
  if [ -s "$TMP/a.gif" ] && is_gif "$TMP/a.gif"; then pass "GIF animation ($(stat -c %s "$TMP/a.gif") bytes)"
  else fail "a.gif is missing, empty or not a GIF"; fi
else
  fail "plot_run.py --animate a.gif: $(cat "$TMP/err")"
fi

# An .mp4 request makes an mp4 with ffmpeg, a GIF beside it without.
if $PY "$ANALYSIS/plot_run.py" "$run" -o "$TMP/b.png" --animate "$TMP/b.mp4" --max-frames 20 2>"$TMP/err"; then
  if [ -s "$TMP/b.mp4" ]; then pass "mp4 animation (ffmpeg present)"
  elif [ -s "$TMP/b.gif" ] && is_gif "$TMP/b.gif"; then pass "mp4 request fell back to GIF (no ffmpeg)"
  else fail "--animate b.mp4 wrote neither b.mp4 nor b.gif"; fi
else
  fail "plot_run.py --animate b.mp4: $(cat "$TMP/err")"
fi

# Bad input: exit 2, one line, no output left behind.
expect_exit2 "missing input" $PY "$ANALYSIS/plot_run.py" "$TMP/no_such.h5" -o "$TMP/x.png"
[ -e "$TMP/x.png" ] && fail "missing input left $TMP/x.png behind"
echo "not hdf5" >"$TMP/text.h5"
expect_exit2 "not an HDF5 file" $PY "$ANALYSIS/plot_run.py" "$TMP/text.h5" -o "$TMP/x.png"
$PY -c 'import h5py, sys; h5py.File(sys.argv[1], "w").create_group("particles")' "$TMP/empty.h5"
expect_exit2 "no datasets" $PY "$ANALYSIS/plot_run.py" "$TMP/empty.h5" -o "$TMP/x.png"
expect_exit2 "unwritable output" $PY "$ANALYSIS/plot_run.py" "$run" -o "$TMP/no_dir/x.png"
expect_exit2 "bad movie suffix" $PY "$ANALYSIS/plot_run.py" "$run" -o "$TMP/x.png" --animate "$TMP/x.avi"
$PY "$ANALYSIS/plot_run.py" --help >/dev/null || fail "--help exited non-zero"

if [ "$failures" -ne 0 ]; then echo "$failures failure(s)" >&2; exit 1; fi
echo "all plot_run checks passed"
