#!/usr/bin/python3
"""The README's rest table, from real runs: each shipped settling scene run for
60 simulated seconds in strict and in fixed mode, read by rest_report.py.

  rest_table.py --collide2d EXE [--scenes DIR] [--until T] [--readme README.md]

Prints one Markdown row per scene (the README's columns): events, the time
from which every ball is still, events per moving ball per second over the
last third, the deepest overlap over r_min, frames where the energy rose,
the share of the collisions the rest rules made plastic (the engine's own
count, stored in /observables/summary: what the rules did, not a check of
it), and the wall time of this one run of each mode (the README's wall-time
column is the median of three paired runs, analysis/paired_time.py, which
this script does not repeat).

--readme FILE compares every figure but the wall times with FILE's rows
(matched by the scene file name in the first cell): events and frame counts
exactly, the other numbers to the significant digits the README prints; "—"
means never still. Exits 1 naming each stale figure: the runs are
deterministic, so a figure that differs is out of date (or the engine
changed). Exit 2: bad input (a missing executable, scene or README row).
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_support import InputError, OneLineParser  # noqa: E402
import rest_report  # noqa: E402

SCENES = ["abound", "resting_pile", "pyramid_groove", "corner_ball", "funnel", "pile_50"]
MODES = ["strict", "fixed"]


def run_scene(exe, path, mode, until, out):
    """Runs one scene; returns (rest_report dict, wall seconds)."""
    start = time.monotonic()
    done = subprocess.run([exe, "run", path, "-o", out, "--until", str(until), "--mode", mode],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - start
    if done.returncode != 0:
        raise InputError(f"{exe} run {path} --mode {mode} failed: {done.stderr.strip()}")
    rep = rest_report.report(rest_report.load(out), out)
    rep["plastic_percent"] = plastic_percent(out)
    return rep, wall


def plastic_percent(path):
    """The share of the collisions the rest rules made plastic, in per cent,
    from the run's stored summary (SPEC.md: /observables/summary)."""
    with rest_report.open_run(path) as f:
        if "observables/summary" not in f:
            raise InputError(f"{path}: no /observables/summary")
        summary = json.loads(f["observables/summary"][()])
    collisions = summary["ball_ball"] + summary["ball_wall"]
    return 100.0 * summary["made_plastic_by_rest_rules"] / collisions if collisions else 0.0


def g2(x):
    """A figure as the README prints it: two significant digits, 0 as 0."""
    return "0" if x == 0 else f"{x:.2g}"


def g3(x):
    """A percentage as the README prints it: three significant digits, 0 as 0."""
    return "0" if x == 0 else f"{x:.3g}"


def figures(rep):
    """The compared figures of one run, as numbers (None: never still)."""
    return {"events": rep["events"], "still": rep["still_from"],
            "rate": rep["events_per_ball_second"]["last_third"],
            "overlap": rep["overlap"]["deepest_relative"], "rising": rep["energy"]["frames_rising"],
            "plastic": rep["plastic_percent"]}


def row(name, per_mode, walls):
    def pair(key, fmt):
        return " / ".join(fmt(per_mode[m][key]) for m in MODES)
    still = " / ".join("—" if per_mode[m]["still"] is None else f"{per_mode[m]['still']:.3g}" for m in MODES)
    return (f"| `{name}.json` | {pair('events', str)} | {still} | {pair('rate', g2)} | {pair('overlap', g2)} | "
            f"{pair('rising', str)} | {pair('plastic', g3)} | {' / '.join(f'{walls[m]:.3g}' for m in MODES)} |")


NUMBER = re.compile(r"—|[0-9]+(?:\.[0-9]+)?(?:e[-+]?[0-9]+)?")


def readme_cells(readme, name):
    for line in open(readme, encoding="utf-8"):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells and cells[0].startswith(f"`{name}.json`"):
            return cells
    raise InputError(f"{readme}: no table row for {name}.json")


def agrees(printed, value):
    """Whether `value` is the README's `printed` figure: integers exactly, "0"
    exactly 0, "—" never still, other numbers to the significant digits
    printed."""
    if printed == "—" or value is None:
        return printed == "—" and value is None
    if isinstance(value, int):
        return float(printed) == value
    if printed == "0":
        return value == 0
    digits = max(1, len(printed.split("e")[0].replace(".", "").lstrip("0")))
    return float(f"{value:.{digits}g}") == float(printed)


def compare(readme, name, per_mode):
    """The stale figures of one scene's README row (a list of messages)."""
    cells = readme_cells(readme, name)
    stale = []
    for column, key in ((1, "events"), (2, "still"), (3, "rate"), (4, "overlap"), (5, "rising"), (6, "plastic")):
        printed = NUMBER.findall(cells[column])[:2]
        if len(printed) != 2:
            stale.append(f"{name}: column {column + 1} ('{cells[column]}') does not give a strict and a fixed figure")
            continue
        for mode, p in zip(MODES, printed):
            if not agrees(p, per_mode[mode][key]):
                stale.append(f"{name} {mode}: README says {key} {p}, the run gives {per_mode[mode][key]}")
    return stale


def main():
    ap = OneLineParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--collide2d", required=True, help="the collide2d executable")
    ap.add_argument("--scenes", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "datasets", "scenes"))
    ap.add_argument("--until", type=float, default=60.0, help="simulated seconds per run (default 60, as the README)")
    ap.add_argument("--readme", help="compare with this README's rest table; exit 1 on a stale figure")
    ap.add_argument("--json", action="store_true", help="print the figures as one JSON object instead of rows")
    args = ap.parse_args()
    try:
        if not os.access(args.collide2d, os.X_OK):
            raise InputError(f"{args.collide2d}: not an executable")
        table, stale = {}, []
        with tempfile.TemporaryDirectory() as tmp:
            for name in SCENES:
                path = os.path.join(args.scenes, name + ".json")
                if not os.path.exists(path):
                    raise InputError(f"{path}: no such scene")
                per_mode, walls = {}, {}
                for mode in MODES:
                    print(f"rest_table: {name} ({mode}) ...", file=sys.stderr, flush=True)
                    rep, walls[mode] = run_scene(args.collide2d, path, mode, args.until, os.path.join(tmp, f"{name}-{mode}.h5"))
                    per_mode[mode] = figures(rep)
                table[name] = {"figures": per_mode, "wall_seconds": walls}
                if not args.json:
                    print(row(name, per_mode, walls), flush=True)
                if args.readme:
                    stale += compare(args.readme, name, per_mode)
        if args.json:
            print(json.dumps(table))
        for s in stale:
            print(f"stale: {s}", file=sys.stderr)
        if args.readme:
            print(f"rest_table: {len(stale)} stale figures in {args.readme}", file=sys.stderr)
        return 1 if stale else 0
    except InputError as e:
        print(f"rest_table.py: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
