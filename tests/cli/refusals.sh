#!/usr/bin/env bash
# Issue 14: every input is checked before any work, no command leaves broken
# output, interrupted work stops cleanly. One case per ctest entry:
#   refusals.sh COLLIDE2D SOURCE_DIR CASE
# A case passes when the command ends with the exit code SPEC.md and
# docs/formats/exit-codes.md give, says what is wrong in one line naming the
# file or option, and leaves no output under the requested name.
set -euo pipefail
exe=$1 root=$2 case=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
scenes=$root/datasets/scenes

fail() { echo "FAIL ($case): $*" >&2; exit 1; }

# expect CODE PATTERN COMMAND...: the exit code, and stderr's last line matching PATTERN.
expect() {
  local want=$1 pattern=$2
  shift 2
  local got=0
  "$@" > out.txt 2> err.txt || got=$?
  [[ $got == "$want" ]] || fail "exit $got (wanted $want) from: $* -- stderr: $(tail -3 err.txt)"
  local last
  last=$(tail -n 1 err.txt)
  [[ $last =~ $pattern ]] || fail "stderr's last line \"$last\" does not match /$pattern/ from: $*"
  (( ${#last} < 400 )) || fail "a message of ${#last} characters from: $*"
  if grep -Eq 'sblock|base_addr|o_flags|H5[A-Z][a-z]*_|HDF5-DIAG' err.txt; then fail "library internals leak: $(cat err.txt)"; fi
}

# scene FILE JSON: a scene file.
scene() { printf '%s\n' "$2" > "$1"; }
one_ball='"balls": [{"position": [0, 0], "velocity": [1, 0], "radius": 0.5}]'

case $case in
options_not_finite)
  for args in "--until nan" "--until inf" "--until -1" "--until 0" "--checkpoint-every nan" "--eps nan" \
              "--engine step --method bisection --dt nan" "--engine step --method bisection --dt -inf" "--max-frames nan"; do
    # shellcheck disable=SC2086
    expect 2 "^collide2d: --[a-z-]+: \".*\" is (not finite|out of range|not a number) \(wanted a finite number" \
      "$exe" run -o r.h5 $args
    [[ ! -e r.h5 && ! -e r.h5.partial ]] || fail "$args left a file"
  done
  expect 2 "^collide2d: --etas: " "$exe" bench sim --etas nan
  expect 2 "^collide2d: --until: " "$exe" study --until nan -o s.h5
  expect 2 "^collide2d: --dt: " "$exe" study --dt 0 -o s.h5
  expect 2 "^collide2d: --eps: " "$exe" toi q.jsonl --eps nan
  ;;
scene_energy_overflows)
  # Every number finite, yet 1/2 m |v|^2 = inf: the run could only report energy inf -> inf.
  scene big.json '{"balls": [{"position": [0, 0], "velocity": [1e200, 0], "radius": 1}]}'
  expect 2 "^big.json: balls\[0\]\.velocity: kinetic energy" "$exe" check big.json
  expect 2 "^big.json: balls\[0\]\.velocity: kinetic energy" "$exe" run big.json -o r.h5
  [[ ! -e r.h5 && ! -e r.h5.partial ]] || fail "a refused scene left a file"
  ;;
run_goes_non_finite)
  # Finite at the start (energy 0), but |a| t = 2e155 by t = 20 squares past
  # DBL_MAX: exit 1 (SPEC: a violated invariant), one line, no output file.
  scene fall.json '{"duration": 20, "record": {"interval": 1}, "balls": [{"position": [0, 0], "velocity": [0, 0], "radius": 1, "acceleration": [0, -1e154]}]}'
  expect 1 "^fall.json: the run went non-finite by t = " "$exe" run fall.json -o r.h5
  [[ ! -e r.h5 && ! -e r.h5.partial ]] || fail "a failed run left a file"
  ;;
scene_without_balls)
  scene none.json '{"walls": [{"a": [0, 0], "b": [1, 0]}], "balls": []}'
  expect 2 "^none.json: balls: a scene needs at least one ball" "$exe" check none.json
  expect 2 "^none.json: balls: a scene needs at least one ball" "$exe" run none.json -o r.h5
  ;;
