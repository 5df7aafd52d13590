#!/usr/bin/env bash
# `collide2d replay` compares a fixed-mode run's raw Q63.64 values too: one
# low word changed by 1 (2^-64, below what the double shows) is a mismatch
# naming frame, ball and field.
set -euo pipefail
exe=$1
scene=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$exe" run "$scene" -o "$work/fixed.h5" --mode fixed --until 0.2 > /dev/null
"$exe" replay "$work/fixed.h5" > /dev/null

/usr/bin/python3 - "$work/fixed.h5" <<'PY'
import sys
import h5py
with h5py.File(sys.argv[1], "r+") as f:
    v = f["/particles/balls/velocity_raw/value"]
    w = v[3, 1, 1]
    w[1] = w[1] + 1 if w[1] < 2**63 - 1 else w[1] - 1
    v[3, 1, 1] = w
PY

set +e
out=$("$exe" replay "$work/fixed.h5")
rc=$?
set -e
if [[ $rc -ne 1 || "$out" != *"MISMATCH at frame 3 "*"ball 1, velocity_raw.y"* ]]; then
  echo "replay did not name the changed raw value (exit $rc): $out" >&2
  exit 1
fi
echo "replay names a raw difference: ok"
