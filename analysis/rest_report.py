#!/usr/bin/python3
"""Rest report of a collide2d run file: does a pile come to rest cleanly?

  rest_report.py RUN.h5 [--check] [--json]

Figures, over the whole run (SPEC.md "Run file (HDF5)"):

  duration     time of the last frame minus that of the first; frames.
  balls        moving and fixed (the scene's "fixed" flags).
  events       every collision in /events/time.
  event rate   events per moving ball per simulated second over the last
               third and the last tenth of the run: events with time in
               (t_end - T/3, t_end] (resp. T/10) divided by the number of
               moving balls and the window's length. A pile at rest has no
               events (resting contacts are held, not bounced); a pile that
               chatters (inelastic collapse, hops, a stalled wedge) has
               thousands. A gas or a scene still settling has many too: the
               figure means "at rest" only for scenes meant to come to rest.
  overlap      deepest overlap over all frames: ball-ball (r_i + r_j - |p_i -
               p_j|) and ball-wall (r - distance from the centre to the
               segment: walls are two-sided with round ends), in scene units
               and as a fraction of the smallest radius r_min; 0 if nothing
               ever overlaps. Only frames are looked at, not the motion
               between them.
  energy rise  the largest increase of /observables/energy from one frame to
               the next, absolute and relative to the energy scale
               S = max over frames of sum over moving balls of
               m (1/2 |v|^2 + |a . p|) (a: the ball's own acceleration, else
               the scene's gravity), and the number of frame pairs where it
               rose by more than 1e-12 S.
  still from   the first frame time from which on the largest speed of any
               moving ball stays below 1e-3 sqrt(g r_min) for the rest of the
               run (g: the largest |a| of a moving ball), or "never". At that
               speed a ball moves 1e-3 r_min in the time sqrt(r_min / g) it
               takes to fall r_min/2: it is still on the scale of the balls.

--check exits 1 (naming each failure) when
  - the event rate over the last third exceeds 1 per moving ball per second:
    one event per ball per second is already far more than a settled pile
    makes (none) and far less than chatter makes (thousands). A scene still
    moving in its last third (a gas, a pile not yet settled) fails it
    honestly: the check is for scenes meant to come to rest.
  - the deepest overlap exceeds 1e-6 r_min, the engine's rest height h_rest
    (src/collide2d/sim/simulate.hpp): exact contacts leave overlaps of a few ulps of
    the coordinates (~1e-16 of the scene's size), and the rest rules let a
    ball sink into a support by at most h_rest (a ball creeping for the
    whole run reaches the bound itself, with no margin for rounding); a
    deeper overlap is a contact the engine lost.
  - the energy rose by more than 1e-12 S between two frames, when every
    restitution in the scene (the default, every ball's and every wall's) is
    below 1, so that every collision takes energy out. Each frame's energy is
    a sum of N terms each rounded to a few eps of its share of S: the sum is
    within ~(N + 3) eps S ~ 7e-14 S of the truth for N = 300, so two frames
    differ by rounding by less than 1e-12 S for N up to ~2000. A larger rise
    is energy made by the engine (a hop, a push out of overlap). With a
    restitution of 1 anywhere an elastic contact may keep energy only to
    rounding at every one of its events, so the check does not apply.
--json prints every figure as one JSON object (the verdicts under "check").
Exit codes: 0 success (and, with --check, every check passed), 1 a check
failed, 2 bad input or usage (one line on stderr).
"""
import argparse
import json
import math
import os
import sys

import h5py
import numpy as np
from cli_support import InputError, OneLineParser, finite_or_null, text_of  # noqa: E402

PROG = "rest_report.py"
EVENT_RATE_BOUND = 1.0        # events per moving ball per second, last third
OVERLAP_BOUND = 1e-6          # of the smallest radius
ENERGY_RISE_BOUND = 1e-12     # of the energy scale S
STILL_FRACTION = 1e-3         # of sqrt(g r_min)
PAIR_CHUNK = 16               # frames per bounding-box chunk (ball-ball overlap)
WALL_CHUNK_ELEMENTS = 2_000_000


# ---------------------------------------------------------------- reading