frame_limit)
  # 1e-12 s between frames over 10 s: 1e13 frames (a run wrote 1 GB in 15 s before).
  scene dense.json "{\"duration\": 10, \"record\": {\"interval\": 1e-12}, $one_ball}"
  SECONDS=0
  expect 2 "^dense.json: record.interval: 1e\+13 frames .* the limit is 1e\+06 \(--max-frames raises it\)" "$exe" check dense.json
  expect 2 "^dense.json: record.interval: .*--max-frames" "$exe" run dense.json -o r.h5
  (( SECONDS < 5 )) || fail "the refusal took $SECONDS s"
  # The limit is the user's to raise.
  scene ok.json "{\"duration\": 1, \"record\": {\"interval\": 1e-3}, $one_ball}"
  expect 2 "--max-frames" "$exe" run ok.json -o r.h5 --max-frames 100
  "$exe" run ok.json -o r.h5 --max-frames 1001 > /dev/null || fail "--max-frames 1001 did not allow 1001 frames"
  ;;
step_limit)
  SECONDS=0
  expect 2 "^collide2d run: --dt 1e-300 makes 2e\+301 steps .*--max-steps" "$exe" run -o r.h5 --engine step --method bisection --dt 1e-300
  (( SECONDS < 5 )) || fail "the refusal took $SECONDS s"
  ;;
output_paths)
  mkdir folder
  cp "$scenes/gas.json" g.json
  SECONDS=0
  expect 2 "^folder: is a directory" "$exe" run -o folder
  expect 2 "^g.json: is also an input of this command" "$exe" run g.json -o g.json
  expect 2 "^\./g.json: is also an input of this command" "$exe" run g.json -o ./g.json
  expect 2 "^nowhere/r.h5: folder nowhere does not exist" "$exe" run -o nowhere/r.h5
  (( SECONDS < 5 )) || fail "refusals took $SECONDS s: the run started before the output was checked"
  cmp -s g.json "$scenes/gas.json" || fail "the scene was overwritten"
  "$exe" run g.json -o r.h5 --until 1 > /dev/null
  expect 2 "^r.h5: is also an input" "$exe" export r.h5 --format extxyz -o r.h5
  expect 2 "^folder: is a directory" "$exe" export r.h5 --format extxyz -o folder
  printf '{"horizon": 1, "balls": [{"position": [0, 0], "velocity": [1, 0], "radius": 0.5}], "walls": [{"a": [2, -1], "b": [2, 1]}]}\n' > q.jsonl
  expect 2 "^q.jsonl: is also an input" "$exe" study --queries q.jsonl --no-scenes -o q.jsonl
  expect 2 "^folder: is a directory" "$exe" study --queries q.jsonl --no-scenes -o folder
  expect 2 "^nowhere/h.jsonl: folder nowhere does not exist" "$exe" hardset --jsonl nowhere/h.jsonl -o h.h5
  expect 2 "^folder: is a directory, not a query file" "$exe" toi folder
  expect 2 "^folder: is a directory, not a scene file" "$exe" check folder
  ;;
partial_in_the_way)
  # An interrupted run's partial file is not overwritten by a new run unasked.
  echo "an interrupted run" > r.h5.partial
  expect 2 "^r.h5.partial: an interrupted run is in the way .*--force" "$exe" run -o r.h5 --until 1
  [[ $(cat r.h5.partial) == "an interrupted run" ]] || fail "the partial file was touched"
  "$exe" run -o r.h5 --until 1 --force > /dev/null || fail "--force did not start afresh"
  [[ -e r.h5 && ! -e r.h5.partial ]] || fail "--force left the wrong files"
  ;;
