#!/usr/bin/python3
"""Write a small synthetic collide2d run file (H5MD 1.1 layout of SPEC.md).

Three balls fall under gravity in a 10 x 8 box with a fixed ball in the
middle. Motion between collisions is an exact parabola; contact times are
roots of polynomials (np.roots), so the run is a tiny event-driven simulation
in numpy, independent of the C++ simulator. The floor has restitution 0.95,
so the total energy steps down at floor bounces and is constant otherwise.

  make_demo_run.py OUT.h5 [--form attr|dataset|json] [--duration T]

--form chooses how /parameters is written: `attr` (scene JSON as attribute
`scene`, radius/walls datasets), `dataset` (scene JSON as the fixed-length
scalar string dataset `scene_json`, as collide2d writes it, with radius/walls
datasets) or `json` (scene attribute only: readers must take
radius and walls from the JSON). All three exercise plot_run.py.
"""
import argparse
import json
import sys

import h5py
import numpy as np

G = np.array([0.0, -9.81])
# Axis-aligned box walls as (inward normal, offset): n . x >= c inside.
WALLS = [((0, 0), (10, 0)), ((10, 0), (10, 8)), ((10, 8), (0, 8)), ((0, 8), (0, 0))]
WALL_NORMALS = [((0, 1), 0.0), ((-1, 0), -10.0), ((0, -1), -8.0), ((1, 0), 0.0)]
WALL_E = [0.95, 1.0, 1.0, 1.0]


def scene_dict(duration):
    balls = [
        {"position": [2.0, 6.0], "velocity": [2.5, 0.0], "radius": 0.5, "mass": 1.0},
        {"position": [7.5, 5.0], "velocity": [-1.5, 1.0], "radius": 0.4, "mass": 0.64},
        {"position": [4.0, 1.5], "velocity": [1.0, 6.0], "radius": 0.6, "mass": 1.44},
        {"position": [5.5, 4.0], "velocity": [0.0, 0.0], "radius": 0.7, "fixed": True},
    ]
    walls = [{"a": list(a), "b": list(b), "restitution": e} for (a, b), e in zip(WALLS, WALL_E)]
    return {"name": "demo-box", "gravity": G.tolist(), "duration": duration,
            "restitution": 1.0, "walls": walls, "balls": balls,
            "record": {"interval": 0.02}}


def first_root(coeffs, rate, t_max):
    """Smallest t in (0, t_max] with poly(coeffs)(t) = 0 and rate(t) < 0."""
    best = np.inf
    for r in np.roots(coeffs):
        if abs(r.imag) > 1e-9 * max(1.0, abs(r.real)):
            continue
        t = r.real
        if 1e-10 < t <= t_max and t < best and rate(t) < 0:
            best = t
    return best