def param(par, name):
    """A parameter stored as a dataset or an attribute of /parameters, or None."""
    return None if par is None else par[name][()] if name in par else par.attrs.get(name)


def open_run(path):
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file")
    try:
        return h5py.File(path, "r")
    except OSError:
        try:  # a run being written, or killed while writing, carries the SWMR flag
            return h5py.File(path, "r", swmr=True)
        except OSError:
            raise InputError(f"{path}: not an HDF5 file (or not readable)")


def dataset(f, path, name):
    if name not in f or not isinstance(f[name], h5py.Dataset):
        raise InputError(f"{path}: missing dataset /{name}")
    return f[name]


def events_after(times, t_cut):
    """How many entries of the sorted dataset `times` are > t_cut, by
    bisection on the file (a chattering run holds 1e7 events or more)."""
    lo, hi = 0, len(times)
    while lo < hi:
        mid = (lo + hi) // 2
        if times[mid] > t_cut:
            hi = mid
        else:
            lo = mid + 1
    return len(times) - lo


def read_scene(path, par):
    text = param(par, "scene_json")
    text = param(par, "scene") if text is None else text
    if text is None:
        raise InputError(f"{path}: no scene JSON in /parameters (scene_json)")
    try:
        scene = json.loads(text_of(text))
    except (ValueError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: /parameters/scene_json is not JSON: {e}")
    if not isinstance(scene, dict) or not all(
            isinstance(scene.get(kind, []), list) and all(isinstance(o, dict) for o in scene.get(kind, []))
            for kind in ("balls", "walls")):
        raise InputError(f"{path}: /parameters/scene_json is not a scene object")
    return scene


def per_ball(path, par, scene, name, n, default):
    """/parameters/<name> if stored, else the scene's balls[].<name>."""
    values = param(par, name)
    if values is None:
        values = [b.get(name, default) for b in scene.get("balls", [])]
    try:
        values = np.asarray(values, float).reshape(-1)
    except (TypeError, ValueError):
        raise InputError(f"{path}: no /parameters/{name} and no numbers balls[].{name} in the scene JSON")
    if len(values) != n:
        raise InputError(f"{path}: /parameters/{name}: {len(values)} values for {n} balls")
    return values


def load(path):
    """Frames, per-ball constants, walls, scene and event counts of a run."""
    with open_run(path) as f:
        t = dataset(f, path, "particles/balls/position/time")[:]
        pos = dataset(f, path, "particles/balls/position/value")[:]
        vel = dataset(f, path, "particles/balls/velocity/value")[:]
        energy = dataset(f, path, "observables/energy/value")[:]
        ev_time = dataset(f, path, "events/time")
        if pos.ndim != 3 or pos.shape[2] != 2 or vel.shape != pos.shape:
            raise InputError(f"{path}: position and velocity must both be frames x N x 2")
        k = min(len(t), len(pos), len(vel), len(energy))  # a file caught mid-write
        if k < 2:
            raise InputError(f"{path}: fewer than two frames")
        t, pos, vel, energy = t[:k], pos[:k], vel[:k], energy[:k]
        if pos.shape[1] == 0:
            raise InputError(f"{path}: no balls")
        par = f["parameters"] if "parameters" in f else None
        scene = read_scene(path, par)
        n = pos.shape[1]
        walls = param(par, "walls")
        if walls is None:
            walls = [w["a"] + w["b"] for w in scene.get("walls", [])]
        run = {"t": t, "pos": pos, "vel": vel, "energy": energy, "scene": scene,
               "radius": per_ball(path, par, scene, "radius", n, None),
               "mass": per_ball(path, par, scene, "mass", n, 1.0),
               "walls": np.asarray(walls, float).reshape(-1, 4), "events": len(ev_time)}
        t_end, span = float(t[-1]), float(t[-1] - t[0])
        beyond = events_after(ev_time, t_end)  # a file caught mid-write may hold later events
        run["events_last"] = {frac: events_after(ev_time, t_end - span * frac) - beyond
                              for frac in (1 / 3, 1 / 10)}
    return run


# ------------------------------------------------------------------ scene

def moving_mask(scene, n):
    balls = scene.get("balls", [])
    if len(balls) != n:
        return np.ones(n, bool)
    return np.array([not b.get("fixed", False) for b in balls])


def accelerations(scene, moving):
    """Each ball's acceleration (N x 2): its own, else gravity; 0 if fixed."""
    gravity = scene.get("gravity", [0.0, 0.0])
    balls = scene.get("balls", [])
    acc = np.array([b.get("acceleration", gravity) for b in balls] if len(balls) == len(moving)
                   else [gravity] * len(moving), float).reshape(-1, 2)
    acc[~moving] = 0.0
    return acc


def elastic_somewhere(scene):
    """Names of the restitutions of 1 in the scene (the default, balls, walls)."""
    default = scene.get("restitution", 1.0)
    found = ["the scene default"] if default >= 1 else []
    for kind in ("balls", "walls"):
        found += [f"{kind}[{i}]" for i, o in enumerate(scene.get(kind, [])) if o.get("restitution", default) >= 1]
    return found


# ---------------------------------------------------------------- figures

def event_rates(run, n_moving):
    """Events per moving ball per second over the last third and tenth."""
    span = float(run["t"][-1] - run["t"][0])
    out = {}
    for frac, key in ((1 / 3, "last_third"), (1 / 10, "last_tenth")):
        window = span * frac
        ok = n_moving > 0 and window > 0
        out[key] = run["events_last"][frac] / (n_moving * window) if ok else None
    return out


def boxes_meeting(lo, hi):
    """Index arrays (i < j) of the pairs whose boxes [lo, hi] (N x 2) meet:
    sweep and prune, the boxes sorted by their left edge, each paired with
    the boxes whose left edge lies between its own edges, then the y test."""
    order = np.argsort(lo[:, 0], kind="stable")
    left = lo[order, 0]
    first = np.arange(1, len(order))
    end = np.searchsorted(left, hi[order, 0], side="right")[:-1]
    counts = np.maximum(end - first, 0)
    a = np.repeat(first - 1, counts)
    b = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts) + np.repeat(first, counts)
    i, j = order[a], order[b]
    keep = (lo[i, 1] <= hi[j, 1]) & (lo[j, 1] <= hi[i, 1])
    i, j = i[keep], j[keep]
    return np.minimum(i, j), np.maximum(i, j)