interrupt_without_checkpoint)
  # SIGINT before any checkpoint: exit 130, nothing left, and it says so.
  "$exe" run "$scenes/dense_gas_2000.json" -o r.h5 --until 1000 > out.txt 2> err.txt &
  pid=$!
  while kill -0 $pid 2> /dev/null && ! grep -q "left" err.txt; do sleep 0.05; done
  kill -INT $pid
  got=0; wait $pid || got=$?
  [[ $got == 130 ]] || fail "exit $got after SIGINT (wanted 130)"
  grep -q "interrupted by SIGINT at t = .*; nothing written" err.txt || fail "message: $(tail -1 err.txt)"
  [[ ! -e r.h5 && ! -e r.h5.partial ]] || fail "an interrupted run without a checkpoint left a file"
  grep -q $'\r' err.txt && fail "a carriage return in progress written to a file"
  grep -Eq "^run r.h5: [0-9.]+% \(about .* left\)" err.txt || fail "no progress line with the time left: $(head -1 err.txt)"
  ;;
interrupt_with_checkpoint)
  # SIGTERM after a checkpoint: exit 143, a resumable partial file, and resume
  # finishes it into a run that replays bit for bit.
  "$exe" run "$scenes/dense_gas_2000.json" -o r.h5 --until 1500 --checkpoint-every 1 > out.txt 2> err.txt &
  pid=$!
  while kill -0 $pid 2> /dev/null && ! grep -q "left" err.txt; do sleep 0.05; done
  kill -TERM $pid
  got=0; wait $pid || got=$?
  [[ $got == 143 ]] || fail "exit $got after SIGTERM (wanted 143)"
  grep -q "interrupted by SIGTERM at t = .*r.h5.partial holds the run up to its last checkpoint .*collide2d resume r.h5" err.txt \
    || fail "message: $(tail -1 err.txt)"
  [[ -e r.h5.partial && ! -e r.h5 ]] || fail "no resumable partial file"
  "$exe" resume r.h5 > /dev/null 2>&1 || fail "resume failed"
  "$exe" replay r.h5 > /dev/null || fail "the resumed run does not replay"
  ;;
study_interrupted_resumes)
  # A study stopped after some of its parts keeps them; --resume with the same
  # options does only what is left, and the file appears only then.
  opts=(--limit-per-family 2 --repeats 1 --scenes "$scenes/dense_gas_400.json" --until 30 --dt 0.01 -o s.h5)
  "$exe" study "${opts[@]}" > out.txt 2> err.txt &
  pid=$!
  while kill -0 $pid 2> /dev/null && ! grep -q '"part":"query_unit"' s.h5.parts.jsonl 2> /dev/null; do sleep 0.05; done
  kill -INT $pid
  got=0; wait $pid || got=$?
  [[ $got == 130 ]] || fail "exit $got after SIGINT (wanted 130)"
  grep -q "finished parts are kept in s.h5.parts.jsonl" err.txt || fail "message: $(tail -1 err.txt)"
  [[ ! -e s.h5 && ! -e s.h5.partial && -e s.h5.parts.jsonl ]] || fail "wrong files after the interrupt: $(ls)"
  kept=$(grep -c '"part":"query_unit"' s.h5.parts.jsonl)
  expect 2 "^s.h5.parts.jsonl: holds the finished parts of an interrupted study; --resume" "$exe" study "${opts[@]}"
  expect 2 "other options" "$exe" study "${opts[@]/30/20}" --resume
  "$exe" study "${opts[@]}" --resume > out.txt 2> err.txt || fail "--resume failed: $(tail -1 err.txt)"
  grep -Eq "resuming from s.h5.parts.jsonl \($kept query units and 0 scenes finished\)" err.txt || fail "resume message: $(head -1 err.txt)"
  [[ -e s.h5 && ! -e s.h5.parts.jsonl && ! -e s.h5.partial ]] || fail "wrong files after resume: $(ls)"
  /usr/bin/python3 -c "import h5py,sys; f=h5py.File('s.h5'); sys.exit(0 if 'query' in f and 'scene' in f else 1)" \
    || fail "the resumed study lacks a level"
  ;;
