#!/usr/bin/env bash
# Issue 16: sweeps under MPI. One case per ctest entry:
#   sweep_ranks.sh COLLIDE2D SUITE MPIEXEC SOURCE_DIR CASE
# props_ranks       1 rank and 2 ranks give the same outcomes, bit for bit
# study_ranks       the same for `study --no-scenes`
# props_kill_resume one rank killed mid-sweep: a readable OUT.partial names the
#                   missing cases, --resume runs exactly those, and the file
#                   equals an uninterrupted sweep's
# props_reproduce   a failure found by the sweep on rank 1 is the failure the
#                   ordinary suite reproduces from the reproduce string: the
#                   same shrunk scene, byte for byte
set -euo pipefail
exe=$(realpath "$1") suite=$(realpath "$2") mpiexec=$3 root=$(realpath "$4") case=$5
compare=$root/tests/sweep/compare_sweep_files.py
py=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# Open MPI refuses to start as root without these; CI runs as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mpirun() { "$mpiexec" --oversubscribe "$@"; }

fail() { echo "FAIL ($case): $*" >&2; exit 1; }

# Three properties, both modes: 6 pairs x 8 seeds = 48 cases (seconds).
props_args=(props --cases 8 --properties energy-kept,momentum-kept,no-overlap --max-size 40)

case $case in
props_ranks)
  "$exe" "${props_args[@]}" -o direct.h5 > direct.txt
  mpirun -n 1 "$exe" "${props_args[@]}" -o one.h5 > one.txt
  mpirun -n 2 "$exe" "${props_args[@]}" -o two.h5 > two.txt
  grep -q "on 2 ranks" two.txt || fail "the 2-rank sweep did not run on 2 ranks: $(tail -2 two.txt)"
  $py "$compare" direct.h5 one.h5 || fail "no mpirun and mpirun -n 1 differ"
  $py "$compare" one.h5 two.h5 || fail "1 rank and 2 ranks differ"
  # Both ranks did work, and the file says how the cases were shared.
  $py - two.h5 <<'PY' || fail "two.h5: ranks or provenance wrong"
import sys, h5py, numpy as np
with h5py.File(sys.argv[1]) as f:
    ranks = f["/timing/rank"][()]
    assert set(ranks.tolist()) == {0, 1}, ranks
    assert (ranks == np.arange(len(ranks)) % 2).all(), "case c not on rank c mod 2"
    assert f["/provenance"].attrs["ranks"] == 2
    assert f.attrs["complete"] == 1 and len(f["/missing"]) == 0
    assert (f["/cases/verdict"].asstr()[()] != "missing").all()
PY
  # The comparison itself can fail: another seed gives other scenes.
  "$exe" "${props_args[@]}" --seed 7 -o other.h5 > /dev/null
  if $py "$compare" one.h5 other.h5 2> /dev/null; then fail "the comparison passed two different sweeps"; fi
  ;;
study_ranks)
  args=(study --no-scenes --repeats 1)
  mpirun -n 1 "$exe" "${args[@]}" --limit-per-family 3 -o one.h5 > one.txt
  mpirun -n 2 "$exe" "${args[@]}" --limit-per-family 3 -o two.h5 > two.txt
  grep -q "on 2 ranks" two.txt || fail "the 2-rank study did not run on 2 ranks"
  $py "$compare" one.h5 two.h5 || fail "1 rank and 2 ranks differ"
  "$exe" "${args[@]}" --limit-per-family 4 -o other.h5 > /dev/null
  if $py "$compare" one.h5 other.h5 2> /dev/null; then fail "the comparison passed two different studies"; fi
  ;;
props_kill_resume)
  # run-file-replay writes and reads a run file per case: about 3 ms a case,
  # 1000 cases, so the kill lands well inside the sweep.
  args=(props --cases 500 --properties run-file-replay)
  "$exe" "${args[@]}" -o whole.h5 > whole.txt
  "$mpiexec" --oversubscribe -n 2 "$exe" "${args[@]}" -o cut.h5 > cut.txt 2> cut.err &
  launcher=$!
  # Wait until some cases are in, then kill rank 1 (the second process).
  for _ in $(seq 1 300); do
    [[ -f cut.h5.parts.jsonl ]] && (( $(wc -l < cut.h5.parts.jsonl) > 20 )) && break
    sleep 0.1
  done
  # Rank 1 is the process whose environment says so (Open MPI's variable).
  rank1=
  for p in $(pgrep -f -- "props --cases 500" || true); do
    [[ $p == "$launcher" ]] && continue
    if tr '\0' '\n' < /proc/$p/environ 2> /dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then rank1=$p; fi
  done
  [[ -n $rank1 ]] || fail "no rank 1 process found"
  kill -9 "$rank1"
  code=0
  wait $launcher || code=$?
  (( code != 0 )) || fail "mpirun exited 0 after a rank was killed"
  [[ ! -e cut.h5 ]] || fail "cut.h5 exists after a killed sweep"
  [[ -f cut.h5.partial ]] || fail "no cut.h5.partial after the kill: $(tail -3 cut.err)"
  $py - cut.h5.partial cut.h5.parts.jsonl <<'PY' || fail "cut.h5.partial does not name the missing cases"
