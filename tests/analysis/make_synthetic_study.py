#!/usr/bin/python3
"""Write a small synthetic study file in the layout `collide2d study` writes
("collide2d study 1"; the layout is described at the top of analysis/plot_study.py's
reader and in the study writer), for tests/analysis/test_plot_study.sh.

    make_synthetic_study.py OUT.h5 [--levels both|query|scene]

/query: families near_miss, grazing, thin_fast and "all"; methods analytic
(strict, fixed), "bisection 1e-6" (strict), seed (strict, fixed) and
"eigen companion" (strict, with no thin_fast row). In the "all" rows the
Pareto front of (ns_median, error_p99) is seed fixed, seed strict and
analytic fixed; analytic strict ties analytic fixed on error but is slower.
/scene: gas (event strict and fixed, step at dt 1e-2, 1e-3, 1e-4) and abound
(event, step at dt 1e-3 with no fitted growth rate), each with a divergence
curve; gas event fixed is identically 0. All strings are variable-length UTF-8.
"""
import argparse

import h5py
import numpy as np

STR = h5py.string_dtype("utf-8")

FAMILIES = {"near_miss": 500, "grazing": 400, "thin_fast": 300}
ALL_QUERIES = 3000
# (method, mode): ns_median of the "all" row, error_p99 of the "all" row,
# per-family (false negatives, false positives); families absent are not written.
SERIES = {
    ("analytic", "strict"): (152.3, 0.0, {"near_miss": (0, 0), "grazing": (0, 0), "thin_fast": (0, 0)}),
    ("analytic", "fixed"): (140.1, 0.0, {"near_miss": (0, 0), "grazing": (0, 1), "thin_fast": (0, 0)}),
    ("bisection 1e-6", "strict"): (2140.0, 3.2e-7, {"near_miss": (25, 0), "grazing": (9, 0), "thin_fast": (3, 0)}),
    ("seed", "strict"): (95.5, 4.1e-12, {"near_miss": (0, 0), "grazing": (0, 0), "thin_fast": (2, 0)}),
    ("seed", "fixed"): (88.0, 7.7e-10, {"near_miss": (0, 0), "grazing": (0, 0), "thin_fast": (5, 0)}),
    ("eigen companion", "strict"): (610.0, 1.2e-15, {"near_miss": (0, 3), "grazing": (0, 0)}),
}

# scene, engine, method, mode, dt, wall_seconds, energy_error_max, growth_rate, missed_contacts
RUNS = [
    ("gas", "event", "analytic", "strict", 0.0, 0.84, 2.2e-15, 3.1, 0),
    ("gas", "event", "analytic", "fixed", 0.0, 0.91, 0.0, float("nan"), 0),
    ("gas", "step", "analytic", "strict", 1e-2, 0.05, 3.4e-2, 2.9, 12),
    ("gas", "step", "analytic", "strict", 1e-3, 0.41, 3.1e-3, 3.0, 1),
    ("gas", "step", "analytic", "strict", 1e-4, 3.9, 2.9e-4, 3.05, 0),
    ("abound", "event", "seed", "strict", 0.0, 0.12, 8e-16, 1.4, 0),
    ("abound", "step", "seed", "strict", 1e-3, 0.3, 1.1e-3, float("nan"), 4),
]


def strings(group, name, values):
    group.create_dataset(name, data=np.array(values, dtype=object), dtype=STR)


