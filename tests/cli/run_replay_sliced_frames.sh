#!/bin/bash
# A scene of over 2^15 balls has its frames written in slices of 2^15 balls
# as they are made (RunWriter::append_frame_slice): replay, which simulates
# again and compares whole frames, finds every frame and event of the file
# the same, bit for bit (in fixed mode the raw words too), and the file's
# frames are chunked one frame by 2^15 balls.
set -euo pipefail
exe=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" bench sim --sizes 40000 --etas 0.45 --collisions 40000 --no-settling --modes strict,fixed --keep "$dir"
for mode in strict fixed; do
  run="$dir/gas_40000_eta0.45-$mode.h5"
  "$exe" replay "$run"
  /usr/bin/python3 - "$run" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
p = f["particles/balls/position/value"]
assert p.shape[1:] == (40000, 2) and p.shape[0] >= 10, p.shape
assert p.chunks == (1, 32768, 2), p.chunks
assert f["particles/balls/position/time"].shape[0] == p.shape[0]
print(sys.argv[1], p.shape[0], "frames, chunks", p.chunks)
PY
done