import json, sys, h5py
with h5py.File(sys.argv[1]) as f:
    missing = set(f["/missing"][()].tolist())
    verdict = f["/cases/verdict"].asstr()[()]
    total = len(verdict)
    assert f.attrs["complete"] == 0
    assert missing == {c for c in range(total) if verdict[c] == "missing"}
    assert 0 < len(missing) < total, (len(missing), total)
    # Every case it says is finished is in the journal too.
    lines = [json.loads(l) for l in open(sys.argv[2]) if l.strip()]
    done = {l["case"] for l in lines if "case" in l}
    assert set(range(total)) - missing <= done
    print(f"cut.h5.partial: {total - len(missing)} of {total} cases finished, {len(missing)} missing")
PY
  mpirun -n 2 "$exe" "${args[@]}" -o cut.h5 --resume > resume.txt 2> resume.err
  grep -q "to run" resume.err || fail "resume did not say what it runs: $(cat resume.err)"
  $py - cut.h5 <<'PY' || fail "the resumed file's sessions are wrong"
import sys, h5py
with h5py.File(sys.argv[1]) as f:
    s = f["/provenance/sessions/cases"][()]
    assert len(s) == 2 and s[0] == len(f["/cases/case"]) and 0 < s[1] < s[0], s
    assert f.attrs["complete"] == 1 and len(f["/missing"]) == 0
PY
  $py "$compare" whole.h5 cut.h5 || fail "the resumed sweep differs from the uninterrupted one"
  [[ ! -e cut.h5.partial && ! -e cut.h5.parts.jsonl ]] || fail "the partial file or journal is left after the resume"
  ;;
props_reproduce)
  # The article's two-ball formula: its failures are expected (unequal masses).
  code=0
  # 101 seeds: sizes 0 to 100, as the suite's 100 cases; about 6 fail.
  mpirun -n 2 "$exe" props --cases 101 --properties article-momentum-kept -o art.h5 > art.txt 2> art.err || code=$?
  (( code == 0 )) || fail "expected failures made props exit $code"
  read -r c rank reproduce < <($py - art.h5 <<'PY'
import sys, h5py
with h5py.File(sys.argv[1]) as f:
    v = f["/cases/verdict"].asstr()[()]
    r = f["/timing/rank"][()]
    fails = [c for c in range(len(v)) if v[c] == "fail" and r[c] == 1] or [c for c in range(len(v)) if v[c] == "fail"]
    assert fails, "no failure found"
    c = fails[0]
    print(c, r[c], f["/cases/reproduce"].asstr()[c])
PY
)
  [[ -f art.h5.counterexamples/article-momentum-kept-strict-case$c.json ]] || fail "no counterexample file for case $c"
  mkdir reg
  COLLIDE2D_REGRESSIONS_DIR=$work/reg RC_PARAMS="$reproduce" "$suite" \
    "scene properties: the article's two-ball formula breaks momentum (expected counterexample)" > suite.txt 2>&1 ||
    fail "the suite failed reproducing: $(tail -5 suite.txt)"
  grep -q "counterexample found as expected" suite.txt || fail "the suite did not reproduce the failure: $(tail -5 suite.txt)"
  shopt -s nullglob
  files=(reg/expected/article-momentum-kept-strict-*.json)
  scenes=()
  for f in "${files[@]}"; do [[ $f == *.meta.json ]] || scenes+=("$f"); done
  (( ${#scenes[@]} == 1 )) || fail "the suite wrote ${#scenes[@]} scene files"
  cmp "${scenes[0]}" "art.h5.counterexamples/article-momentum-kept-strict-case$c.json" ||
    fail "the suite's shrunk scene differs from the sweep's (case $c, found on rank $rank)"
  echo "case $c (rank $rank): the suite reproduced the sweep's shrunk scene byte for byte"
  ;;
*) fail "unknown case" ;;
esac
echo "PASS ($case)"
