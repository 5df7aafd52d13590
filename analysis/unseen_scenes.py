#!/usr/bin/python3
"""Settling scenes of the shipped kinds that nothing was tuned on.

Issue 11 asks that held-out scenes of the kinds of datasets/scenes/ (piles,
stacks, hoppers; sizes and restitutions not seen) finish 60 simulated
seconds in strict mode in under 10 s of wall time (a hopper under 30 s).
This script makes nine such scenes from fixed seeds (the same bytes on every
machine), beside the shipped ones in kind but not in size, radii,
restitution or walls, and runs each with a time limit, printing one row per
scene: whether it finished, its wall time, events, when every ball was
still, the deepest overlap, the island LCPs it solved and, for a run cut
off by the limit, how far it got.

    /usr/bin/python3 analysis/unseen_scenes.py --collide2d build/release/collide2d \\
        [--limit 60] [--mode strict] [--keep DIR] [--only NAME,...]

It checks nothing and fails no test: it measures where the engine stands.
"""
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "datasets", "scenes"))
import make_scenes as shipped  # noqa: E402  (box_walls, jittered_ball, check_no_overlap)

from cli_support import OneLineParser  # noqa: E402


def scene(name, e, walls, balls):
    return {"name": name, "gravity": [0.0, -9.81], "duration": 60.0, "restitution": e,
            "record": {"interval": 0.02}, "walls": walls, "balls": balls}


def pile(name, n, radii, e, width, height, slants, seed):
    """n balls of the given radii (masses by area) on a jittered grid above
    the floor of a closed box, random velocities up to 0.5, the box's
    corners cut by the slanted walls given."""
    rng = random.Random(seed)
    r_max = max(radii)
    spacing = 2 * r_max + 0.05
    columns = int((width - 2 * r_max) / spacing)
    sites = [(i, j) for j in range(200) for i in range(columns)][: int(n * 1.15) + 1]
    rng.shuffle(sites)
    sites = sorted(sites[:n], key=lambda s: (s[1], s[0]))
    balls = [shipped.jittered_ball(rng, r_max + 0.02 + spacing * i, 1.2 + spacing * j, 0.02, 0.5, rng.choice(radii), r_max)
             for i, j in sites]
    if max(b["position"][1] for b in balls) + r_max >= height:
        raise SystemExit(f"unseen_scenes: {name}: the balls do not fit in the box")
    return scene(name, e, shipped.box_walls(0, 0, width, height) + slants, balls)


def hopper(name, n, radii, e, neck, seed):
    """n balls of the given radii in equal numbers above a V hopper whose
    walls run from the box's sides at y = 2.5 down to a neck of the given
    width at y = 1.8, in a closed box [-1.5, 1.5] x [0, 7]."""
    rng = random.Random(seed)
    walls = shipped.box_walls(-1.5, 0, 1.5, 7) + [{"a": [-1.5, 2.5], "b": [-neck / 2, 1.8]},
                                                   {"a": [neck / 2, 1.8], "b": [1.5, 2.5]}]
    each = [radii[k % len(radii)] for k in range(n)]
    rng.shuffle(each)
    r_max = max(radii)
    spacing = 2 * r_max + 0.04
    columns = int(2.8 / spacing)
    sites = [(i, j) for j in range(100) for i in range(columns)][: n + 5]
    rng.shuffle(sites)
    sites = sorted(sites[:n], key=lambda s: (s[1], s[0]))
    balls = [shipped.jittered_ball(rng, -1.4 + r_max + spacing * i, 2.7 + spacing * j, 0.01, 0.3, r, r_max)
             for (i, j), r in zip(sites, each)]
    return scene(name, e, walls, balls)


def column(name, n, r, gap, e):
    """n equal balls stacked at rest in a channel a hair wider than they are,
    every gap (to the floor, the sides, the ball below) `gap`."""
    w = 2 * r + 2 * gap
    walls = [{"a": [0, 0], "b": [w, 0]}, {"a": [w, 0], "b": [w, 2 * n * r + 1]}, {"a": [0, 2 * n * r + 1], "b": [0, 0]}]
    balls = [{"position": [r + gap, r + gap + k * (2 * r + gap)], "velocity": [0.0, 0.0], "radius": r} for k in range(n)]
    return scene(name, e, walls, balls)


def pyramid(name, rows, r, gap, e):
    """A pyramid of rows, rows - 1, ..., 1 equal balls at rest on a floor
    between two side walls, gaps of about `gap` (rounded, not placed to the
    ulp as pyramid_groove.json is)."""
    d = 2 * r + gap
    balls = [{"position": [r + gap + d * k + level * d / 2, r + gap + level * d * math.sqrt(3) / 2],
              "velocity": [0.0, 0.0], "radius": r}
             for level in range(rows) for k in range(rows - level)]
    w = 2 * (r + gap) + d * (rows - 1)
    return scene(name, e, [{"a": [0, 0], "b": [w, 0]}, {"a": [w, 0], "b": [w, 2]}, {"a": [0, 2], "b": [0, 0]}], balls)