def simulate(scene):
    balls = scene["balls"]
    n = len(balls)
    p = np.array([b["position"] for b in balls], float)
    v = np.array([b["velocity"] for b in balls], float)
    r = np.array([b["radius"] for b in balls], float)
    m = np.array([b.get("mass", 1.0) for b in balls], float)
    fixed = np.array([b.get("fixed", False) for b in balls])
    acc = np.where(fixed[:, None], 0.0, G[None, :])
    interval, duration = scene["record"]["interval"], scene["duration"]
    frame_times = np.arange(0.0, duration + 0.5 * interval, interval)
    pos, vel, events = [], [], []
    t, k = 0.0, 0

    def state(dt):
        return p + v * dt + 0.5 * acc * dt * dt, v + acc * dt

    while True:
        # Next event: (time, kind, a, b).
        nxt = (np.inf, None, None, None)
        for i in np.flatnonzero(~fixed):
            for w, (nrm, c) in enumerate(WALL_NORMALS):
                nrm = np.array(nrm, float)
                coeffs = [0.5 * nrm @ acc[i], nrm @ v[i], nrm @ p[i] - c - r[i]]
                te = first_root(coeffs, lambda s: nrm @ (v[i] + acc[i] * s), duration - t)
                if te < nxt[0]:
                    nxt = (te, 1, i, w)
            for j in range(n):
                if j == i or (not fixed[j] and j < i):
                    continue
                dp, dv, da = p[i] - p[j], v[i] - v[j], 0.5 * (acc[i] - acc[j])
                # |dp + dv t + da t^2|^2 - R^2, a quartic (quadratic if da = 0).
                coeffs = [da @ da, 2 * dv @ da, dv @ dv + 2 * dp @ da, 2 * dp @ dv,
                          dp @ dp - (r[i] + r[j]) ** 2]
                rate = lambda s: (dp + dv * s + da * s * s) @ (dv + 2 * da * s)
                te = first_root(coeffs, rate, duration - t)
                if te < nxt[0]:
                    nxt = (te, 0, i, j)
        dt_ev, kind, a, b = nxt
        t_end = t + dt_ev if np.isfinite(dt_ev) else np.inf
        while k < len(frame_times) and frame_times[k] < t_end:
            pk, vk = state(frame_times[k] - t)
            pos.append(pk)
            vel.append(vk)
            k += 1
        if not np.isfinite(dt_ev) or len(events) > 100000:
            break
        p, v = state(dt_ev)
        t = t_end
        if kind == 1:
            nrm = np.array(WALL_NORMALS[b][0], float)
            e, inv_m = WALL_E[b], 1.0 / m[a]
        else:
            nrm = (p[a] - p[b]) / np.linalg.norm(p[a] - p[b])
            e, inv_m = 1.0, 1.0 / m[a] + (0.0 if fixed[b] else 1.0 / m[b])
        vn = (v[a] - (0.0 if kind == 1 else v[b])) @ nrm
        impulse = -(1.0 + e) * vn / inv_m
        v[a] += impulse / m[a] * nrm
        if kind == 0 and not fixed[b]:
            v[b] -= impulse / m[b] * nrm
        events.append((t, kind, a, b, abs(impulse)))

    pos, vel = np.array(pos), np.array(vel)
    mov = ~fixed
    energy = (0.5 * m[mov] * (vel[:, mov] ** 2).sum(-1)
              - m[mov] * (pos[:, mov] @ G)).sum(-1)
    return frame_times[:len(pos)], pos, vel, energy, events, r


def write(path, scene, form):
    times, pos, vel, energy, events, radius = simulate(scene)
    steps = np.arange(len(times), dtype=np.int64)
    text = json.dumps(scene, indent=1)
    with h5py.File(path, "w") as f:
        h = f.create_group("h5md")
        h.attrs["version"] = np.array([1, 1], dtype=np.int32)
        h.create_group("author").attrs["name"] = "make_demo_run.py"
        c = h.create_group("creator")
        c.attrs["name"] = "collide2d"
        c.attrs["version"] = "demo"
        balls = f.create_group("particles/balls")
        box = balls.create_group("box")
        box.attrs["dimension"] = np.int32(2)
        box.attrs["boundary"] = np.array([b"none", b"none"], dtype="S4")
        for group, data in (("particles/balls/position", pos),
                            ("particles/balls/velocity", vel),
                            ("observables/energy", energy)):
            g = f.create_group(group)
            g["step"], g["time"], g["value"] = steps, times, data
        ev = np.array(events, dtype=float).reshape(-1, 5)
        f["events/time"] = ev[:, 0]
        f["events/kind"] = ev[:, 1].astype(np.int32)
        f["events/a"] = ev[:, 2].astype(np.int64)
        f["events/b"] = ev[:, 3].astype(np.int64)
        f["events/impulse"] = ev[:, 4]
        par = f.create_group("parameters")
        if form == "dataset":
            par["scene_json"] = np.bytes_(text)
        else:
            par.attrs["scene"] = text
        if form != "json":
            par["radius"] = radius
            par["walls"] = np.array([a + b for a, b in WALLS], float)
    return len(times), len(events)


def main():
    ap = argparse.ArgumentParser(description="Write a synthetic collide2d run file (H5MD).")
    ap.add_argument("out", help="output HDF5 file")
    ap.add_argument("--form", choices=["attr", "dataset", "json"], default="attr",
                    help="how /parameters stores the scene and radii (default attr)")
    ap.add_argument("--duration", type=float, default=8.0, help="simulated time (default 8)")
    args = ap.parse_args()
    try:
        frames, n_events = write(args.out, scene_dict(args.duration), args.form)
    except OSError as e:
        print(f"make_demo_run.py: {args.out}: cannot write: {e}", file=sys.stderr)
        sys.exit(2)
    print(f"{args.out}: {frames} frames, {n_events} events", file=sys.stderr)


if __name__ == "__main__":
    main()
