#!/usr/bin/python3
"""Write a small synthetic run file (the H5MD layout collide2d writes) for
tests/analysis/test_rest_report.sh, clean or with one planted fault.

    make_rest_run.py OUT.h5 [--fault none|overlap|ball_overlap|energy|chatter|elastic_energy]

The clean run (6 s, frames every 0.02, g = 9.81, restitution 0.5): ball 0
(r = 0.1) falls from rest onto the floor y = 0 on an exact parabola and stops
dead on landing at t = 0.5 (one ball-wall event); balls 1 and 2 (r = 0.1,
masses 2 and 0.5) rest on the floor in exact contact (centres at y = r, 0.2
apart); ball 3 (r = 0.1) is fixed in mid-air. Every frame's energy is
computed from its state (sum of 1/2 m v^2 - m a.p over moving balls), so it
is constant to rounding while ball 0 falls. Besides the landing there are
events at the rate of 0.5 per moving ball per second over the last third
(three moving balls: 3 events in those 2 s): below the bound of 1.

Faults, each breaking exactly one check of rest_report.py --check:
  overlap         ball 1 sinks 1e-5 r into the floor from t = 2 on (its energy
                  drops: no rise);
  ball_overlap    ball 2 sits 1e-5 r inside ball 1 from t = 2 on;
  energy          ball 2 is lifted by 1e-6 from t = 2 on: the energy rises by
                  m g 1e-6 = 4.9e-6 ~ 3e-7 S once;
  chatter         60 events over the last third: 10 per ball per second;
  elastic_energy  the energy fault with restitution 1 for the walls: the
                  energy check does not apply, --check passes.
"""
import argparse
import json

import h5py
import numpy as np

G = 9.81
R = 0.1
DT, FRAMES = 0.02, 301          # 6 s
T_LAND = 0.5
T_FAULT = 2.0


def scene(fault):
    walls = [{"a": [0, 0], "b": [2, 0]}, {"a": [2, 0], "b": [2, 2]}, {"a": [0, 2], "b": [0, 0]}]
    if fault == "elastic_energy":
        for w in walls:
            w["restitution"] = 1.0
    h = 0.5 * G * T_LAND ** 2
    balls = [{"position": [0.5, R + h], "velocity": [0, 0], "radius": R},
             {"position": [1.0, R], "velocity": [0, 0], "radius": R, "mass": 2.0},
             {"position": [1.2, R], "velocity": [0, 0], "radius": R, "mass": 0.5},
             {"position": [1.6, 1.0], "velocity": [0, 0], "radius": R, "fixed": True}]
    return {"name": f"synthetic_{fault}", "gravity": [0.0, -G], "duration": (FRAMES - 1) * DT,
            "restitution": 0.5, "record": {"interval": DT}, "walls": walls, "balls": balls}


def frames(sc, fault):
    """Positions and velocities (frames x N x 2) at the record times."""
    t = np.arange(FRAMES) * DT
    p0 = np.array([b["position"] for b in sc["balls"]], float)
    pos = np.repeat(p0[None], FRAMES, axis=0)
    vel = np.zeros_like(pos)
    falling = t < T_LAND
    pos[falling, 0, 1] = p0[0, 1] - 0.5 * G * t[falling] ** 2
    vel[falling, 0, 1] = -G * t[falling]
    pos[~falling, 0, 1] = R
    late = t >= T_FAULT
    if fault == "overlap":
        pos[late, 1, 1] = R - 1e-5 * R
    elif fault == "ball_overlap":
        pos[late, 2, 0] = p0[1, 0] + 2 * R - 1e-5 * R
    elif fault in ("energy", "elastic_energy"):
        pos[late, 2, 1] = R + 1e-6
    return t, pos, vel


def energy(sc, pos, vel):
    m = np.array([b.get("mass", 1.0) for b in sc["balls"]])
    moving = np.array([not b.get("fixed", False) for b in sc["balls"]])
    e = 0.5 * m * np.sum(vel * vel, axis=2) - m * (-G) * pos[..., 1]
    return e[:, moving].sum(axis=1)


def events(fault):
    """(time, kind, a, b): the landing, then 3 (chatter: 60) events spread
    evenly over the last third."""
    t_end = (FRAMES - 1) * DT
    count = 60 if fault == "chatter" else 3
    late = t_end - t_end / 3 + (np.arange(count) + 0.5) * (t_end / 3) / count
    time = np.concatenate([[T_LAND], late])
    n = len(time)
    return time, np.ones(n, np.int32), np.arange(n, dtype=np.int32) % 3, np.zeros(n, np.int32)


def series(group, name, step, time, value):
    g = group.create_group(name)
    g["step"], g["time"], g["value"] = step, time, value


def write(path, fault):
    sc = scene(fault)
    t, pos, vel = frames(sc, fault)
    with h5py.File(path, "w") as f:
        f.create_group("h5md").attrs["version"] = [1, 1]
        balls = f.create_group("particles/balls")
        step = np.arange(FRAMES, dtype=np.int64)
        series(balls, "position", step, t, pos)
        series(balls, "velocity", step, t, vel)
        series(f.require_group("observables"), "energy", step, t, energy(sc, pos, vel))
        ev_t, kind, a, b = events(fault)
        ev = f.create_group("events")
        ev["time"], ev["kind"], ev["a"], ev["b"] = ev_t, kind, a, b
        ev["impulse"] = np.ones(len(ev_t))
        par = f.create_group("parameters")
        par["scene_json"] = json.dumps(sc)
        par["radius"] = [b["radius"] for b in sc["balls"]]
        par["mass"] = [b.get("mass", 1.0) for b in sc["balls"]]
        par["walls"] = np.array([w["a"] + w["b"] for w in sc["walls"]], float)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out")
    ap.add_argument("--fault", default="none",
                    choices=["none", "overlap", "ball_overlap", "energy", "chatter", "elastic_energy"])
    args = ap.parse_args()
    write(args.out, args.fault)


if __name__ == "__main__":
    main()
