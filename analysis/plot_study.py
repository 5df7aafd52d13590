#!/usr/bin/python3
"""Plot a collide2d study file (written by `collide2d study`, format "collide2d study 1").

    plot_study.py STUDY.h5 [-o OUTDIR] [--print]

Writes three PNG figures into OUTDIR (default: the directory of STUDY.h5) and
prints the path of each on stdout:

  study_speed_error.png         /query rows of family "all": median ns per query
                                against the 99th-percentile error, one point per
                                (method, mode); the Pareto front is marked.
  study_failures_by_family.png  /query rows of each hard family: the fraction of
                                its queries that were false negatives or false
                                positives, one bar per (method, mode).
  study_step_vs_event.png       /scene runs: wall seconds against the maximum
                                relative energy error (step runs as a curve over
                                dt, event runs as stars), and each run's
                                divergence from the reference against time.

A study that ran only one level (no /query or no /scene) gets the figures it
can make; the others are skipped with a line on stdout. --print also prints
the numbers behind each figure as a table, to check the figures against the
table `collide2d study` prints. Run it with Debian's /usr/bin/python3 (h5py,
numpy, matplotlib). Exit codes: 0 success, 2 bad input or usage (one line on
stderr).
"""
import math
import os
import sys
from cli_support import InputError, OneLineParser, text_of  # noqa: E402

try:
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: E402
    import numpy as np  # noqa: E402
    from matplotlib import ticker  # noqa: E402
    from matplotlib.patches import Patch  # noqa: E402
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"plot_study.py: needs h5py, numpy and matplotlib (/usr/bin/python3): {e}\n")
    sys.exit(2)

PROG = "plot_study.py"
FORMAT = "collide2d study 1"
FIG_SPEED, FIG_FAMILY, FIG_SCENE = (
    "study_speed_error.png", "study_failures_by_family.png", "study_step_vs_event.png")
ERROR_FLOOR = 1e-18   # zero errors are drawn here on the log axes (and the axis label says so)
WALL_FLOOR = 1e-6     # zero wall times (s), likewise
MODE_MARKER = {"strict": "o", "fixed": "s"}
MODE_HATCH = {"strict": "", "fixed": "///"}
OTHER_MARKERS = "^Dv<>ph"
DT_STYLES = ["--", ":", "-.", (0, (6, 2, 1, 2, 1, 2)), (0, (1, 4))]
DT_MARKERS = "osD^vph"
MAX_DT_LABELS = 12    # label each step run (dt, missed contacts) in figure 3's left panel up to this many

# The datasets each table must hold (others are ignored): name and kind.
QUERY_COLUMNS = [
    ("family", str), ("method", str), ("mode", str),
    ("queries", int), ("oracle_hits", int), ("false_negatives", int), ("false_positives", int),
    ("rule_failures", int), ("threw", int),
    ("ns_median", float), ("ns_p99", float), ("ns_max", float),
    ("error_median", float), ("error_p99", float), ("error_max", float),
    ("time_error_p99", float)]
SCENE_COLUMNS = [
    ("scene", str), ("engine", str), ("method", str), ("mode", str),
    ("dt", float), ("wall_seconds", float), ("energy_error_max", float),
    ("divergence_final", float), ("growth_rate", float), ("fit_from", float), ("fit_to", float),
    ("events", int), ("missed_contacts", int), ("frames", int), ("deepest_overlap", float)]
META_ATTRS = ["created", "command", "compiler", "build_type", "hostname", "cpu", "cores"]


def note(message):
    print(f"{PROG}: {message}", flush=True)


# ---------------------------------------------------------------- reading

