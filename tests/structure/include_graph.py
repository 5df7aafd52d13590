#!/usr/bin/python3
"""The layering of src/, checked from the includes themselves.

Fails (exit 1, naming the files) when
  - a folder of src/ includes a folder above it in LAYERS, the order of
    docs/ARCHITECTURE.md's table (src/collide2d/<layer> counts as one folder
    per layer), or the folders include each other in a cycle;
  - the core (src/collide2d/) includes anything from the laboratory, the
    program or the peers (lab/, cli/, peers/), or Eigen or Boost: a user of
    collide2d::core must pull in neither.
Usage: include_graph.py SRC_DIR
"""
import collections
import pathlib
import re
import sys


# From the bottom up: a folder may include only folders before it.
LAYERS = ["collide2d/numeric", "collide2d/geometry", "collide2d/toi", "collide2d/response", "collide2d/scene",
          "collide2d/sim", "collide2d/io", "collide2d", "lab", "peers", "cli"]

QUOTED_OR_ANGLED = re.compile(r'#include\s*[<"]([^>"]+)[>"]')
EIGEN_OR_BOOST = re.compile(r"(^|/)(Eigen|boost)/")


def folder(path: str) -> str:
    parts = path.split("/")
    if parts[0] == "collide2d" and len(parts) > 2:
        return "collide2d/" + parts[1]
    return parts[0]


def main(src: pathlib.Path) -> int:
    edges = collections.defaultdict(set)
    where = {}
    problems = []
    for f in sorted(src.rglob("*")):
        if f.suffix not in (".hpp", ".cpp", ".in"):
            continue
        rel = str(f.relative_to(src))
        here = folder(rel)
        text = f.read_text()
        for inc in QUOTED_OR_ANGLED.findall(text):
            there = folder(inc)
            if rel.startswith("collide2d/") and (there in ("lab", "cli", "peers") or EIGEN_OR_BOOST.search(inc)):
                problems.append(f"{rel}: the core includes {inc}")
            if there not in LAYERS or there == here:
                continue  # the standard library and other packages
            edges[here].add(there)
            where.setdefault((here, there), rel)
            if here in LAYERS and LAYERS.index(there) > LAYERS.index(here):
                problems.append(f"{rel}: {here} includes {inc}, a layer above it")

    state = {}

    def visit(u, path):
        state[u] = "open"
        for v in sorted(edges.get(u, ())):
            if state.get(v) == "open":
                cycle = path[path.index(v):] + [v] if v in path else [u, v]
                problems.append("folders include each other: " + " -> ".join(cycle) +
                                " (e.g. " + where[(u, v)] + ")")
            elif v not in state:
                visit(v, path + [v])
        state[u] = "done"

    for u in sorted(edges):
        if u not in state:
            visit(u, [u])
    for p in problems:
        print(p)
    if not problems:
        print(f"{len(edges)} folders, {sum(len(v) for v in edges.values())} folder-to-folder includes, each "
              "downwards, no cycle; the core includes neither lab/, cli/, peers/, Eigen nor Boost")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "src")))
