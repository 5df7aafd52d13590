#!/usr/bin/python3
"""The summary's `restitution` line and its warning (issue 11: the share of
collisions the rest rules touched is reported, and over 1 % warned about).

For a gas (no rest rule can act: 0 % and no warning) and a settling scene
(Abound: over 1 %, so the warning), checks that the printed counts add up to
the `events` line's collisions, that the percentage is the printed counts'
own, that the warning appears exactly when it is over 1 %, and that the
stored summary (/observables/summary) holds the same count.

Usage: restitution_line.py COLLIDE2D SCENES_DIR
"""
import json
import pathlib
import re
import subprocess
import sys
import tempfile

import h5py


def check(exe: str, scene: pathlib.Path, until: str, work: str, expect_warning: bool) -> list[str]:
    out = pathlib.Path(work) / (scene.stem + ".h5")
    run = subprocess.run([exe, "run", str(scene), "-o", str(out), "--until", until], capture_output=True, text=True)
    if run.returncode != 0:
        return [f"{scene.name}: collide2d run exited {run.returncode}: {run.stderr.strip()}"]
    text = run.stdout
    problems = []
    events = re.search(r"^events +\d+ \(ball-ball (\d+), ball-wall (\d+)\)$", text, re.M)
    line = re.search(r"^restitution applied in (\d+) of (\d+) collisions; the rest rules made (\d+) plastic \(([0-9.e+-]+) %\)$",
                     text, re.M)
    if not events or not line:
        return [f"{scene.name}: no events or restitution line in:\n{text}"]
    applied, collisions, plastic, percent = int(line[1]), int(line[2]), int(line[3]), float(line[4])
    if collisions != int(events[1]) + int(events[2]):
        problems.append(f"{scene.name}: {collisions} collisions, the events line says {int(events[1]) + int(events[2])}")
    if applied + plastic != collisions:
        problems.append(f"{scene.name}: {applied} + {plastic} is not {collisions}")
    if collisions and f"{100.0 * plastic / collisions:.3g}" != line[4]:
        problems.append(f"{scene.name}: {line[4]} % is not {plastic} of {collisions}")
    warned = re.search(r"^warning +over 1 % of the collisions were made plastic", text, re.M) is not None
    if warned != (percent > 1.0) or warned != expect_warning:
        problems.append(f"{scene.name}: {percent} % made plastic, warning printed: {warned}, expected: {expect_warning}")
    with h5py.File(out, "r") as f:
        stored = json.loads(f["observables/summary"][()])
    if stored["made_plastic_by_rest_rules"] != plastic:
        problems.append(f"{scene.name}: the stored summary says {stored['made_plastic_by_rest_rules']} made plastic, "
                        f"the printed one {plastic}")
    return problems


def main(exe: str, scenes: str) -> int:
    exe = str(pathlib.Path(exe).resolve())
    folder = pathlib.Path(scenes)
    problems = []
    with tempfile.TemporaryDirectory() as work:
        problems += check(exe, folder / "gas.json", "5", work, expect_warning=False)
        problems += check(exe, folder / "abound.json", "20", work, expect_warning=True)
    for p in problems:
        print("FAIL:", p)
    if not problems:
        print("restitution line: the gas 0 % without a warning, Abound over 1 % with one; counts add up")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
