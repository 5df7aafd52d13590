#!/usr/bin/python3
"""Plot a collide2d run file (H5MD layout, SPEC.md "Run file (HDF5)").

  plot_run.py RUN.h5 -o run.png [--animate run.mp4|run.gif] [--fps N] [--max-frames N]

The PNG shows the scene (walls, trajectories, final positions at true radius,
fixed balls in grey) beside the total energy, its relative change and a rug of
collision times. --animate renders the balls frame by frame: mp4 through ffmpeg
when it is installed, otherwise a GIF next to the requested name.
Exit codes: 0 success, 2 bad input or usage (one line on stderr).
"""
import argparse
import json
import os
import sys

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import animation  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402
from cli_support import InputError, text_of  # noqa: E402

PROG = "plot_run.py"
KIND_STYLE = {0: ("ball–ball", "tab:purple"), 1: ("ball–wall", "tab:orange")}


def param(par, name):
    """A parameter stored as a dataset or an attribute of /parameters, or None."""
    return None if par is None else par[name] if name in par else par.attrs.get(name)


def load(path):
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError:
        try:  # a run being written, or killed while writing, carries the SWMR flag
            f = h5py.File(path, "r", swmr=True)
        except OSError:
            raise InputError(f"{path}: not an HDF5 file (or not readable)")
    with f:
        need = ["particles/balls/position/time", "particles/balls/position/value",
                "observables/energy/time", "observables/energy/value"]
        for name in need:
            if name not in f or not isinstance(f[name], h5py.Dataset):
                raise InputError(f"{path}: missing dataset /{name}")
        run = {"t": f[need[0]][:], "pos": f[need[1]][:], "te": f[need[2]][:], "e": f[need[3]][:]}
        if run["pos"].ndim != 3 or run["pos"].shape[2] != 2:
            raise InputError(f"{path}: /{need[1]}: expected frames x N x 2")
        # A file caught mid-write may hold series of slightly different lengths.
        k = min(len(run["t"]), len(run["pos"]))
        run["t"], run["pos"] = run["t"][:k], run["pos"][:k]
        k = min(len(run["te"]), len(run["e"]))
        run["te"], run["e"] = run["te"][:k], run["e"][:k]
        if len(run["t"]) == 0:
            raise InputError(f"{path}: /{need[1]}: no frames")
        ev = {k: f[f"events/{k}"][:] if f"events/{k}" in f else np.empty(0) for k in ("time", "kind")}
        run["ev_t"], run["ev_kind"] = ev["time"], ev["kind"].astype(int)
        if len(run["ev_t"]) != len(run["ev_kind"]):
            raise InputError(f"{path}: /events/time and /events/kind differ in length")
        par = f["parameters"] if "parameters" in f else None
        scene_text = param(par, "scene")  # the name SPEC.md suggests; collide2d writes scene_json
        scene_text = param(par, "scene_json") if scene_text is None else scene_text
        try:
            run["scene"] = json.loads(text_of(scene_text)) if scene_text is not None else {}
        except (json.JSONDecodeError, UnicodeDecodeError):
            raise InputError(f"{path}: /parameters/scene: not valid JSON")
        if not isinstance(run["scene"], dict):
            raise InputError(f"{path}: /parameters/scene: not a JSON object")
        n = run["pos"].shape[1]
        radius, walls = param(par, "radius"), param(par, "walls")
        try:
            if radius is None:
                radius = [b["radius"] for b in run["scene"]["balls"]]
            if walls is None:
                walls = [w["a"] + w["b"] for w in run["scene"].get("walls", [])]
        except (KeyError, TypeError):
            raise InputError(f"{path}: no /parameters/radius and no balls[].radius in the scene JSON")
        run["radius"] = np.asarray(radius, float).reshape(-1)
        run["walls"] = np.asarray(walls, float).reshape(-1, 4)
        if len(run["radius"]) != n:
            raise InputError(f"{path}: /parameters/radius: {len(run['radius'])} radii for {n} balls")
    return run


def check_writable(path):
    d = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(d) or not os.access(d, os.W_OK) or (
            os.path.exists(path) and not os.access(path, os.W_OK)):
        raise InputError(f"{path}: cannot write output here")


