#!/bin/bash
# collide2d bench lcp on two small lattice piles: the CSV has its header and
# one row per pile and mode, each pile has the contacts its packing gives
# (w floor, 2 walls a long row, w − 1 or w − 2 in a row, 2 (w − 1) between
# a long and a short row), and the forces solved carry the pile: the floor's
# sum is the weight to 1e-9 (rounding of sums of a few hundred forces is
# 1e-13; an answer off its conditions misses by far more: balls that fall).
set -euo pipefail
exe=$1
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$exe" bench lcp --widths 4,7 --modes strict,fixed > "$out"
cat "$out"
/usr/bin/python3 - "$out" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys()) == "pile,balls,rows,nonzeros,mode,factor_us,fill,solve_us,rounds,weight_error".split(","), rows[0].keys()
assert len(rows) == 4, len(rows)
for r in rows:
    w = int(r["pile"].split("_")[1].split("x")[0])
    h = int(r["pile"].split("x")[1])
    long_rows, short_rows = (h + 1) // 2, h // 2
    balls = long_rows * w + short_rows * (w - 1)
    contacts = w + 2 * long_rows + long_rows * (w - 1) + short_rows * (w - 2) + (h - 1) * 2 * (w - 1)
    assert int(r["balls"]) == balls, (r, balls)
    assert int(r["rows"]) == contacts, (r, contacts)
    assert float(r["factor_us"]) > 0 and float(r["solve_us"]) > 0, r
    assert float(r["weight_error"]) < 1e-9, r
print("bench lcp: 4 rows, the contacts of each packing, the floor carries the weight")
PY
