#!/usr/bin/env bash
# fast_box: 20 elastic balls at speed 1e5 in a unit box of four zero-thickness
# walls, ~1e6 events in 0.25 s. Known answers: no ball ever leaves the box,
# kinetic energy is kept, and the run replays bit for bit.
#   check_fast_box.sh COLLIDE2D datasets/scenes/fast_box.json
source "$(dirname "$0")/common.sh"

PYTHONPATH="$here" "$py" - "$work/obs.json" <<'PY'
import json, sys
o = json.load(open(sys.argv[1]))
from verdict import check, finish

# The scene is what it claims: enough events for the checks to mean something.
check(o["ball_wall_events"] > 300000 and o["ball_ball_events"] > 100000,
      f"{o['ball_wall_events']} ball-wall and {o['ball_ball_events']} ball-ball events (> 3e5, > 1e5)")

# Escape: every centre stays in [r, 1 - r]^2 up to 1e-9 of the box. A ball
# that passes through a wall never comes back in (the walls are two-sided and
# meet at the corners), so checking every frame catches every escape. The
# exact contact leaves a centre r from the wall up to rounding (~1e-16).
check(o["escape_max_rel"] <= 1e-9, f"escape {o['escape_max_rel']:.3g} of the box (<= 1e-9)")
check(o["deepest_overlap"] is not None and o["deepest_overlap"] <= 1e-9,
      f"deepest overlap {o['deepest_overlap']} (<= 1e-9, the box is 1 wide)")

# Energy: an elastic collision in doubles changes the kinetic energy by a few
# ulp (~1e-16 relative); even adding up linearly over ~1e6 events that is
# 1e-10, so 1e-9 is a bound that only a wrong collision can break.
check(o["energy_max_rel_change"] <= 1e-9, f"energy change {o['energy_max_rel_change']:.3g} relative (<= 1e-9)")

# The virial identity (gas_observables.py) ties every recorded impulse to the
# motion: [sum x.p] = 2 int K dt + sum J (r_a + r_b) + sum_wall J n.x. Its
# terms are ~2.5e10 and cancel to rounding (~1e-15); one missed wall hit
# (J up to 2e5 at ~0.5 from the centre) leaves up to ~4e-6 (one zeroed
# impulse, tried by hand: 1.9e-6). Bound: 1e-9.
v = o["virial"]
check(abs(v["residual_rel"]) <= 1e-9, f"virial identity residual {v['residual_rel']:.3g} (<= 1e-9)")
finish()
PY