def colours(run):
    """Moving mask and one colour per ball: tab10 (turbo beyond 10), grey if fixed."""
    moving = np.any(run["pos"] != run["pos"][:1], axis=(0, 2))
    n = int(moving.sum())
    shade = (lambda k: plt.get_cmap("tab10")(k)) if n <= 10 else (
        lambda k: plt.get_cmap("turbo")(k / max(1, n - 1)))
    rank = np.cumsum(moving) - 1
    return moving, [shade(rank[i]) if moving[i] else "0.55" for i in range(len(moving))]


def draw_scene(ax, run):
    ends = run["walls"].reshape(-1, 2, 2)
    ax.add_collection(LineCollection(ends, colors="k", linewidths=2,
                                     label="wall" if len(ends) else None))
    r = run["radius"][None, :, None]
    lo = np.vstack([ends.reshape(-1, 2), (run["pos"] - r).min((0, 1))[None]]).min(0)
    hi = np.vstack([ends.reshape(-1, 2), (run["pos"] + r).max((0, 1))[None]]).max(0)
    pad = 0.04 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (scene units)")
    ax.set_ylabel("y (scene units)")


def figure(run, name, out):
    moving, cols = colours(run)
    n, t, e = run["pos"].shape[1], run["te"], run["e"]
    fig = plt.figure(figsize=(14, 6.5), layout="constrained")
    gs = fig.add_gridspec(3, 2, width_ratios=[1, 1.15], height_ratios=[3, 3, 1])
    ax = fig.add_subplot(gs[:, 0])
    draw_scene(ax, run)
    label_balls = n <= 10
    for i in range(n):
        p = run["pos"][:, i]
        if moving[i]:
            ax.plot(p[:, 0], p[:, 1], lw=0.8, color=cols[i], alpha=0.8)
            ax.plot(*p[0], marker="o", ms=3, color=cols[i])
        ax.add_patch(Circle(p[-1], run["radius"][i], fc=cols[i], ec="k", lw=0.6, alpha=0.85,
                            label=(f"ball {i}" + ("" if moving[i] else " (fixed)")) if label_balls else None))
    if not label_balls and (~moving).any():
        ax.add_patch(Circle((np.nan, np.nan), 1, fc="0.55", label="fixed ball"))
    ax.set_title("trajectories (dot: start, circle: final position)", fontsize=10)
    ax.legend(loc="upper left", bbox_to_anchor=(0, -0.08), ncol=min(6, n + 1), fontsize=8, frameon=False)

    ax_e = fig.add_subplot(gs[0, 1])
    ax_e.plot(t, e, color="tab:blue", lw=1.2, label="total energy E")
    ax_e.set_ylabel("energy E (scene units)")
    ax_e.legend(loc="best", fontsize=8)
    ax_r = fig.add_subplot(gs[1, 1], sharex=ax_e)
    if len(e) and e[0] != 0:
        ax_r.plot(t, (e - e[0]) / abs(e[0]), color="tab:red", lw=1.2)
        ax_r.set_ylabel("(E − E₀) / |E₀|")
    else:
        ax_r.plot(t, e - (e[0] if len(e) else 0), color="tab:red", lw=1.2)
        ax_r.set_ylabel("E − E₀ (E₀ = 0)")
    ax_r.axhline(0, color="0.6", lw=0.6, ls=":")
    ax_v = fig.add_subplot(gs[2, 1], sharex=ax_e)
    for row, (kind, (label, colour)) in enumerate(KIND_STYLE.items()):
        tk = run["ev_t"][run["ev_kind"] == kind]
        ax_v.eventplot(tk, lineoffsets=row, linelengths=0.8, colors=colour, linewidths=0.8)
    ax_v.set_yticks([0, 1], [f"{KIND_STYLE[k][0]} ({(run['ev_kind'] == k).sum()})" for k in (0, 1)], fontsize=8)
    for tick, kind in zip(ax_v.get_yticklabels(), KIND_STYLE):
        tick.set_color(KIND_STYLE[kind][1])
    ax_v.set_ylim(-0.6, 1.6)
    ax_v.set_xlabel("time t (s)")
    for a in (ax_e, ax_r):
        a.tick_params(labelbottom=False)
        a.grid(alpha=0.3)
    ax_v.set_xlim(min(run["t"][0], t[0] if len(t) else 0), max(run["t"][-1], t[-1] if len(t) else 0))
    ax_e.set_title("energy and collisions", fontsize=10)
    fig.suptitle(title(run, name), fontsize=12)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def title(run, name):
    dur = run["t"][-1] - run["t"][0]
    return (f"{name}: {run['pos'].shape[1]} balls, {len(run['ev_t'])} events, "
            f"{dur:.6g} s, {len(run['t'])} frames")


