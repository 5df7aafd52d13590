#!/bin/bash
# analysis/scene_ensemble.py on a small pile: one line per variant and mode,
# the summary lines, and the same events and rest times when run again (the
# variants are a fixed pattern, the runs deterministic); CPU times aside.
# Usage: test_scene_ensemble.sh COLLIDE2D SOURCE_DIR. Exits non-zero on failure.
set -u
HERE="$(cd "$(dirname "$0")" && pwd)"
. "$HERE/harness.sh"
EXE="$1"
SRC="$2"
ensemble() {
  $PY "$SRC/analysis/scene_ensemble.py" "$SRC/datasets/scenes/resting_pile.json" --collide2d "$EXE" \
    --variants 2 --until 1.5 --modes strict,fixed
}
ensemble > "$TMP/first" 2> "$TMP/err" || { echo "FAIL: scene_ensemble.py exited non-zero:" >&2; cat "$TMP/err" >&2; exit 1; }
ensemble > "$TMP/second" 2>> "$TMP/err" || { echo "FAIL: second run exited non-zero" >&2; exit 1; }
runs=$(grep -c '^variant [01] \(strict\|fixed\) *events' "$TMP/first")
[ "$runs" = 4 ] || { echo "FAIL: expected 4 run lines, got $runs:" >&2; cat "$TMP/first" >&2; exit 1; }
for mode in strict fixed; do
  grep -q "^$mode *events *median" "$TMP/first" || { echo "FAIL: no $mode summary" >&2; exit 1; }
done
# Six balls come to rest on a floor and on each other: their contact forces
# are solved, so every run reports island LCPs (none would mean the summary's
# islands line went unread).
lcp_runs=$(grep -c '^variant .* island LCPs [1-9]' "$TMP/first")
[ "$lcp_runs" = 4 ] || { echo "FAIL: expected island LCPs in all 4 runs, got $lcp_runs:" >&2; cat "$TMP/first" >&2; exit 1; }
strip() { sed -e '/cpu s /d' -e 's/cpu *[0-9.]* s//' "$1"; }
if ! diff <(strip "$TMP/first") <(strip "$TMP/second") >&2; then
  echo "FAIL: the same variants gave other events or rest times" >&2
  exit 1
fi
echo "ok: 4 runs, each with island LCPs, the same events, rest times and LCPs twice"