def deepest_ball_ball(pos, radius):
    """(depth, frame, i, j) of the deepest ball-ball overlap (depth < 0: the
    closest approach). Frames go in chunks; a pair is measured in a chunk only
    if the two balls' bounding boxes over the chunk, grown by their radii,
    meet, so a settled pile costs its contacts, not all N^2/2 pairs."""
    best = (-math.inf, 0, 0, 0)
    for start in range(0, len(pos), PAIR_CHUNK):
        chunk = pos[start:start + PAIR_CHUNK]
        i, j = boxes_meeting(chunk.min(0) - radius[:, None], chunk.max(0) + radius[:, None])
        if len(i) == 0:
            continue
        d = chunk[:, i] - chunk[:, j]
        depth = (radius[i] + radius[j])[None, :] - np.hypot(d[..., 0], d[..., 1])
        f, k = np.unravel_index(np.argmax(depth), depth.shape)
        if depth[f, k] > best[0]:
            best = (float(depth[f, k]), start + int(f), int(i[k]), int(j[k]))
    return best


def deepest_ball_wall(pos, radius, walls):
    """(depth, frame, ball, wall) of the deepest ball-wall overlap: r minus
    the distance from the centre to the segment (round ends included)."""
    best = (-math.inf, 0, 0, 0)
    if len(walls) == 0:
        return best
    a, ab = walls[:, :2], walls[:, 2:] - walls[:, :2]
    ab2 = np.maximum(np.sum(ab * ab, axis=1), np.finfo(float).tiny)  # a zero-length wall: its point
    step = max(1, WALL_CHUNK_ELEMENTS // (pos.shape[1] * len(walls)))
    for start in range(0, len(pos), step):
        ap = pos[start:start + step, :, None, :] - a[None, None]            # F x N x W x 2
        s = np.clip(np.sum(ap * ab, axis=3) / ab2, 0.0, 1.0)
        d = ap - s[..., None] * ab
        depth = radius[None, :, None] - np.hypot(d[..., 0], d[..., 1])
        f, b, w = np.unravel_index(np.argmax(depth), depth.shape)
        if depth[f, b, w] > best[0]:
            best = (float(depth[f, b, w]), start + int(f), int(b), int(w))
    return best


def energy_rise(run, moving, acc):
    """Largest frame-to-frame rise of the energy, the scale S and how many
    frame pairs rose by more than ENERGY_RISE_BOUND S."""
    m, v, p = run["mass"][moving], run["vel"][:, moving], run["pos"][:, moving]
    per_ball = m * (0.5 * np.sum(v * v, axis=2) + np.abs(np.sum(acc[moving] * p, axis=2)))
    scale = float(per_ball.sum(axis=1).max()) if per_ball.size else 0.0
    rise = np.diff(run["energy"])
    k = int(np.argmax(rise))
    top = max(0.0, float(rise[k]))
    return {"max_rise": top, "between": [float(run["t"][k]), float(run["t"][k + 1])] if top > 0 else None,
            "scale": scale, "max_rise_relative": top / scale if scale > 0 else None,
            "frames_rising": int(np.sum(rise > ENERGY_RISE_BOUND * scale))}


def still_from(run, moving, acc, r_min):
    """First frame time from which every moving ball stays slower than
    STILL_FRACTION sqrt(g r_min); None: never; threshold None: no g."""
    g = float(np.max(np.hypot(acc[moving, 0], acc[moving, 1]))) if moving.any() else 0.0
    if g <= 0:
        return None, None
    threshold = STILL_FRACTION * math.sqrt(g * r_min)
    v = run["vel"][:, moving]
    fast = np.flatnonzero(np.max(np.hypot(v[..., 0], v[..., 1]), axis=1) >= threshold)
    if len(fast) == 0:
        return float(run["t"][0]), threshold
    last = fast[-1]
    return (float(run["t"][last + 1]) if last + 1 < len(run["t"]) else None), threshold


def overlap_figures(run, r_min):
    """Deepest ball-ball and ball-wall overlaps (0: none), the deeper one
    relative to r_min, and where it happened."""
    t = run["t"]
    bb = deepest_ball_ball(run["pos"], run["radius"])
    bw = deepest_ball_wall(run["pos"], run["radius"], run["walls"])
    deepest = max(0.0, bb[0], bw[0])
    out = {"ball_ball": max(0.0, bb[0]), "ball_wall": max(0.0, bw[0]), "deepest": deepest,
           "deepest_relative": deepest / r_min, "where": None}
    if deepest > 0:
        _, f, x, y = bb if bb[0] >= bw[0] else bw
        out["where"] = {"time": float(t[f]), "ball": x, ("ball_b" if bb[0] >= bw[0] else "wall"): y}
    return out


def report(run, path):
    """Every figure of the module docstring, as one dict (the --json object)."""
    n = run["pos"].shape[1]
    scene = run["scene"]
    moving = moving_mask(scene, n)
    acc = accelerations(scene, moving)
    r_min = float(run["radius"].min())
    still, still_threshold = still_from(run, moving, acc, r_min)
    elastic = elastic_somewhere(scene)
    energy = dict(energy_rise(run, moving, acc), check_applies=not elastic)
    return {"file": path, "name": scene.get("name", ""),
            "duration": float(run["t"][-1] - run["t"][0]), "frames": int(len(run["t"])),
            "balls_moving": int(moving.sum()), "balls_fixed": int(n - moving.sum()),
            "events": int(run["events"]),
            "events_per_ball_second": event_rates(run, int(moving.sum())),
            "r_min": r_min, "overlap": overlap_figures(run, r_min),
            "energy": energy, "restitution_one": elastic,
            "still_from": still, "still_speed": still_threshold}


# ----------------------------------------------------------------- checks

def checks(o):
    """(failures, notes) of --check, each a sentence."""
    failures, notes = [], []
    rate = o["events_per_ball_second"]["last_third"]
    if rate is not None and rate > EVENT_RATE_BOUND:
        failures.append(f"events: {rate:.4g} per moving ball per second over the last third "
                        f"(> {EVENT_RATE_BOUND:g})")
    ov = o["overlap"]
    if ov["deepest_relative"] > OVERLAP_BOUND:
        failures.append(f"overlap: deepest {ov['deepest']:.3g} = {ov['deepest_relative']:.3g} r_min "
                        f"(> {OVERLAP_BOUND:g} r_min)")
    e = o["energy"]
    where = o["restitution_one"]
    if where:
        notes.append(f"the energy check does not apply: restitution 1 in {', '.join(where[:3])}"
                     + (f" and {len(where) - 3} more" if len(where) > 3 else ""))
    elif e["frames_rising"] > 0:
        failures.append(f"energy: rose by up to {e['max_rise']:.3g} = {e['max_rise_relative']:.3g} S between "
                        f"frames; by more than {ENERGY_RISE_BOUND:g} S between {e['frames_rising']} of "
                        f"{o['frames'] - 1} pairs of frames")
    return failures, notes


# ----------------------------------------------------------------- output

def fmt(x, unit=""):
    return "n/a" if x is None else f"{x:.4g}{unit}"


def print_text(o, failures, notes, with_check):
    rate, ov, e = o["events_per_ball_second"], o["overlap"], o["energy"]
    print(f"rest report: {o['name'] or '(unnamed)'} ({o['file']})")
    print(f"duration     {o['duration']:.6g} s, {o['frames']} frames")
    print(f"balls        {o['balls_moving']} moving, {o['balls_fixed']} fixed; r_min {o['r_min']:.4g}")
    print(f"events       {o['events']}")
    print(f"event rate   {fmt(rate['last_third'])} per moving ball per second over the last third, "
          f"{fmt(rate['last_tenth'])} over the last tenth")
    where = ov["where"]
    at = "" if where is None else f" at t = {where['time']:.6g} (ball {where['ball']}, " + (
        f"ball {where['ball_b']})" if "ball_b" in where else f"wall {where['wall']})")
    print(f"overlap      deepest {ov['deepest']:.3g} = {ov['deepest_relative']:.3g} r_min{at}; "
          f"ball-ball {ov['ball_ball']:.3g}, ball-wall {ov['ball_wall']:.3g}")
    if e["between"] is None:
        print(f"energy rise  none: the energy never rose from one frame to the next (S = {e['scale']:.6g})")
    else:
        print(f"energy rise  largest {e['max_rise']:.3g} = {fmt(e['max_rise_relative'])} S between t = "
              f"{e['between'][0]:.6g} and {e['between'][1]:.6g} (S = {e['scale']:.6g}); by more than "
              f"{ENERGY_RISE_BOUND:g} S between {e['frames_rising']} of {o['frames'] - 1} pairs of frames")
    if o["still_speed"] is None:
        print("still from   n/a (no acceleration: no speed scale sqrt(g r_min))")
    else:
        still = "never" if o["still_from"] is None else f"t = {o['still_from']:.6g} s"
        print(f"still from   {still} (every speed below {o['still_speed']:.3g} = "
              f"{STILL_FRACTION:g} sqrt(g r_min))")
    if with_check:
        for note in notes:
            print(f"check: {note}")
        for failure in failures:
            print(f"check FAILED: {failure}")
        if not failures:
            print("check: passed")


def main():
    ap = OneLineParser(prog=PROG, description=__doc__.split("\n\n")[0],
                       formatter_class=argparse.RawDescriptionHelpFormatter,
                       epilog=__doc__[__doc__.index("Figures"):])
    ap.add_argument("run", help="run file written by `collide2d run` (HDF5)")
    ap.add_argument("--check", action="store_true", help="exit 1 if a check fails (see below)")
    ap.add_argument("--json", action="store_true", help="print the figures as one JSON object")
    args = ap.parse_args()
    try:
        o = report(load(args.run), args.run)
    except InputError as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 2
    failures, notes = checks(o)
    if args.json:
        o["check"] = {"passed": not failures, "failures": failures, "notes": notes}
        print(json.dumps(finite_or_null(o)))
        if args.check:
            for failure in failures:
                print(f"{PROG}: check FAILED: {failure}", file=sys.stderr)
    else:
        print_text(o, failures, notes, args.check)
    return 1 if args.check and failures else 0


if __name__ == "__main__":
    sys.exit(main())
