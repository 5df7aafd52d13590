#!/bin/bash
# analysis/unseen_scenes.py on its two smallest scenes: a table row each,
# both finished; every scene it writes is one `collide2d check` accepts, and
# the same bytes when made again (fixed seeds: the set is the same on every
# machine); a scene name it does not have is refused in one line.
# Usage: test_unseen_scenes.sh COLLIDE2D SOURCE_DIR. Exits non-zero on failure.
set -u
HERE="$(cd "$(dirname "$0")" && pwd)"
. "$HERE/harness.sh"
EXE="$1"
SRC="$2"
unseen() {
  $PY "$SRC/analysis/unseen_scenes.py" --collide2d "$EXE" --limit 60 --keep "$1" --only column_8_e070,pyramid_21_e040
}
unseen "$TMP/a" > "$TMP/table" 2> "$TMP/err" || { echo "FAIL: unseen_scenes.py exited non-zero:" >&2; cat "$TMP/err" >&2; exit 1; }
rows=$(grep -c '^| \(column_8_e070\|pyramid_21_e040\) | .* | finished | ' "$TMP/table")
[ "$rows" = 2 ] || { echo "FAIL: expected 2 finished rows, got $rows:" >&2; cat "$TMP/table" >&2; exit 1; }
unseen "$TMP/b" > /dev/null 2>> "$TMP/err" || { echo "FAIL: second run exited non-zero" >&2; exit 1; }
for f in "$TMP"/a/*.json; do
  "$EXE" check "$f" > /dev/null || { echo "FAIL: collide2d check refuses $(basename "$f")" >&2; exit 1; }
  cmp -s "$f" "$TMP/b/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs when made again" >&2; exit 1; }
done
[ "$(ls "$TMP"/a/*.json | wc -l)" = 2 ] || { echo "FAIL: expected 2 scene files" >&2; exit 1; }
expect_exit2 "unknown scene" $PY "$SRC/analysis/unseen_scenes.py" --collide2d "$EXE" --only no_such_scene
expect_exit2 "no program" $PY "$SRC/analysis/unseen_scenes.py" --collide2d "$TMP/none" --only column_8_e070
[ "$failures" = 0 ] || exit 1
echo "ok: unseen_scenes.py"