def scenes():
    return [
        pile("pile_15_e030", 15, [0.2, 0.3], 0.3, 2.5, 9, [{"a": [1.8, 0], "b": [2.5, 0.4]}], 15),
        column("column_8_e070", 8, 0.1, 1e-8, 0.7),
        pyramid("pyramid_21_e040", 6, 0.05, 1e-8, 0.4),
        pile("pile_30_e060", 30, [0.1, 0.15, 0.2], 0.6, 3, 8, [{"a": [0, 0.6], "b": [0.6, 0]}], 11),
        pile("pile_80_e075", 80, [0.12, 0.18], 0.75, 5, 10, [{"a": [0, 0.8], "b": [0.8, 0]}, {"a": [4.2, 0], "b": [5, 0.8]}], 12),
        pile("pile_120_e050", 120, [0.1, 0.14, 0.2], 0.5, 6, 10, [{"a": [0, 0.8], "b": [2, 0]}], 13),
        pile("pile_200_e095", 200, [0.08, 0.12], 0.95, 5, 10, [{"a": [3.5, 0], "b": [5, 1]}], 14),
        hopper("hopper_80_e070", 80, [0.04, 0.06], 0.7, 0.5, 21),
        hopper("hopper_150_e090", 150, [0.035, 0.05, 0.065], 0.9, 0.6, 22),
    ]


def run(exe, path, out, mode, limit):
    """One run, cut off after `limit` seconds: its summary figures, or how far it got."""
    started = time.monotonic()
    try:
        done = subprocess.run([exe, "run", path, "-o", out, "--until", "60", "--mode", mode, "--force"],
                              capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired as cut:
        text = "".join(x.decode() if isinstance(x, bytes) else x for x in (cut.stderr or "", cut.stdout or ""))
        reached = re.findall(r"t = ([0-9.e+-]+) of 60, (\d+) events", text)
        got = f"t = {reached[-1][0]}, {int(reached[-1][1]):,} events" if reached else "no progress line"
        return {"status": f"cut off at {limit:g} s ({got})"}
    row = {"status": "finished" if done.returncode == 0 else f"exit {done.returncode}: {done.stderr.strip()[-200:]}",
           "wall": f"{time.monotonic() - started:.2f}"}
    for line in done.stdout.splitlines():
        if line.startswith("events "):
            row["events"] = f"{int(line.split()[1]):,}"
        elif line.startswith("at rest "):
            row["still"] = line.split()[-1] if "from t =" in line else "-"
        elif line.startswith("overlap "):
            row["overlap"] = line.split()[2].rstrip(";")
        elif m := re.match(r"islands +(\d+) LCP solves .*?, ([0-9.e+]+) rows", line):
            row["islands"] = f"{int(m.group(1)):,} of {float(m.group(2)):g} rows"
    return row


def main():
    parser = OneLineParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--collide2d", required=True, help="the collide2d program")
    parser.add_argument("--limit", type=float, default=60, help="wall seconds a run may take (default 60)")
    parser.add_argument("--mode", default="strict", choices=["strict", "fixed"])
    parser.add_argument("--keep", help="write the scenes and runs here (default: a temporary folder)")
    parser.add_argument("--only", help="comma-separated scene names")
    args = parser.parse_args()
    chosen = scenes()
    if args.only:
        names = set(args.only.split(","))
        unknown = names - {s["name"] for s in chosen}
        if unknown:
            parser.error(f"--only: no scene named {', '.join(sorted(unknown))}")
        chosen = [s for s in chosen if s["name"] in names]
    if not (os.path.isfile(args.collide2d) and os.access(args.collide2d, os.X_OK)):
        parser.error(f"--collide2d: {args.collide2d} is not an executable file")
    with tempfile.TemporaryDirectory(prefix="unseen_scenes_") as scratch:
        folder = args.keep or scratch
        os.makedirs(folder, exist_ok=True)
        print("| scene | balls | e | status | wall s | events | still from | deepest overlap | island LCPs |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
        for s in chosen:
            shipped.check_no_overlap(s, 1e-12)
            path = os.path.join(folder, s["name"] + ".json")
            with open(path, "w") as f:
                json.dump(s, f)
            row = run(args.collide2d, path, os.path.join(folder, s["name"] + "-" + args.mode + ".h5"), args.mode,
                      args.limit)
            cells = [s["name"], len(s["balls"]), s["restitution"], row["status"]]
            cells += [row.get(k, "-") for k in ("wall", "events", "still", "overlap", "islands")]
            print("| " + " | ".join(str(c) for c in cells) + " |", flush=True)


if __name__ == "__main__":
    main()