def read_table(path, f, group, columns):
    """The parallel 1-D datasets of `group` as {name: list of str | int64 array | float array}."""
    if group not in f or not isinstance(f[group], h5py.Group):
        raise InputError(f"{path}: missing group /{group}")
    g, table, n, first = f[group], {}, None, None
    for name, kind in columns:
        where = f"{path}: /{group}/{name}"
        if name not in g or not isinstance(g[name], h5py.Dataset):
            raise InputError(f"{path}: missing dataset /{group}/{name}")
        ds = g[name]
        if ds.ndim != 1:
            raise InputError(f"{where}: expected a 1-D dataset, found shape {ds.shape}")
        raw = ds[()]
        dk = raw.dtype.kind
        if kind is str:
            if dk not in "OSU":
                raise InputError(f"{where}: expected strings, found {raw.dtype}")
            values = [text_of(v) for v in raw]
        elif kind is int:
            if dk not in "iu":
                raise InputError(f"{where}: expected integers, found {raw.dtype}")
            values = raw.astype(np.int64)
        else:
            if dk not in "fiu":
                raise InputError(f"{where}: expected numbers, found {raw.dtype}")
            values = raw.astype(float)
        if n is None:
            n, first = len(values), name
        elif len(values) != n:
            raise InputError(f"{where}: {len(values)} entries, but /{group}/{first} has {n}")
        table[name] = values
    return table, n


def rows_of(table, n):
    return [{k: (v[i].item() if isinstance(v, np.ndarray) else v[i]) for k, v in table.items()}
            for i in range(n)]


def load(path):
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise InputError(f"{path}: not an HDF5 file (or not readable)")
    with f:
        if "format" not in f.attrs:
            raise InputError(f"{path}: no 'format' attribute on /: not a collide2d study file")
        fmt = text_of(f.attrs["format"])
        if fmt != FORMAT:
            raise InputError(f"{path}: format attribute is '{fmt}', expected '{FORMAT}'")
        study = {"path": path, "meta": {k: text_of(f.attrs[k]) for k in META_ATTRS if k in f.attrs},
                 "query": None, "scene": None}
        if "query" in f:
            table, n = read_table(path, f, "query/table", QUERY_COLUMNS)
            rows = rows_of(table, n)
            seen = set()
            for i, r in enumerate(rows):
                key = (r["family"], r["method"], r["mode"])
                if key in seen:
                    raise InputError(f"{path}: /query/table: row {i} repeats family '{key[0]}', "
                                     f"method '{key[1]}', mode '{key[2]}'")
                seen.add(key)
            a = f["query"].attrs
            study["query"] = {"rows": rows,
                              "dataset": text_of(a["dataset"]) if "dataset" in a else "?",
                              "repeats": text_of(a["repeats"]) if "repeats" in a else "?"}
        if "scene" in f:
            table, n = read_table(path, f, "scene/table", SCENE_COLUMNS)
            rows = rows_of(table, n)
            for i, r in enumerate(rows):
                r["index"], r["time"], r["divergence"] = i, None, None
                name = f"scene/divergence/{i:03d}"
                if name not in f:
                    continue  # drawn without a curve; said on stdout when plotting
                g = f[name]
                for d in ("time", "divergence"):
                    if d not in g or not isinstance(g[d], h5py.Dataset) or g[d].ndim != 1:
                        raise InputError(f"{path}: missing 1-D dataset /{name}/{d}")
                    if g[d].dtype.kind not in "fiu":
                        raise InputError(f"{path}: /{name}/{d}: expected numbers, found {g[d].dtype}")
                t, d = g["time"][()].astype(float), g["divergence"][()].astype(float)
                if len(t) != len(d):
                    raise InputError(f"{path}: /{name}/time has {len(t)} entries, "
                                     f"/{name}/divergence has {len(d)}")
                r["time"], r["divergence"] = t, d
            study["scene"] = {"rows": rows,
                              "reference": text_of(f["scene"].attrs.get("reference", "?"))}
        if study["query"] is None and study["scene"] is None:
            raise InputError(f"{path}: neither /query nor /scene: nothing to plot")
    return study


# ---------------------------------------------------------------- helpers

def num(x, spec=".4g"):
    return "nan" if x is None or not math.isfinite(x) else format(x, spec)