def write_query(f):
    q = f.create_group("query")
    q.attrs["dataset"] = "datasets/queries/hard_families.h5"
    q.attrs["repeats"] = np.int64(5)
    rows = []
    for (method, mode), (ns, err, fam) in SERIES.items():
        fn_all = sum(v[0] for v in fam.values())
        fp_all = sum(v[1] for v in fam.values())
        rows.append(("all", method, mode, ALL_QUERIES, fn_all, fp_all, ns, err))
        for k, (name, n) in enumerate(FAMILIES.items()):
            if name in fam:
                rows.append((name, method, mode, n, *fam[name], ns * (1.1 + 0.2 * k), err * (2 + k)))
    t = q.create_group("table")
    col = lambda i: [r[i] for r in rows]  # noqa: E731
    strings(t, "family", col(0))
    strings(t, "method", col(1))
    strings(t, "mode", col(2))
    queries = np.array(col(3), np.int64)
    fn, fp = np.array(col(4), np.int64), np.array(col(5), np.int64)
    t["queries"] = queries
    t["oracle_hits"] = queries // 2 - fn
    t["false_negatives"] = fn
    t["false_positives"] = fp
    t["rule_failures"] = np.zeros(len(rows), np.int64)
    t["threw"] = np.zeros(len(rows), np.int64)
    ns, err = np.array(col(6)), np.array(col(7))
    t["ns_median"], t["ns_p99"], t["ns_max"] = ns, ns * 2.5, ns * 40
    t["error_median"], t["error_p99"], t["error_max"] = err / 100, err, err * 10
    terr = err / 50
    terr[[i for i, r in enumerate(rows) if r[1] == "bisection 1e-6" and r[0] == "thin_fast"]] = np.nan
    t["time_error_median"], t["time_error_p99"], t["time_error_max"] = terr / 10, terr, terr * 3


def write_scene(f):
    s = f.create_group("scene")
    s.attrs["reference"] = "event engine, bisection 1e-12, strict, 4x the default precision"
    t = s.create_group("table")
    col = lambda i: [r[i] for r in RUNS]  # noqa: E731
    strings(t, "scene", col(0))
    strings(t, "engine", col(1))
    strings(t, "method", col(2))
    strings(t, "mode", col(3))
    t["dt"], t["wall_seconds"], t["energy_error_max"] = col(4), col(5), col(6)
    t["growth_rate"] = col(7)
    t["missed_contacts"] = np.array(col(8), np.int64)
    frames = 201
    time = np.linspace(0.0, 5.0, frames)
    finals, fit_from, fit_to = [], [], []
    for i, (scene, engine, method, mode, dt, _, _, lam, _) in enumerate(RUNS):
        if mode == "fixed":
            div = np.zeros(frames)
        else:
            a0 = 1e-13 if engine == "event" else 1e-3 * dt
            rate = lam if np.isfinite(lam) else 1.0
            div = np.minimum(a0 * np.exp(rate * time) * (1 + 0.1 * np.sin(7 * time + i)), 0.5)
            div[0] = 0.0
        g = s.create_group(f"divergence/{i:03d}")
        g["time"], g["divergence"] = time, div
        finals.append(div[-1])
        fit_from.append(0.5 if np.isfinite(lam) else np.nan)
        fit_to.append(min(4.0, np.log(0.4 / (1e-13 if engine == "event" else 1e-3 * dt)) / lam)
                      if np.isfinite(lam) else np.nan)
    t["divergence_final"], t["fit_from"], t["fit_to"] = finals, fit_from, fit_to
    t["events"] = np.array([12000 if e == "event" else 9000 for e in col(1)], np.int64)
    t["frames"] = np.full(len(RUNS), frames, np.int64)
    t["deepest_overlap"] = [0.0 if e == "event" else 1e-4 for e in col(1)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="study file to write (HDF5)")
    ap.add_argument("--levels", choices=["both", "query", "scene"], default="both")
    args = ap.parse_args()
    with h5py.File(args.out, "w") as f:
        f.attrs["format"] = "collide2d study 1"
        f.attrs["created"] = "2025-01-01T00:00:00Z"
        f.attrs["command"] = "collide2d study --queries datasets/queries/hard_families.h5 --out study.h5"
        f.attrs["compiler"] = "GCC 12.2.0"
        f.attrs["build_type"] = "Release"
        f.attrs["hostname"] = "synthetic"
        f.attrs["cpu"] = "Synthetic CPU @ 3.0GHz"
        f.attrs["cores"] = np.int64(2)
        if args.levels in ("both", "query"):
            write_query(f)
        if args.levels in ("both", "scene"):
            write_scene(f)


if __name__ == "__main__":
    main()
