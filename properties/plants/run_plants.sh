#!/bin/bash
# Planted-bug harness: does the property suite catch each planted bug?
#
#   properties/plants/run_plants.sh [--only GLOB[,GLOB...]] [--keep] [--timeout S] [--report FILE]
#
# Copies the work tree (tracked and untracked files, no build dirs, no .git)
# to a temporary directory, builds the property executables there once
# (Release, Ninja, -j2), runs the suite unplanted (it must pass), then for
# each plant (NN-name.sed: "# target: FILE" names the file it edits) applies
# it in place, rebuilds (ninja rebuilds only what depends on the file), runs
# every property at the CI size (RC_PARAMS as set by the caller; unset:
# RapidCheck's defaults with the runner's fixed seed) and restores the file.
# A plant is caught when a property (or a Catch2 check) that passes unplanted
# fails, or an executable crashes or times out; what fails unplanted is
# reported and left out. A plant not caught whose run log (every property's
# case count and distribution of tags) equals the unplanted one, times aside,
# changed nothing visible at this size: "no change", not judged. Prints a
# table and the catch rate; every outcome is also recorded in
# plants_outcomes.h5 (analysis/summarise_properties.py reads it; run label =
# plant name). --report FILE also writes the table as Markdown, with the
# date, the commit, the machine and what failed unplanted (commit it as
# properties/plants/LAST_REPORT.md). A plant that makes a scene run away is
# stopped by the checks' per-scene event cap (properties/event_cap.hpp) and
# fails in seconds; the timeout is the last resort. Exit 0 when at least 9
# in 10 judged plants are caught.
set -u
HERE="$(cd "$(dirname "$0")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
ONLY="*"
KEEP=0
REPORT=""
TIMEOUT=120  # the unplanted suite takes seconds; a plant can make a scene loop for ever
while [ $# -gt 0 ]; do
  case "$1" in
    --only) ONLY="$2"; shift 2 ;;
    --keep) KEEP=1; shift ;;
    --timeout) TIMEOUT="$2"; shift 2 ;;
    --report) REPORT="$(realpath -m "$2")"; shift 2 ;;
    -h|--help) sed -n '2,25p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_plants.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done

# --only takes a glob, or several separated by commas ('0[25]-*,2[0-5]-*').
PLANTS=()
IFS=',' read -r -a GLOBS <<<"$ONLY"
for glob in "${GLOBS[@]}"; do
  compgen -G "$HERE/$glob.sed" > /dev/null ||
    { echo "run_plants.sh: no plant matches '$glob' (names: $(cd "$HERE" && ls *.sed | sed 's/\.sed$//' | tr '\n' ' '))" >&2; exit 2; }
  for plant in "$HERE"/$glob.sed; do PLANTS+=("$plant"); done
done

WORK="$(mktemp -d /tmp/collide2d-plants.XXXXXX)"
[ "$KEEP" = 1 ] || trap 'rm -rf "$WORK"' EXIT
SRC="$WORK/src-tree"
BUILD="$WORK/build"
OUT="$WORK/out"
mkdir -p "$SRC" "$OUT"
RESULTS="${PLANT_RESULTS_DIR:-$REPO/build/plants}"
mkdir -p "$RESULTS"
RECORD="$RESULTS/plants_outcomes.h5"
rm -f "$RECORD" "$RECORD.lock"

echo "== copying the work tree to $SRC"
(cd "$REPO" && git ls-files -z --cached --others --exclude-standard | grep -zv '^build/' |
  tar --null -cf - -T - 2>/dev/null) | tar -xf - -C "$SRC" || { echo "copy failed" >&2; exit 2; }

echo "== configuring (Release, Ninja)"
cmake -S "$SRC" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >"$OUT/configure.log" 2>&1 ||
  { tail -20 "$OUT/configure.log" >&2; exit 2; }
TARGETS=()
for t in collide2d_properties collide2d_scene_properties; do
  ninja -C "$BUILD" -t targets all 2>/dev/null | grep -q "^$t:" && TARGETS+=("$t")
done
echo "   property executables: ${TARGETS[*]}"

build() { ninja -C "$BUILD" -j2 "${TARGETS[@]}" >"$1" 2>&1; }

# run_suite LABEL LOG FAILSET: every property executable; writes the set of
# failures (one line each: a property that failed, a Catch2 check that failed,
# or a crash or timeout of an executable) to FAILSET.
run_suite() {
  local label="$1" log="$2" failset="$3" exe rc
  : >"$log"
  : >"$failset.raw"
  for t in "${TARGETS[@]}"; do
    exe="$(find "$BUILD" -name "$t" -type f -perm -u+x | head -1)"
    COLLIDE2D_PROPERTY_RECORD="$RECORD" COLLIDE2D_PROPERTY_RUN_LABEL="$label" \
      COLLIDE2D_REGRESSIONS_DIR="$OUT/regressions" timeout "$TIMEOUT" "$exe" >>"$log" 2>&1
    rc=$?
    [ "$rc" -eq 124 ] && echo "timeout of $t" >>"$failset.raw"
    [ "$rc" -gt 124 ] && echo "crash of $t (exit $rc)" >>"$failset.raw"
  done
  grep -Eo '^property .*: FAILED' "$log" | sed -e 's/^property //' -e 's/: FAILED$//' >>"$failset.raw"
  grep -E '^/.*:[0-9]+: FAILED:$' "$log" | grep -v 'property_runner.hpp' | sed "s|^$SRC/||" >>"$failset.raw"
  sort -u "$failset.raw" >"$failset"
}

