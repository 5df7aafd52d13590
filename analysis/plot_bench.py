#!/usr/bin/python3
"""Plot `collide2d bench peers` (and, if given, `collide2d bench sim`) CSV.

    plot_bench.py PEERS.csv [--sim SIM.csv] [-o OUTDIR]

Writes into OUTDIR (default: the directory of PEERS.csv) and prints each path:

  bench_peers.png  per scene, one bar per engine: wall seconds per simulated
                   second (log scale), with the deepest overlap (over the
                   radius) and the relative energy change written above each
                   bar and the number of balls that left the box, if any.
  bench_sim.png    (with --sim) collisions per CPU second against N, one line
                   per packing fraction and mode.

Run it with Debian's /usr/bin/python3 (numpy, matplotlib). Exit codes: 0
success, 2 bad input or usage (one line on stderr).
"""
import csv
import os
import sys

from cli_support import InputError, OneLineParser

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: E402
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"plot_bench.py: needs matplotlib ({e}); run it with /usr/bin/python3\n")
    sys.exit(2)

PEERS_COLUMNS = ["scene", "engine", "simulated_s", "wall_s_per_simulated_s", "energy_change", "deepest_overlap", "balls_outside"]
SIM_COLUMNS = ["scene", "n", "eta", "mode", "collisions", "wall_s", "cpu_s", "collisions_per_s", "bytes_per_ball"]


def read_csv(path, columns):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror}")
    if not rows or list(rows[0].keys()) != columns:
        raise InputError(f"{path}: not the CSV of collide2d bench (expected columns {','.join(columns)})")
    return rows


def plot_peers(rows, path):
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    engines = list(dict.fromkeys(r["engine"] for r in rows))
    width = 0.8 / len(engines)
    fig, ax = plt.subplots(figsize=(11, 5.5))
    for k, engine in enumerate(engines):
        for s, scene in enumerate(scenes):
            r = next((r for r in rows if r["scene"] == scene and r["engine"] == engine), None)
            if r is None:
                continue
            x = s + (k - (len(engines) - 1) / 2) * width
            wall = float(r["wall_s_per_simulated_s"])
            ax.bar(x, wall, width, color=f"C{k}", label=engine if s == 0 else None)
            note = f"ov {float(r['deepest_overlap']):.1g}\ndE {float(r['energy_change']):.1g}"
            if int(r["balls_outside"]):
                note += f"\nout {r['balls_outside']}"
            ax.text(x, wall * 1.15, note, ha="center", va="bottom", fontsize=6.5)
    ax.set_yscale("log")
    ax.set_xticks(range(len(scenes)))
    ax.set_xticklabels(scenes)
    ax.set_ylabel("wall seconds per simulated second")
    ax.set_title("collide2d and its peers (ov: deepest overlap / radius, dE: relative energy change, out: balls lost)")
    ax.legend(fontsize=8)
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo, hi * 30)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_sim(rows, path):
    gases = [r for r in rows if r["eta"]]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, (eta, mode) in enumerate(sorted({(r["eta"], r["mode"]) for r in gases})):
        line = sorted((int(r["n"]), float(r["collisions_per_s"])) for r in gases if r["eta"] == eta and r["mode"] == mode)
        ax.plot([n for n, _ in line], [c for _, c in line], "o-" if mode == "strict" else "s--", color=f"C{k}",
                label=f"eta {eta}, {mode}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("discs N")
    ax.set_ylabel("collisions per CPU second (whole run)")
    ax.set_title("collide2d bench sim: hard-disk gases")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    p = OneLineParser(prog="plot_bench.py", description=__doc__.split("\n")[0])
    p.add_argument("peers", help="CSV of collide2d bench peers")
    p.add_argument("--sim", help="CSV of collide2d bench sim")
    p.add_argument("-o", "--outdir", help="where the PNG files go (default: beside PEERS.csv)")
    a = p.parse_args()
    try:
        outdir = a.outdir or os.path.dirname(os.path.abspath(a.peers))
        os.makedirs(outdir, exist_ok=True)
        peers = read_csv(a.peers, PEERS_COLUMNS)
        sim = read_csv(a.sim, SIM_COLUMNS) if a.sim else None
        out = os.path.join(outdir, "bench_peers.png")
        plot_peers(peers, out)
        print(out)
        if sim is not None:
            out = os.path.join(outdir, "bench_sim.png")
            plot_sim(sim, out)
            print(out)
    except InputError as e:
        sys.stderr.write(f"plot_bench.py: {e}\n")
        sys.exit(2)


if __name__ == "__main__":
    main()
