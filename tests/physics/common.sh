# Sourced by the check_*.sh tests: runs SCENE with default options (event
# engine, strict mode), replays the run file (must exit 0: bit for bit), and
# writes the analysis (analysis/gas_observables.py --json) to $work/obs.json.
# Leaves the run file at $work/run.h5; $work is removed on exit.
set -euo pipefail
exe=$1
scene=$2
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
analysis="$here/../../analysis/gas_observables.py"
py=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

start=$EPOCHREALTIME
"$exe" run "$scene" -o "$work/run.h5" > "$work/run.txt"
ran=$EPOCHREALTIME
if ! "$exe" replay "$work/run.h5" > "$work/replay.txt" 2>&1; then
  echo "FAIL: collide2d replay did not reproduce the run: $(cat "$work/replay.txt")" >&2
  exit 1
fi
replayed=$EPOCHREALTIME
grep -E '^(events|energy|overlap|time) ' "$work/run.txt" || true
awk -v a="$start" -v b="$ran" -v c="$replayed" 'BEGIN { printf "run %.2f s, replay %.2f s\n", b - a, c - b }'
tail -n 1 "$work/replay.txt"
"$py" "$analysis" "$work/run.h5" --json > "$work/obs.json"