def animate(run, name, out, fps, max_frames):
    if out.lower().endswith(".mp4") and not animation.FFMpegWriter.isAvailable():
        gif = os.path.splitext(out)[0] + ".gif"
        print(f"{PROG}: ffmpeg not found; writing {gif} instead of {out}", file=sys.stderr)
        out = gif
    check_writable(out)
    frames = np.unique(np.linspace(0, len(run["t"]) - 1, min(max_frames, len(run["t"]))).astype(int))
    moving, cols = colours(run)
    fig, ax = plt.subplots(figsize=(7, 6), layout="constrained")
    draw_scene(ax, run)
    fig.suptitle(title(run, name), fontsize=10)
    circles = [ax.add_patch(Circle(run["pos"][0, i], run["radius"][i], fc=cols[i], ec="k", lw=0.5))
               for i in range(run["pos"].shape[1])]
    label = ax.set_title("", family="monospace", fontsize=10)

    def update(k):
        for c, p in zip(circles, run["pos"][frames[k]]):
            c.center = p
        label.set_text(f"t = {run['t'][frames[k]]:9.4f} s")
        return circles + [label]

    anim = animation.FuncAnimation(fig, update, frames=len(frames), blit=False)
    show, tty, last = len(frames) / fps > 3, sys.stderr.isatty(), [-1]

    def progress(i, n):
        # One updating line on a terminal; a line per quarter in a log.
        pct = 100 * (i + 1) // n
        if show and pct // (1 if tty else 25) != last[0]:
            last[0] = pct // (1 if tty else 25)
            end = "" if tty and i + 1 < n else "\n"
            print(f"{chr(13) if tty else ''}{PROG}: rendering {out}: frame {i + 1}/{n} ({pct}%)",
                  end=end, file=sys.stderr, flush=True)

    writer = (animation.FFMpegWriter(fps=fps) if out.lower().endswith(".mp4")
              else animation.PillowWriter(fps=fps))
    try:
        anim.save(out, writer=writer, dpi=90, progress_callback=progress)
    except Exception:
        if os.path.exists(out):
            os.remove(out)
        raise
    finally:
        plt.close(fig)
    return out


def main():
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0],
                                 epilog="Exit codes: 0 success, 2 bad input or usage.")
    ap.add_argument("run", help="run file written by `collide2d run` (HDF5)")
    ap.add_argument("-o", "--output", help="PNG figure to write (default: RUN with .png)")
    ap.add_argument("--animate", metavar="MOVIE", help="also write an animation (.mp4 or .gif)")
    ap.add_argument("--fps", type=int, default=25, help="animation frames per second (default 25)")
    ap.add_argument("--max-frames", type=int, default=500,
                    help="at most this many animation frames, evenly subsampled (default 500)")
    args = ap.parse_args()
    out = args.output or os.path.splitext(args.run)[0] + ".png"
    try:
        if args.fps <= 0 or args.max_frames <= 0:
            raise InputError("--fps and --max-frames must be positive")
        if args.animate and not args.animate.lower().endswith((".mp4", ".gif")):
            raise InputError(f"{args.animate}: animation must end in .mp4 or .gif")
        for path in filter(None, (out, args.animate)):
            check_writable(path)
        run = load(args.run)
        name = run["scene"].get("name") or os.path.splitext(os.path.basename(args.run))[0]
        try:
            figure(run, name, out)
            if args.animate:
                movie = animate(run, name, args.animate, args.fps, args.max_frames)
                print(f"{PROG}: wrote {out} and {movie}", file=sys.stderr)
        except OSError as e:
            raise InputError(f"{e.filename or out}: cannot write: {e.strerror or e}")
    except InputError as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()