def short(x):
    """1e-3 rather than 0.001 or 1e-03, for dt annotations."""
    s = f"{x:.3g}"
    if "e" in s:
        m, e = s.split("e")
        s = f"{m}e{int(e)}"
    elif 0 < abs(x) < 0.1:
        m, e = f"{x:.2e}".split("e")
        s = f"{m.rstrip('0').rstrip('.')}e{int(e)}"
    return s


def series_of(rows):
    """(method, mode) pairs in order of first appearance."""
    out = []
    for r in rows:
        k = (r["method"], r["mode"])
        if k not in out:
            out.append(k)
    return out


def palette(keys):
    cmap = plt.get_cmap("tab10" if len(keys) <= 10 else "tab20")
    return {k: cmap(i % cmap.N) for i, k in enumerate(keys)}


def method_colours(rows):
    methods = []
    for r in rows:
        if r["method"] not in methods:
            methods.append(r["method"])
    return palette(methods)


def mode_marker(mode, modes):
    if mode in MODE_MARKER:
        return MODE_MARKER[mode]
    others = [m for m in modes if m not in MODE_MARKER]
    return OTHER_MARKERS[others.index(mode) % len(OTHER_MARKERS)]


def provenance(study):
    m = study["meta"]
    host = f"{m.get('hostname', '?')} ({m.get('cpu', '?')}, {m.get('cores', '?')} cores)"
    cmd = m.get("command", "?")
    cmd = cmd if len(cmd) <= 140 else cmd[:139] + "…"
    return (f"{os.path.basename(study['path'])}: created {m.get('created', '?')} on {host}, "
            f"{m.get('compiler', '?')} {m.get('build_type', '?')}\n$ {cmd}")


def save(fig, study, out):
    fig.supxlabel(provenance(study), fontsize=7, color="0.35")
    try:
        fig.savefig(out, dpi=110)
    except OSError as e:
        raise InputError(f"{out}: cannot write: {e.strerror or e}")
    finally:
        plt.close(fig)
    print(out, flush=True)


def label_minor(axis):
    """Label the 2 and 5 minor ticks of a log axis that spans under three decades."""
    lo, hi = axis.get_view_interval()
    if lo > 0 and hi / lo < 1e3:
        axis.set_minor_locator(ticker.LogLocator(base=10, subs=(2, 3, 4, 5, 6, 7, 8, 9)))
        axis.set_minor_formatter(ticker.FuncFormatter(
            lambda v, _: f"{v:g}" if round(v / 10 ** math.floor(math.log10(v) + 1e-9)) in (2, 5) else ""))
        axis.set_tick_params(which="minor", labelsize=8)


def pareto(points):
    """Indices of points (x, y) that no other point beats in both (lower is better)."""
    front = []
    for i, (x, y) in enumerate(points):
        if not any(u <= x and v <= y and (u < x or v < y) for u, v in points):
            front.append(i)
    return front


# ---------------------------------------------------------------- figure 1

