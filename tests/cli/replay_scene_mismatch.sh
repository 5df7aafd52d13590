#!/usr/bin/env bash
# `collide2d replay` (and resume) trust /parameters/scene_json only when it is
# the scene the file's own datasets describe. A file edited to hold a scene of
# one ball while its frames hold two made replay read past the end of the
# replayed frame (AddressSanitizer: heap-buffer-overflow in frame_difference;
# found by review, see fuzz/README.md); it is refused with exit 2 now. And a
# scene_json stored as h5py writes strings by default (ASCII, not UTF-8) is
# read, not refused for want of a conversion path.
set -euo pipefail
exe=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat > "$work/two.json" <<'JSON'
{"name": "two", "duration": 0.1, "balls": [{"position": [0, 0], "velocity": [1, 0], "radius": 0.5}, {"position": [5, 0], "radius": 0.5}]}
JSON
"$exe" run "$work/two.json" -o "$work/run.h5" > /dev/null

# The same scene, stored as an ASCII string: replay must read it and agree.
/usr/bin/python3 - "$work/run.h5" "$work/two.json" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "r+") as f:
    text = open(sys.argv[2]).read()
    del f["parameters/scene_json"]
    f["parameters"].create_dataset("scene_json", data=np.bytes_(text))
    assert f["parameters/scene_json"].id.get_type().get_cset() == h5py.h5t.CSET_ASCII
PY
out=$("$exe" replay "$work/run.h5")
if [[ "$out" != *"identical"* ]]; then
  echo "replay of an ASCII scene_json: expected identical, got: $out" >&2
  exit 1
fi

# One ball fewer in scene_json than in /parameters/radius: refused.
/usr/bin/python3 - "$work/run.h5" <<'PY'
import sys
import h5py
one = '{"name": "two", "duration": 0.1, "balls": [{"position": [0, 0], "velocity": [1, 0], "radius": 0.5}]}'
with h5py.File(sys.argv[1], "r+") as f:
    del f["parameters/scene_json"]
    f["parameters"].create_dataset("scene_json", data=one.encode(), dtype=h5py.string_dtype("utf-8", len(one) + 1))
PY
set +e
err=$("$exe" replay "$work/run.h5" 2>&1 >/dev/null)
rc=$?
set -e
if [[ $rc -ne 2 || "$err" != *"run.h5: /parameters cannot be read back: scene_json holds 1 balls, /parameters/radius 2"* ]]; then
  echo "replay of a scene_json that disagrees with /parameters: expected exit 2 naming both counts, got $rc: $err" >&2
  exit 1
fi
echo "replay reads ASCII scene_json and refuses one that disagrees with /parameters: ok"
