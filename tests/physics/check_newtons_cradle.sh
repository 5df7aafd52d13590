#!/usr/bin/env bash
# newtons_cradle: ball 0 (speed 1) strikes four equal balls at rest in a row
# (gaps 1e-9) between two walls 3 apart; elastic, no gravity. Known answers:
#  - each chain hands the whole velocity on: at every frame exactly one ball
#    moves, at speed 1, and the others are at rest, all on the line y = 0.5.
#    Equal masses, head-on along x, e = 1: the exchange v' = v - (1 + e)
#    m/(2m) (v - w) = w is exact in doubles, so the tolerance is 1e-12;
#  - the motion is periodic with period 4: ball 0 meets the row at x = 0.8
#    (t = 0.3), ball 4 crosses 1.6 -> 2.9 -> 1.6 (2.6), ball 0 crosses
#    0.8 -> 0.1 -> 0.8 (1.4); at t = 20 (five periods, the last ending with
#    ball 0 back at 0.5 moving right) the state is the initial one, up to the
#    rounding of the travel times (1e-9 on positions);
#  - 8 ball-ball and 2 ball-wall events per period: 40 and 10;
#  - the run replays bit for bit.
#   check_newtons_cradle.sh COLLIDE2D datasets/scenes/newtons_cradle.json
source "$(dirname "$0")/common.sh"

PYTHONPATH="$here" "$py" - "$work/run.h5" <<'PY'
import sys
import h5py
import numpy as np
from verdict import check, finish

with h5py.File(sys.argv[1], "r") as f:
    x = f["particles/balls/position/value"][:]
    v = f["particles/balls/velocity/value"][:]
    kind = f["events/kind"][:]
speed = np.linalg.norm(v, axis=2)
order = np.sort(speed, axis=1)
check(np.all(np.abs(order[:, -1] - 1) <= 1e-12), f"one ball at speed 1 in every frame (largest deviation {np.abs(order[:, -1] - 1).max():.3g})")
check(np.all(order[:, -2] <= 1e-12), f"the other four at rest in every frame (fastest {order[:, -2].max():.3g})")
check(np.all(x[:, :, 1] == 0.5) and np.all(v[:, :, 1] == 0), "every ball stays on y = 0.5, no vertical velocity")
check(np.abs(x[-1] - x[0]).max() <= 1e-9 and np.abs(v[-1] - v[0]).max() <= 1e-12,
      f"state at t = 20 equals the initial state (positions within {np.abs(x[-1] - x[0]).max():.3g})")
n_bb, n_bw = int(np.sum(kind == 0)), int(np.sum(kind == 1))
check((n_bb, n_bw) == (40, 10), f"{n_bb} ball-ball and {n_bw} ball-wall events (40 and 10)")
finish()
PY
