#!/usr/bin/python3
"""The README's example run summary is a real one: run the built-in scene as
the README's first command does and compare every line of the summary block
with the README's, except the wall-time and peak-memory lines (`time ...`,
`memory ...`), which no two runs share. Exits 1 naming the first stale line.

Usage: readme_summary.py COLLIDE2D README.md
"""
import pathlib
import re
import subprocess
import sys
import tempfile


def summary_block(readme: str) -> list[str]:
    m = re.search(r"```\n(run abound .*?)```", readme, re.S)
    if not m:
        sys.exit("FAIL: no summary block starting 'run abound' in the README")
    return m.group(1).rstrip("\n").split("\n")


def main(exe: str, readme_path: str) -> int:
    exe = str(pathlib.Path(exe).resolve())
    documented = summary_block(pathlib.Path(readme_path).read_text())
    with tempfile.TemporaryDirectory() as work:
        run = subprocess.run([exe, "run", "-o", "abound.h5"], cwd=work, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"FAIL: collide2d run exited {run.returncode}: {run.stderr.strip()}")
    printed = [line for line in run.stdout.rstrip("\n").split("\n")]
    start = next((k for k, line in enumerate(printed) if line.startswith("run abound")), None)
    if start is None:
        sys.exit("FAIL: the run printed no summary")
    printed = printed[start:]
    if len(printed) != len(documented):
        sys.exit(f"FAIL: the README shows {len(documented)} summary lines, the run prints {len(printed)}")
    stale = 0
    for want, got in zip(documented, printed):
        if (want.startswith("time ") and got.startswith("time ")) or (want.startswith("memory ") and got.startswith("memory ")):
            continue  # wall time and peak memory differ from run to run
        # The README names the output file as the first command does.
        if want.startswith("run abound"):
            want, got = re.sub(r"-> \S+$", "", want), re.sub(r"-> \S+$", "", got)
        if want != got:
            print(f"stale README line:\n  README: {want}\n  run:    {got}")
            stale += 1
    if stale:
        return 1
    print(f"README summary block matches a real run ({len(documented)} lines, the wall time aside)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
