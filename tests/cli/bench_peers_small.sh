#!/bin/bash
# collide2d bench peers, short: one row per scene and engine, and collide2d's
# own rows keep its promises: elastic gases and the tunnelling trap keep their
# energy to 1e-12 (issue 12's bound; rounding in ~1e5 collisions grows like
# 2e-16 sqrt(1e5) ~ 1e-13), no overlap deeper than 1e-6 of the radius (issue
# 11's), no ball leaves a box. The peers'
# rows are reported, not judged.
set -euo pipefail
exe=$1
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$exe" bench peers --gas-seconds 0.5 --pile-seconds 2 > "$out"
cat "$out"
/usr/bin/python3 - "$out" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
engines = ["collide2d", "box2d", "box2d_threshold0", "chipmunk"]
scenes = ["dense_gas_2000_speed1", "dense_gas_2000_speed10", "tunnelling_trap", "pile_50"]
assert [(r["scene"], r["engine"]) for r in rows] == [(s, e) for s in scenes for e in engines], rows
for r in rows:
    if r["engine"] != "collide2d":
        continue
    assert float(r["deepest_overlap"]) <= 1e-6, r
    assert int(r["balls_outside"]) == 0, r
    if r["scene"] != "pile_50":
        assert abs(float(r["energy_change"])) <= 1e-12, r
print("bench peers: 16 rows; collide2d kept energy, no overlap, no escape")
PY
# The figures of analysis/plot_bench.py from these rows and a tiny bench sim.
dir=$(mktemp -d)
trap 'rm -f "$out"; rm -rf "$dir"' EXIT
"$exe" bench sim --sizes 50,200 --etas 0.3 --collisions 2000 --no-settling --modes strict > "$dir/sim.csv"
src=$(cd "$(dirname "$0")/../.." && pwd)
/usr/bin/python3 "$src/analysis/plot_bench.py" "$out" --sim "$dir/sim.csv" -o "$dir"
test -s "$dir/bench_peers.png" && test -s "$dir/bench_sim.png"
echo "plot_bench.py: both figures written"
