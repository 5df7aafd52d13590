#!/bin/bash
# collide2d bench toi on the engine's own query mixes: the CSV has its header
# and a row per mix and mode, every query was answered, and the analytic
# method finds the same contacts in strict and fixed mode (the same queries,
# converted exactly: a different count would be a wrong answer in one mode).
set -euo pipefail
exe=$1
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$exe" bench toi --queries 3000 --families engine_gas,engine_abound --modes strict,fixed --methods analytic > "$out"
cat "$out"
/usr/bin/python3 - "$out" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys()) == "family,method,mode,queries,ns_per_query,hits".split(","), rows[0].keys()
assert {(r["family"], r["mode"]) for r in rows} == {(f, m) for f in ("engine_gas", "engine_abound") for m in ("strict", "fixed")}, rows
for r in rows:
    assert int(r["queries"]) == 3000 and float(r["ns_per_query"]) > 0, r
    assert 0 < int(r["hits"]) < 3000, r
for f in ("engine_gas", "engine_abound"):
    hits = {r["mode"]: int(r["hits"]) for r in rows if r["family"] == f}
    assert hits["strict"] == hits["fixed"], (f, hits)
print("bench toi: both engine mixes, same contacts in strict and fixed mode")
PY