def speed_error(study, out, show):
    q = study["query"]
    rows = [r for r in q["rows"] if r["family"] == "all"]
    if not rows:
        note(f"skipped {FIG_SPEED}: /query/table has no rows with family 'all'")
        return
    ok = [math.isfinite(r["ns_median"]) and r["ns_median"] > 0 and math.isfinite(r["error_p99"]) for r in rows]
    drawn = [r for r, good in zip(rows, ok) if good]
    undrawn = [r for r, good in zip(rows, ok) if not good]
    ys = [max(r["error_p99"], ERROR_FLOOR) for r in drawn]
    front = set(pareto([(r["ns_median"], y) for r, y in zip(drawn, ys)]))
    on_front = {id(drawn[i]) for i in front}
    if show:
        w = max(len("method"), *(len(r["method"]) for r in rows))
        print(f"== {FIG_SPEED}: /query/table rows of family 'all' (query set {q['dataset']}, "
              f"repeats {q['repeats']})")
        print(f"{'method':<{w}} {'mode':<6} {'queries':>8} {'hits':>8} {'FN':>6} {'FP':>6} {'rule':>5} "
              f"{'threw':>5} {'ns_median':>10} {'ns_p99':>10} {'ns_max':>10} {'error_median':>12} "
              f"{'error_p99':>12} {'error_max':>12} {'t_err_p99':>10} pareto")
        for r, good in zip(rows, ok):
            on = "yes" if id(r) in on_front else ("no" if good else "-")
            print(f"{r['method']:<{w}} {r['mode']:<6} {r['queries']:>8} {r['oracle_hits']:>8} "
                  f"{r['false_negatives']:>6} {r['false_positives']:>6} {r['rule_failures']:>5} "
                  f"{r['threw']:>5} {num(r['ns_median']):>10} {num(r['ns_p99']):>10} "
                  f"{num(r['ns_max']):>10} {num(r['error_median'], '.3e'):>12} "
                  f"{num(r['error_p99'], '.3e'):>12} {num(r['error_max'], '.3e'):>12} "
                  f"{num(r['time_error_p99'], '.3e'):>10} {on}")
    colours = method_colours(q["rows"])
    modes = [m for _, m in series_of(q["rows"])]
    fig, ax = plt.subplots(figsize=(12, 7), layout="constrained")
    for r, y in zip(drawn, ys):
        ax.scatter(r["ns_median"], y, s=80, marker=mode_marker(r["mode"], modes),
                   color=colours[r["method"]], edgecolors="k", linewidths=0.7, zorder=3,
                   label=f"{r['method']} ({r['mode']})")
        fails = [f"{k} {r[c]}" for k, c in (("FN", "false_negatives"), ("FP", "false_positives")) if r[c] > 0]
        if fails:
            ax.annotate(", ".join(fails), (r["ns_median"], y), xytext=(8, -13), textcoords="offset points",
                        fontsize=8, color="firebrick", zorder=4)
    if front:
        pts = sorted((drawn[i]["ns_median"], ys[i]) for i in front)
        ax.step([p[0] for p in pts], [p[1] for p in pts], where="post", color="0.25", ls="--", lw=1.2,
                zorder=2, label="Pareto front")
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=260, facecolors="none", edgecolors="0.25",
                   linewidths=1.0, zorder=2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    if drawn:
        x = np.array([r["ns_median"] for r in drawn])
        ax.set_xlim(x.min() / 1.6, x.max() * 1.6)
        ax.set_ylim(min(ys) / 30, max(ys) * 30)
    if any(r["error_p99"] <= 0 for r in drawn):
        ax.axhline(ERROR_FLOOR, color="0.6", lw=0.8, ls=":", zorder=1)
        ax.annotate("error 0", (0.005, ERROR_FLOOR), xycoords=("axes fraction", "data"),
                    xytext=(0, 3), textcoords="offset points", fontsize=8, color="0.4")
    label_minor(ax.xaxis)
    ax.set_xlabel("median time per query (ns, log scale)")
    ax.set_ylabel(f"99th-percentile error  |gap| / scale  (log scale; 0 drawn at {ERROR_FLOOR:g})")
    ax.grid(which="major", alpha=0.3)
    ax.grid(which="minor", alpha=0.1)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=9, title="method (mode)",
              title_fontsize=9, borderaxespad=0)
    queries = sorted({r["queries"] for r in rows})
    qtext = f"{queries[0]}" if len(queries) == 1 else f"{queries[0]}–{queries[-1]}"
    sub = (f"Pareto front (dashed step line, ringed): {len(front)} of {len(drawn)} method–modes not "
           f"beaten in both speed and error; red: false negatives / positives")
    if undrawn:
        sub += "\nnot drawn (NaN or non-positive time): " + ", ".join(
            f"{r['method']} ({r['mode']})" for r in undrawn)
    ax.set_title(sub, fontsize=9)
    fig.suptitle(f"Speed against error over all {qtext} queries of {os.path.basename(q['dataset'])} "
                 f"(lower left is better)", fontsize=12)
    save(fig, study, out)


# ---------------------------------------------------------------- figure 2

