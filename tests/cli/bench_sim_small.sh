#!/bin/bash
# collide2d bench sim on small gases: the CSV has its header and one row per
# gas and mode, every run made collisions, and as many as the Enskog estimate
# it was sized by, within a factor of two (the start is not Maxwellian, the
# box has walls: the estimate is rough, the benchmark prints what it measures).
set -euo pipefail
exe=$1
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$exe" bench sim --sizes 100 --etas 0.1,0.45 --collisions 20000 --no-settling --modes strict,fixed > "$out"
cat "$out"
/usr/bin/python3 - "$out" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys()) == "scene,n,eta,mode,collisions,wall_s,cpu_s,collisions_per_s,bytes_per_ball".split(","), rows[0].keys()
assert len(rows) == 4, len(rows)
assert {(r["eta"], r["mode"]) for r in rows} == {(e, m) for e in ("0.10", "0.45") for m in ("strict", "fixed")}
for r in rows:
    c = int(r["collisions"])
    assert 10000 <= c <= 40000, r
    assert float(r["cpu_s"]) > 0 and float(r["collisions_per_s"]) > 0, r
print("bench sim: 4 rows, collisions within a factor of two of the estimate")
PY