# The run log without times and RapidCheck's start-up line: what a plant that
# changes nothing visible at this size leaves exactly as it was.
normalised() {
  sed -E -e 's/in [0-9.e+-]+ s/in X s/g' -e 's/[0-9]+ s( |$)/X s\1/g' "$1" | grep -v '^Using configuration'
}

echo "== building the unplanted tree (takes a while the first time)"
start=$(date +%s)
build "$OUT/build-baseline.log" || { tail -30 "$OUT/build-baseline.log" >&2; exit 2; }
echo "   built in $(( $(date +%s) - start )) s"
start=$(date +%s)
run_suite baseline "$OUT/run-baseline.log" "$OUT/fail-baseline"
cp "$OUT/run-baseline.log" "$RESULTS/"
echo "   unplanted suite ran in $(( $(date +%s) - start )) s"
# What fails unplanted cannot catch anything: it is left out of the judgement.
if [ -s "$OUT/fail-baseline" ]; then
  echo "   WARNING: fails without any plant (left out of the judgement):"
  sed 's/^/     /' "$OUT/fail-baseline"
fi

printf '\n%-34s %-11s %7s %6s  %s\n' plant result build_s run_s "caught by" | tee "$RESULTS/table.txt"
: >"$RESULTS/rows.md"
caught=0 judged=0
for plant in "${PLANTS[@]}"; do
  name="$(basename "$plant" .sed)"
  target="$SRC/$(sed -n 's/^# target: //p' "$plant")"
  cp "$target" "$OUT/original"
  sed -i -f "$plant" "$target"
  if cmp -s "$target" "$OUT/original"; then
    result="not applied" by="(the pattern no longer matches)" build_s=0 run_s=0
  else
    start=$(date +%s)
    if ! build "$OUT/build-$name.log"; then
      result="no build" by="see $OUT/build-$name.log" run_s=0
      build_s=$(( $(date +%s) - start ))
    else
      build_s=$(( $(date +%s) - start ))
      start=$(date +%s)
      judged=$((judged + 1))
      run_suite "$name" "$OUT/run-$name.log" "$OUT/fail-$name"
      by=$(comm -13 "$OUT/fail-baseline" "$OUT/fail-$name" | head -3 | paste -sd ';' -)
      if [ -z "$by" ] && cmp -s <(normalised "$OUT/run-baseline.log") <(normalised "$OUT/run-$name.log"); then
        result="no change" by="(every property's distribution as unplanted; not judged)"
        judged=$((judged - 1))
      elif [ -z "$by" ]; then
        result="NOT CAUGHT" by="(distributions differ from the unplanted run)"
      else
        result="caught" caught=$((caught + 1))
      fi
      run_s=$(( $(date +%s) - start ))
      cp "$OUT/run-$name.log" "$RESULTS/"
    fi
  fi
  cp "$OUT/original" "$target"  # a new mtime: ninja rebuilds its dependents for the next plant
  printf '%-34s %-11s %7s %6s  %s\n' "$name" "$result" "$build_s" "$run_s" "$by" | tee -a "$RESULTS/table.txt"
  printf '| %s | %s | %s | %s | %s |\n' "$name" "$(sed -n '2p' "$plant" | sed 's/^# //')" "$result" "$run_s" "$(echo "$by" | sed 's/;/; /g; s/|/\\|/g')" >>"$RESULTS/rows.md"
done

if [ "$judged" -eq 0 ]; then echo "no plant built and changed what the suite sees" | tee -a "$RESULTS/table.txt"; exit 1; fi
rate=$(awk -v c="$caught" -v n="$judged" 'BEGIN { printf "%.0f", 100 * c / n }')
echo "caught $caught of $judged plants that built and changed what the suite sees ($rate %); logs and outcomes in $RESULTS" |
  tee -a "$RESULTS/table.txt"
if [ -n "$REPORT" ]; then
  {
    echo "# Planted bugs: the harness's last report"
    echo
    echo "Written by \`properties/plants/run_plants.sh --only '$ONLY' --report ...\`"
    echo "on $(date -u +%Y-%m-%d) ($(date -u +%H:%M) UTC), commit $(cd "$REPO" && git rev-parse --short HEAD)$(cd "$REPO" && git diff --quiet HEAD -- . 2>/dev/null || echo ' plus uncommitted changes'),"
    echo "$(nproc) cores, RC_PARAMS=\"${RC_PARAMS:-}\" (empty: CI size, the runner's fixed seed), timeout $TIMEOUT s."
    echo "A plant is caught when a property (or a Catch2 check) that passes unplanted fails;"
    echo "\"no change\": every property's output (cases, discards, tags) as unplanted, not judged."
    echo
    echo "| plant | what it breaks | result | run s | caught by (first three failures) |"
    echo "| --- | --- | --- | --- | --- |"
    cat "$RESULTS/rows.md"
    echo
    echo "Caught $caught of $judged plants that built and changed what the suite sees ($rate %)."
    if [ -s "$OUT/fail-baseline" ]; then
      echo
      echo "Failing without any plant (left out of the judgement):"
      sed 's/^/- /' "$OUT/fail-baseline"
    fi
  } >"$REPORT"
  echo "report written to $REPORT"
fi
[ $((caught * 10)) -ge $((judged * 9)) ]