def failures_by_family(study, out, show):
    q = study["query"]
    rows = [r for r in q["rows"] if r["family"] != "all"]
    if not rows:
        note(f"skipped {FIG_FAMILY}: /query/table has no rows for a hard family (a family other than 'all')")
        return
    families = []
    for r in rows:
        if r["family"] not in families:
            families.append(r["family"])
    series = series_of(q["rows"])
    by_key = {(r["family"], r["method"], r["mode"]): r for r in rows}

    def fraction(r):
        return (r["false_negatives"] + r["false_positives"]) / r["queries"] if r["queries"] > 0 else math.nan

    if show:
        wf = max(len("family"), *(len(f) for f in families))
        wm = max(len("method"), *(len(m) for m, _ in series))
        print(f"== {FIG_FAMILY}: (false_negatives + false_positives) / queries per family")
        print(f"{'family':<{wf}} {'method':<{wm}} {'mode':<6} {'queries':>8} {'FN':>6} {'FP':>6} "
              f"{'FN+FP':>6} {'fraction':>10} {'rule':>5} {'threw':>5}")
        for fam in families:
            for m, mode in series:
                r = by_key.get((fam, m, mode))
                if r:
                    print(f"{fam:<{wf}} {m:<{wm}} {mode:<6} {r['queries']:>8} {r['false_negatives']:>6} "
                          f"{r['false_positives']:>6} {r['false_negatives'] + r['false_positives']:>6} "
                          f"{num(fraction(r), '.3e'):>10} {r['rule_failures']:>5} {r['threw']:>5}")
    fractions = [fraction(r) for r in rows]
    positive = [p for p in fractions if math.isfinite(p) and p > 0]
    qmax = max([r["queries"] for r in rows] + [1])
    smallest = min(positive + [1.0 / qmax])
    lo = 10 ** math.floor(math.log10(smallest)) / 10      # left edge of the axis: zero bars start here
    stub = lo * 1.8                                       # a zero is drawn as a bar from lo to stub
    hi = max(positive + [1.0 / qmax]) * 40                # room for the counts at the bar ends
    colours = method_colours(q["rows"])
    ns, gap = len(series), 1.0
    fig_h = max(5.0, 0.17 * len(families) * (ns + gap) + 2.2)
    fig, ax = plt.subplots(figsize=(13, fig_h), layout="constrained")
    centres, labels = [], []
    for g, fam in enumerate(families):
        base = g * (ns + gap)
        if g % 2 == 0:
            ax.axhspan(base - 0.6, base + ns - 0.4, color="0.94", zorder=0)
        qs = sorted({by_key[(fam, m, mode)]["queries"] for m, mode in series if (fam, m, mode) in by_key})
        centres.append(base + (ns - 1) / 2)
        labels.append(f"{fam}\n({qs[0] if len(qs) == 1 else f'{qs[0]}–{qs[-1]}'} queries)")
        for j, (m, mode) in enumerate(series):
            y = base + j
            r = by_key.get((fam, m, mode))
            if r is None:
                ax.text(lo * 1.1, y, "no row", va="center", fontsize=6.5, color="0.5")
                continue
            p = fraction(r)
            if not math.isfinite(p):
                ax.text(lo * 1.1, y, "no queries", va="center", fontsize=6.5, color="0.5")
                continue
            end = p if p > 0 else stub
            ax.barh(y, end - lo, left=lo, height=0.8, color=colours[m], hatch=MODE_HATCH.get(mode, "xx"),
                    edgecolor="k", linewidth=0.4, zorder=2, alpha=1.0 if p > 0 else 0.45)
            fn, fp = r["false_negatives"], r["false_positives"]
            lab = "0" if fn + fp == 0 else ", ".join(
                f"{k} {v}" for k, v in (("FN", fn), ("FP", fp)) if v > 0)
            ax.text(end * 1.15, y, lab, va="center", fontsize=6.5, zorder=3)
    ax.set_xscale("log")
    ax.set_xlim(lo, hi)
    ax.set_ylim(len(families) * (ns + gap) - gap - 0.4, -0.6)
    ax.set_yticks(centres, labels, fontsize=8)
    ax.tick_params(axis="y", length=0)
    ax.tick_params(axis="x", top=True, labeltop=True)
    ax.grid(axis="x", which="major", alpha=0.35)
    ax.set_xlabel("fraction of the family's queries that were false negatives or false positives "
                  "(log scale; 0 drawn as a stub at the left edge, labelled \"0\")")
    handles = [Patch(facecolor=colours[m], hatch=MODE_HATCH.get(mode, "xx"), edgecolor="k", linewidth=0.4,
                     label=f"{m} ({mode})") for m, mode in series]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8,
              title="method (mode)\nhatched: fixed", title_fontsize=8, borderaxespad=0)
    ax.set_title("bar ends: false-negative (FN) and false-positive (FP) counts; bars top to bottom in "
                 "legend order", fontsize=9)
    fig.suptitle(f"Failures per hard family ({os.path.basename(q['dataset'])}, "
                 f"repeats {q['repeats']})", fontsize=12)
    save(fig, study, out)


