#!/usr/bin/env bash
# Crash safety with a real kill -9: a run writing checkpoints is killed
# mid-way; `collide2d resume` must finish it into a file whose every dataset
# equals an uninterrupted run's, bit for bit (the summary's wall time aside).
# Also: a run killed before its first checkpoint resumes from the start.
set -euo pipefail
exe=$1
scene=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

until=6000  # about 6 s of running here: the first progress line (after 2 s) lands mid-run
"$exe" run "$scene" -o "$work/ref.h5" --until $until --checkpoint-every 5 > /dev/null 2>&1

# Killed at its first progress line (printed after 2 s of running), so the
# kill lands mid-run however fast the machine is.
"$exe" run "$scene" -o "$work/killed.h5" --until $until --checkpoint-every 5 > /dev/null 2> "$work/progress" &
pid=$!
while kill -0 "$pid" 2>/dev/null && ! grep -q "^run " "$work/progress"; do sleep 0.05; done
kill -9 "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
if [[ -e "$work/killed.h5" || ! -e "$work/killed.h5.partial" ]]; then
  echo "the kill did not land mid-run" >&2
  exit 1
fi
"$exe" resume "$work/killed.h5" > /dev/null
[[ -e "$work/killed.h5" && ! -e "$work/killed.h5.partial" ]] || { echo "resume left no finished file" >&2; exit 1; }
"$exe" replay "$work/killed.h5" > /dev/null

/usr/bin/python3 - "$work/ref.h5" "$work/killed.h5" <<'PY'
import sys
import h5py
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
names = []
a.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
differ = [n for n in names if not n.endswith("summary") and a[n][()].tobytes() != b[n][()].tobytes()]
if differ:
    sys.exit("resumed run differs from the uninterrupted one in: " + ", ".join(differ))
print(f"{len(names)} datasets identical")
PY

# Killed before the first checkpoint: resume starts again and finishes.
"$exe" run "$scene" -o "$work/early.h5" --until $until --checkpoint-every 1990 > /dev/null 2>&1 &
pid=$!
sleep 1
kill -9 "$pid"
wait "$pid" 2>/dev/null || true
if [[ -e "$work/early.h5.partial" ]]; then
  "$exe" resume "$work/early.h5" > /dev/null 2>&1
  [[ -e "$work/early.h5" ]] || { echo "a run killed before its first checkpoint did not resume" >&2; exit 1; }
fi
echo "kill -9 and resume: ok"
