#!/usr/bin/python3
"""How much a settling scene's cost depends on its history.

A pile under gravity is chaotic: a change in the last digits of one velocity
gives another history, with another number of events and island solves. One
scene is one sample. This script makes K variants of a scene, each ball's
initial velocity moved by a few times 1e-7 (a fixed pattern per variant, so
the variants are the same on every machine), runs each for the given time in
each mode, and prints per run the events, the CPU seconds, when every
ball was still and the island LCPs the run solved (from the summary's
`islands` line: their number, mean rows and pivoting rounds), then the
median and range of each column.

    /usr/bin/python3 analysis/scene_ensemble.py --collide2d build/release/collide2d \\
        datasets/scenes/pile_50.json --variants 8 --until 60 --modes strict,fixed
"""
import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile


def variant(scene, k):
    """Scene k: ball i's velocity moved by (((7i + 13k) mod 11) - 5, ((5i + 3k) mod 7) - 3) x 1e-7."""
    out = json.loads(json.dumps(scene))
    for i, ball in enumerate(out["balls"]):
        vx, vy = ball.get("velocity", [0.0, 0.0])
        ball["velocity"] = [vx + 1e-7 * ((i * 7 + k * 13) % 11 - 5), vy + 1e-7 * ((i * 5 + k * 3) % 7 - 3)]
    out["name"] = f"{scene.get('name', 'scene')}_variant{k}"
    return out


def run(exe, scene_path, out_path, until, mode):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run([exe, "run", scene_path, "-o", out_path, "--until", str(until), "--mode", mode, "--force"],
                          capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"scene_ensemble: {scene_path} ({mode}) failed:\n{done.stderr}")
    events, still, solves, rows, rounds = None, None, 0, 0.0, 0.0
    for line in done.stdout.splitlines():
        if line.startswith("events "):
            events = int(line.split()[1])
        if line.startswith("at rest "):
            still = float(line.split()[-1]) if "from t =" in line else None
        # "islands     N LCP solves (...), R rows and Q pivoting rounds per solve, largest L rows"
        if m := re.match(r"islands +(\d+) LCP solves .*?, ([0-9.e+]+) rows and ([0-9.e+]+) pivoting rounds", line):
            solves, rows, rounds = int(m.group(1)), float(m.group(2)), float(m.group(3))
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return events, cpu, still, solves, rows, rounds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--collide2d", required=True, help="the collide2d program")
    parser.add_argument("--variants", type=int, default=8)
    parser.add_argument("--until", type=float, default=60)
    parser.add_argument("--modes", default="strict,fixed")
    args = parser.parse_args()
    with open(args.scene) as f:
        scene = json.load(f)
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for k in range(args.variants):
            path = os.path.join(folder, f"variant{k}.json")
            with open(path, "w") as f:
                json.dump(variant(scene, k), f)
            for mode in args.modes.split(","):
                events, cpu, still, solves, lcp_rows, rounds = run(args.collide2d, path, os.path.join(folder, "run.h5"),
                                                                   args.until, mode)
                rows.append((k, mode, events, cpu, still, solves))
                print(f"variant {k} {mode:6s} events {events:9d}  cpu {cpu:7.2f} s  still from "
                      f"{'-' if still is None else f'{still:g} s'}  island LCPs {solves} "
                      f"({lcp_rows:g} rows, {rounds:g} rounds each)", flush=True)
    for mode in args.modes.split(","):
        mine = [r for r in rows if r[1] == mode]
        for name, column in (("events", 2), ("cpu s", 3), ("LCPs", 5)):
            values = [r[column] for r in mine]
            print(f"{mode:6s} {name:7s} median {statistics.median(values):10.6g}  range {min(values):g} .. {max(values):g}")
        still = [r[4] for r in mine if r[4] is not None]
        print(f"{mode:6s} still   {len(still)} of {len(mine)} by t = {args.until:g}"
              + (f", median from {statistics.median(still):g} s, latest {max(still):g} s" if still else ""))


if __name__ == "__main__":
    main()