# ---------------------------------------------------------------- figure 3

def series_key(r):
    return r["scene"], r["method"], r["mode"]


def run_label(r, with_dt=True):
    s = f"{r['scene']} · {r['engine']} · {r['method']} {r['mode']}"
    return s + (f" · dt {short(r['dt'])}" if with_dt and r["engine"] != "event" else "")


def step_vs_event(study, out, show):
    sc = study["scene"]
    rows = sc["rows"]
    if not rows:
        note(f"skipped {FIG_SCENE}: /scene/table has no runs")
        return
    if show:
        wl = max(len(f"{r['scene']} {r['engine']} {r['method']} {r['mode']}") for r in rows)
        print(f"== {FIG_SCENE}: /scene/table (reference: {sc['reference']})")
        print(f"{'#':>3} {'scene engine method mode':<{wl}} {'dt':>9} {'wall_s':>10} {'energy_err':>10} "
              f"{'div_final':>10} {'lambda_1/s':>10} {'fit_from':>8} {'fit_to':>8} {'events':>8} "
              f"{'missed':>6} {'frames':>6} {'deepest':>10}")
        for r in rows:
            name = f"{r['scene']} {r['engine']} {r['method']} {r['mode']}"
            print(f"{r['index']:>3} {name:<{wl}} {short(r['dt']):>9} {num(r['wall_seconds']):>10} "
                  f"{num(r['energy_error_max'], '.3e'):>10} {num(r['divergence_final'], '.3e'):>10} "
                  f"{num(r['growth_rate']):>10} {num(r['fit_from']):>8} {num(r['fit_to']):>8} "
                  f"{r['events']:>8} {r['missed_contacts']:>6} {r['frames']:>6} "
                  f"{num(r['deepest_overlap'], '.3e'):>10}")
    keys = []
    for r in rows:
        if series_key(r) not in keys:
            keys.append(series_key(r))
    colours = palette(keys)
    # One marker (left) and one line style (right) per step size, largest dt first.
    dts = sorted({r["dt"] for r in rows if r["engine"] != "event"}, reverse=True)
    dt_marker = {dt: DT_MARKERS[i % len(DT_MARKERS)] for i, dt in enumerate(dts)}
    dt_style = {dt: DT_STYLES[i % len(DT_STYLES)] for i, dt in enumerate(dts)}
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(17, 8), layout="constrained", width_ratios=[1, 1.1])

    # Left: cost against energy error, one curve over dt per (scene, method, mode), events as stars.
    skipped, zero_e, zero_w, points = [], False, False, {}
    for r in rows:
        w, e = r["wall_seconds"], r["energy_error_max"]
        if not (math.isfinite(w) and math.isfinite(e)):
            skipped.append(run_label(r))
            continue
        zero_e |= e <= 0
        zero_w |= w <= 0
        points[r["index"]] = (max(w, WALL_FLOOR), max(e, ERROR_FLOOR))
    n_step = sum(1 for r in rows if r["engine"] != "event" and r["index"] in points)
    annotate_dt = n_step <= MAX_DT_LABELS
    for n_k, k in enumerate(keys):
        steps = sorted((r for r in rows if series_key(r) == k and r["engine"] != "event" and r["index"] in points),
                       key=lambda r: r["dt"])
        if steps:
            ax.plot([points[r["index"]][0] for r in steps], [points[r["index"]][1] for r in steps], "-",
                    color=colours[k], lw=1.4, zorder=3, label=f"{k[0]} · step · {k[1]} {k[2]} (over dt)")
        for r in steps:
            p = points[r["index"]]
            ax.plot(*p, marker=dt_marker[r["dt"]], ms=7, color=colours[k], mec="k", mew=0.5, zorder=4)
            if annotate_dt:
                text = f"dt {short(r['dt'])}" + (f", {r['missed_contacts']} missed" if r["missed_contacts"] else "")
                ax.annotate(text, p, xytext=(6, 4 if n_k % 2 == 0 else -11), textcoords="offset points",
                            fontsize=7.5, color="firebrick" if r["missed_contacts"] > 0 else "0.15")
        for n, r in enumerate(r for r in rows if series_key(r) == k and r["engine"] == "event"
                              and r["index"] in points):
            p = points[r["index"]]
            ax.scatter(*p, marker="*", s=300, color=colours[k], edgecolors="k", linewidths=0.6, zorder=5,
                       label=f"{k[0]} · event · {k[1]} {k[2]}" if n == 0 else None)
            if annotate_dt and r["missed_contacts"] > 0:
                ax.annotate(f"{r['missed_contacts']} missed", p, xytext=(8, -12), textcoords="offset points",
                            fontsize=7.5, color="firebrick")
    for dt in dts:
        ax.plot([], [], ls="", marker=dt_marker[dt], ms=7, color="0.7", mec="k", mew=0.5,
                label=f"step dt {short(dt)}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    if points:
        xs, ys = zip(*points.values())
        ax.set_xlim(min(xs) / 2.5, max(xs) * 4)
        ax.set_ylim(min(ys) / 30, max(ys) * 30)
    if zero_e:
        ax.axhline(ERROR_FLOOR, color="0.6", lw=0.8, ls=":", zorder=1)
        ax.annotate("energy error 0", (0.005, ERROR_FLOOR), xycoords=("axes fraction", "data"),
                    xytext=(0, 3), textcoords="offset points", fontsize=8, color="0.4")
    label_minor(ax.xaxis)
    ax.set_xlabel("wall time of the run (s, log scale" + (f"; 0 drawn at {WALL_FLOOR:g}" if zero_w else "") + ")")
    ax.set_ylabel(f"max over frames of |E − E₀| / |E₀|  (log scale; 0 drawn at {ERROR_FLOOR:g})")
    ax.grid(which="major", alpha=0.3)
    ax.grid(which="minor", alpha=0.1)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2, fontsize=8, frameon=False)
    title = "cost against energy conservation per run (lower left is better)\nstars: event engine; " + (
        "marker: step size dt" if annotate_dt else "marker: step size dt\n(too many runs to label each: dt and missed contacts are in the --print table)")
    if skipped:
        title += "\nnot drawn (NaN): " + "; ".join(skipped)
    ax.set_title(title, fontsize=10)

    # Right: divergence from the reference against time, with the fitted exponential over its window.
    fitted, tmax = False, 0.0
    for r in rows:
        k = series_key(r)
        ls, lw = ("-", 2.0) if r["engine"] == "event" else (dt_style[r["dt"]], 1.3)
        lam = r["growth_rate"]
        label = run_label(r) + (f": λ = {lam:.3g} /s" if math.isfinite(lam) else ": λ not fitted")
        if r["time"] is None:
            note(f"{FIG_SCENE}: no /scene/divergence/{r['index']:03d} for run {r['index']} ({run_label(r)}): "
                 "no curve drawn")
            bx.plot([], [], color=colours[k], ls=ls, lw=lw, label=label + " (no curve in file)")
            continue
        t, d = r["time"], r["divergence"]
        ok = np.isfinite(t) & np.isfinite(d) & (d > 0)
        if np.isfinite(t).any():
            tmax = max(tmax, float(np.nanmax(t)))
        if not ok.any():
            bx.plot([], [], color=colours[k], ls=ls, lw=lw, label=label + " (identically 0)")
            continue
        # Frames where the divergence is 0 are left as gaps, not joined across.
        bx.plot(t, np.where(ok, d, np.nan), color=colours[k], ls=ls, lw=lw, label=label, zorder=3)
        if math.isfinite(lam) and math.isfinite(r["fit_from"]) and math.isfinite(r["fit_to"]):
            w = ok & (t >= r["fit_from"]) & (t <= r["fit_to"])
            if w.sum() >= 2:
                # The fitted slope with the intercept that best matches the curve in the window.
                c = float(np.mean(np.log(d[w]) - lam * t[w]))
                tw = np.linspace(r["fit_from"], r["fit_to"], 50)
                bx.plot(tw, np.exp(c + lam * tw), color=colours[k], lw=7, alpha=0.22, solid_capstyle="butt",
                        zorder=2)
                fitted = True
    if fitted:
        bx.plot([], [], color="0.5", lw=7, alpha=0.3, label="fit: divergence ∝ exp(λ t) over its window")
    bx.set_yscale("log")
    if tmax > 0:
        bx.set_xlim(0, tmax)
    bx.set_xlabel("time t (s)")
    bx.set_ylabel("RMS over balls of the position difference from the reference\n"
                  "(scene units, m; log scale; zeros not drawn)")
    bx.grid(which="major", alpha=0.3)
    bx.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7.5, borderaxespad=0,
              title="run: fitted growth rate λ", title_fontsize=8)
    bx.set_title("divergence from the reference run\nsolid: event engine; line style: step size dt; "
                 "wide pale band: the fitted exponential", fontsize=10)
    fig.suptitle(f"Step against event: {len(rows)} scene runs (reference: {sc['reference']})", fontsize=12)
    save(fig, study, out)


