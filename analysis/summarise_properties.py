#!/usr/bin/python3
"""Summarise property outcome files (COLLIDE2D_PROPERTY_RECORD, layout at the
top of properties/outcome_record.cpp).

    summarise_properties.py FILE.h5 [FILE2.h5 ...] [--top N]

Prints, per file, one row per property and mode (the latest record of each):
cases judged, cases discarded (a check that did not apply: neither a pass nor
a failure), failures, seed, seconds and the most frequent tags of the
distribution, then the reasons for the discards. With several files, a
comparison follows: judged/discarded/failures of each property and mode in
each file, files in the order their first runs began. Records written before
discards were counted show "-" for them.
Exit 2 with one line on stderr for a missing or unreadable file.
"""
import sys
from cli_support import OneLineParser  # noqa: E402

try:
    import h5py
    import numpy as np
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"summarise_properties.py: needs h5py and numpy (/usr/bin/python3): {e}\n")
    sys.exit(2)

FORMAT = "collide2d property outcomes 1"


class BadInput(Exception):
    pass


def text(value):
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def read_record(group):
    """One property run as a dict."""
    a = group.attrs
    try:
        tags = [text(t) for t in group["distribution_tags"][()]]
        counts = [int(c) for c in np.asarray(group["distribution_counts"][()])]
        reasons = {}
        if "discard_reasons" in group:  # absent from records older than the discard counts
            reasons = dict(zip([text(t) for t in group["discard_reasons"][()]],
                               [int(c) for c in np.asarray(group["discard_counts"][()])]))
        return {
            "property": text(a["property"]),
            "mode": text(a["mode"]),
            "seed": int(a["seed"]),
            "cases": int(a["cases"]),
            "judged": int(a["judged"]) if "judged" in a else int(a["cases"]),
            "discarded": int(a["discarded"]) if "discarded" in a else None,
            "rejected": int(a["rejected"]) if "rejected" in a else None,
            "discard_reasons": reasons,
            "failures": int(a["failures"]),
            "gave_up": bool(a["gave_up"]),
            "seconds": float(a["seconds"]),
            "recorded": text(a["recorded"]),
            "counterexample": text(a["counterexample"]),
            "distribution": dict(zip(tags, counts)),
        }
    except KeyError as e:
        raise BadInput(f"{group.name}: missing {e}") from None


def read_file(path):
    """(runs, records): the run groups' attributes and every record, in order."""
    try:
        f = h5py.File(path, "r")
    except FileNotFoundError:
        raise BadInput("no such file") from None
    except OSError as e:
        raise BadInput(f"not a readable HDF5 file ({e})") from None
    with f:
        if text(f.attrs.get("format", "")) != FORMAT or "runs" not in f:
            raise BadInput(f"not a property outcome file (no /runs or format attribute '{FORMAT}')")
        runs, records = [], []
        for run_name in sorted(f["runs"]):
            run = f["runs"][run_name]
            runs.append({k: text(v) if isinstance(v, (bytes, str)) else v for k, v in run.attrs.items()})
            for rec_name in sorted(run):
                records.append(read_record(run[rec_name]))
    return runs, records


def latest_by_property(records):
    """The last record of each (property, mode), in order of first appearance."""
    out = {}
    for r in records:
        out[(r["property"], r["mode"])] = r
    return out


def top_tags(distribution, n):
    total = sum(distribution.values())
    if total == 0:
        return "-"
    items = sorted(distribution.items(), key=lambda kv: (-kv[1], kv[0]))[:n]
    return "; ".join(f"{100.0 * c / total:.0f}% {t}" for t, c in items)


def clip(s, width):
    return s if len(s) <= width else s[: width - 1] + "…"


def print_file_table(path, runs, records, top):
    hosts = sorted({f"{r.get('hostname', '?')} ({r.get('cores', '?')} cores)" for r in runs})
    compilers = sorted({str(r.get("compiler", "?")) for r in runs})
    print(f"== {path}: {len(records)} records in {len(runs)} runs; {', '.join(hosts)}; {', '.join(compilers)}")
    print(f"{'property':<60} {'mode':<6} {'judged':>7} {'discarded':>9} {'fail':>4} {'seed':>20} {'seconds':>8}  top tags")
    for (name, mode), r in latest_by_property(records).items():
        fail = f"{r['failures']}{'*' if r['gave_up'] else ''}"
        discarded = "-" if r["discarded"] is None else str(r["discarded"])
        print(f"{clip(name, 60):<60} {mode:<6} {r['judged']:>7} {discarded:>9} {fail:>4} {r['seed']:>20} "
              f"{r['seconds']:>8.2f}  {top_tags(r['distribution'], top)}")
        if r["discard_reasons"]:
            why = "; ".join(f"{c} x {t}" for t, c in sorted(r["discard_reasons"].items(), key=lambda kv: (-kv[1], kv[0])))
            print(f"{'':<6}discarded, not applicable: {clip(why, 110)}")
        if r["counterexample"]:
            first = r["counterexample"].strip().splitlines()[0] if r["counterexample"].strip() else ""
            print(f"{'':<6}counterexample: {clip(first, 110)}")
    if any(r["gave_up"] for r in records):
        print("(* gave up: too many cases discarded)")


def print_comparison(paths, tables):
    print("== comparison: judged/discarded/failures per file, files ordered by their first run's start")
    keys = []
    for t in tables:
        for k in t:
            if k not in keys:
                keys.append(k)
    header = "  ".join(f"{'file ' + str(i + 1):>14}" for i in range(len(paths)))
    print(f"{'property':<60} {'mode':<6} {header}  trend")
    for k in keys:
        cells, cases = [], []
        for t in tables:
            r = t.get(k)
            discarded = "-" if not r or r["discarded"] is None else str(r["discarded"])
            cells.append(f"{r['judged']}/{discarded}/{r['failures']}" if r else "-")
            if r:
                cases.append(r["cases"])
        fails = [t[k]["failures"] for t in tables if k in t]
        trend = "new failure" if len(fails) > 1 and fails[-1] > fails[0] else (
            "fixed" if len(fails) > 1 and fails[-1] < fails[0] else "")
        print(f"{clip(k[0], 60):<60} {k[1]:<6} " + "  ".join(f"{c:>14}" for c in cells) + f"  {trend}")
    for i, p in enumerate(paths):
        print(f"  file {i + 1}: {p}")


def main(argv):
    parser = OneLineParser(description=__doc__.split("\n\n")[0],
                                     epilog="Layout: see the comment at the top of properties/outcome_record.cpp.")
    parser.add_argument("files", nargs="+", metavar="FILE.h5", help="outcome files (COLLIDE2D_PROPERTY_RECORD)")
    parser.add_argument("--top", type=int, default=3, help="distribution tags shown per property (default 3)")
    args = parser.parse_args(argv)
    loaded = []
    for path in args.files:
        try:
            loaded.append((path, *read_file(path)))
        except BadInput as e:
            one_line = " ".join(str(e).split())
            sys.stderr.write(f"summarise_properties.py: {path}: {one_line}\n")
            return 2
    for path, runs, records in loaded:
        print_file_table(path, runs, records, args.top)
    if len(loaded) > 1:
        # Over time: files ordered by when their first run began.
        loaded.sort(key=lambda item: min((str(r.get("started", "")) for r in item[1]), default=""))
        print_comparison([p for p, _, _ in loaded], [latest_by_property(r) for _, _, r in loaded])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