study_failure_keeps_parts)
  # Every input is read before any work: a scene that does not exist is
  # refused at once, naming the file, and nothing is written. (A study that
  # fails or is stopped later keeps its finished parts: study_interrupted_resumes.)
  expect 2 "^collide2d study: missing.json: cannot open file$" \
    "$exe" study --limit-per-family 1 --repeats 1 --scenes missing.json -o s.h5
  [[ ! -e s.h5 && ! -e s.h5.partial && ! -e s.h5.parts.jsonl ]] || fail "wrong files: $(ls)"
  ;;
datasets_from_anywhere)
  # From a folder that is not the repository, the defaults find the datasets.
  "$exe" study --limit-per-family 1 --repeats 1 --no-scenes -o s.h5 > out.txt 2> err.txt || fail "$(tail -1 err.txt)"
  grep -q "hard_queries.jsonl" out.txt || fail "the default query set was not used"
  "$exe" study --help | grep -q "$root/datasets/hard/hard_queries.jsonl" || fail "--help does not show where the default is"
  ;;
run_file_messages)
  "$exe" run -o good.h5 --until 1 > /dev/null
  head -c 3000 good.h5 > cut.h5
  expect 2 "^cut.h5: cannot open the run file \(the file is truncated: 3000 of [0-9]+ bytes\)" "$exe" replay cut.h5
  cp cut.h5 r.h5.partial
  expect 2 "^r.h5.partial: cannot open the run file \(the file is truncated" "$exe" resume r.h5
  echo "not hdf5" > text.h5
  expect 2 "^text.h5: not an HDF5 file" "$exe" replay text.h5
  ;;
fixed_range_named)
  scene far.json '{"balls": [{"position": [2e19, 0], "velocity": [0, 0], "radius": 1}]}'
  expect 2 "^far.json: balls\[0\]\.position\[0\]: outside the fixed-point range" "$exe" run far.json -o r.h5 --mode fixed
  "$exe" check far.json | grep -q "note: balls\[0\].position\[0\] lies outside the fixed-point range" || fail "check does not note it"
  printf '{"horizon": 1, "balls": [{"position": [0, 0], "velocity": [1, 3e19], "radius": 0.5}], "walls": [{"a": [2, -1], "b": [2, 1]}]}\n' > q.jsonl
  expect 2 "^q.jsonl: line 1: balls\[0\]\.velocity\[1\]: outside the fixed-point range" "$exe" toi q.jsonl --mode fixed
  "$exe" toi q.jsonl --mode strict > /dev/null || fail "strict mode refused a query it can answer"
  ;;
refused_scene_leaves_nothing)
  # `run` writes the scene's text into the run file before it parses the
  # scene from its file; a scene refused at any step after that leaves no
  # file, partial or finished, under the requested name or beside it.
  scene syntax.json '{"balls": [{"position": [0, 0], "velocity": [1, 0], "radius": 0.5}'
  scene field.json '{"balls": [{"position": [0, 0], "velocity": [1, 0], "radius": -1}]}'
  scene late.json "{$one_ball, \"walls\": [{\"a\": [0, 0], \"b\": [0, 0]}]}"
  scene overlap.json '{"balls": [{"position": [0, 0], "velocity": [1, 0], "radius": 0.5}, {"position": [0.5, 0], "velocity": [0, 0], "radius": 0.5}]}'
  scene far.json '{"balls": [{"position": [2e19, 0], "velocity": [0, 0], "radius": 1}]}'
  scene frames.json "{\"duration\": 10, \"record\": {\"interval\": 1e-12}, $one_ball}"
  for refused in "syntax.json" "field.json" "late.json" "overlap.json" "far.json --mode fixed" "frames.json"; do
    # shellcheck disable=SC2086
    expect 2 "^${refused%% *}: " "$exe" run $refused -o r.h5
    leftovers=$(ls | grep -v -e '\.json$' -e '^out.txt$' -e '^err.txt$' || true)
    [[ -z $leftovers ]] || fail "run $refused left: $leftovers"
  done
  ;;
*)
  fail "unknown case"
  ;;
esac
echo "ok: $case"
