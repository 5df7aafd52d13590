#!/usr/bin/python3
"""Two sweep files hold the same results, bit for bit (issue 16).

Compares every dataset and every attribute of two `collide2d props` or
`collide2d study` files, except what depends on the ranks, the machine or
the moment, all kept under names that say so:
  - groups /timing and /provenance (who ran what, when, for how long);
  - datasets named ns_*, wall_seconds and /query/per_query/*/ns (times);
  - attributes created, command, hostname, cpu, cores of the root group.
Exit 0 when equal; 1 naming the first difference.
Usage: compare_sweep_files.py A.h5 B.h5
"""
import re
import sys

import h5py
import numpy as np

TIMING_GROUPS = ("timing", "provenance")
TIMING_DATASET = re.compile(r"(^|/)(ns_[a-z0-9]+|wall_seconds|ns)$")
MOMENT_ATTRIBUTES = {"created", "command", "hostname", "cpu", "cores"}


def items(f):
    out = {}

    def visit(name, obj):
        if name.split("/")[0] in TIMING_GROUPS:
            return
        out[name] = obj

    f.visititems(visit)
    return out


def same_values(a, b):
    if a.dtype.kind in "fc" and b.dtype.kind in "fc":
        return a.shape == b.shape and np.array_equal(a.view(np.uint64) if a.dtype == np.float64 else a,
                                                     b.view(np.uint64) if b.dtype == np.float64 else b)
    return a.shape == b.shape and np.array_equal(a, b)


def compare_attributes(name, a, b):
    keys = set(a.attrs) | set(b.attrs)
    if name == "/":
        keys -= MOMENT_ATTRIBUTES
    for k in sorted(keys):
        if k not in a.attrs or k not in b.attrs:
            return f"{name}: attribute {k} in only one file"
        if not same_values(np.asarray(a.attrs[k]), np.asarray(b.attrs[k])):
            return f"{name}: attribute {k}: {a.attrs[k]!r} != {b.attrs[k]!r}"
    return None


def main(path_a, path_b):
    with h5py.File(path_a, "r") as a, h5py.File(path_b, "r") as b:
        problem = compare_attributes("/", a, b)
        if problem:
            return problem
        ia, ib = items(a), items(b)
        if set(ia) != set(ib):
            return f"objects in only one file: {sorted(set(ia) ^ set(ib))}"
        compared = 0
        for name in sorted(ia):
            problem = compare_attributes(name, ia[name], ib[name])
            if problem:
                return problem
            if isinstance(ia[name], h5py.Dataset) and not TIMING_DATASET.search(name):
                if not same_values(ia[name][()], ib[name][()]):
                    return f"/{name} differs"
                compared += 1
        print(f"{path_a} and {path_b}: {compared} datasets equal bit for bit (times and provenance aside)")
    return None


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    problem = main(sys.argv[1], sys.argv[2])
    if problem:
        print(f"DIFFER: {problem}", file=sys.stderr)
        sys.exit(1)