# ---------------------------------------------------------------- main

def main(argv):
    ap = OneLineParser(prog=PROG, description=__doc__.split("\n\n")[0],
                       epilog="Exit codes: 0 success, 2 bad input or usage. Layout of the study file: "
                              "see the C++ writer of `collide2d study`.")
    ap.add_argument("study", metavar="STUDY.h5", help="study file written by `collide2d study` (HDF5)")
    ap.add_argument("-o", "--outdir", help="directory for the PNGs (created if missing; "
                                           "default: the directory of STUDY.h5)")
    ap.add_argument("--print", dest="show", action="store_true",
                    help="also print the numbers behind each figure as tables")
    args = ap.parse_args(argv)
    try:
        study = load(args.study)
        outdir = args.outdir or os.path.dirname(os.path.abspath(args.study))
        try:
            os.makedirs(outdir, exist_ok=True)
        except OSError as e:
            raise InputError(f"{outdir}: cannot create the output directory: {e.strerror or e}")
        if not os.access(outdir, os.W_OK):
            raise InputError(f"{outdir}: cannot write output here")
        if study["query"] is None:
            note(f"skipped {FIG_SPEED} and {FIG_FAMILY}: {args.study} has no /query group")
        else:
            speed_error(study, os.path.join(outdir, FIG_SPEED), args.show)
            failures_by_family(study, os.path.join(outdir, FIG_FAMILY), args.show)
        if study["scene"] is None:
            note(f"skipped {FIG_SCENE}: {args.study} has no /scene group")
        else:
            step_vs_event(study, os.path.join(outdir, FIG_SCENE), args.show)
    except InputError as e:
        sys.stderr.write(f"{PROG}: {' '.join(str(e).split())}\n")
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
