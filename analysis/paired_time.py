#!/usr/bin/python3
"""Times a command as a whole process, alone or paired against a second one.

    analysis/paired_time.py [-n RUNS] [--warmup N] [--vs 'B COMMAND'] -- A COMMAND ...

Runs each command `--warmup` times uncounted, then RUNS times counted; with
--vs, A and B take turns (A B A B ...), so that a drift of the machine's
speed falls on both alike, and the ratio A/B is formed pair by pair. Each
run's CPU time (user + system) and peak resident memory are the kernel's
own accounting of that child process (wait4; the peak can include the
few MiB this script's own pages take until the exec), its wall time the
clock around it; the commands' output is discarded. Prints, per figure, the
minimum, median and maximum. The README's speed figures are its medians
(a shared machine is noisy: quote medians and paired ratios, not one run).
"""
import argparse
import os
import shlex
import statistics
import subprocess
import sys
import time


def run_once(command):
    start = time.monotonic()
    with open(os.devnull, "wb") as devnull:
        child = subprocess.Popen(command, stdout=devnull, stderr=devnull)
        _, status, usage = os.wait4(child.pid, 0)
    wall = time.monotonic() - start
    code = os.waitstatus_to_exitcode(status)
    return {"cpu s": usage.ru_utime + usage.ru_stime, "wall s": wall, "peak MiB": usage.ru_maxrss / 1024.0}, code


def usage_error(message):
    print(f"paired_time.py: {message} (see --help)", file=sys.stderr)
    sys.exit(2)


def row(name, values):
    return f"{name:<14}{min(values):>12.4g}{statistics.median(values):>12.4g}{max(values):>12.4g}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-n", type=int, default=5, help="counted runs of each command (default 5)")
    parser.add_argument("--warmup", type=int, default=1, help="uncounted runs first (default 1)")
    parser.add_argument("--vs", help="a second command B, one string split as a shell splits words")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- then command A and its arguments")
    parser.error = usage_error  # one line on stderr, exit 2, as every collide2d tool
    args = parser.parse_args()
    a = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not a or args.n < 1 or args.warmup < 0:
        usage_error("give -n >= 1, --warmup >= 0 and a command after --")
    commands = {"A": a}
    if args.vs:
        commands["B"] = shlex.split(args.vs)
        if not commands["B"]:
            usage_error("--vs names no command")
    figures = {name: [] for name in commands}
    failed = {name: 0 for name in commands}
    try:
        for _ in range(args.warmup):
            for command in commands.values():
                run_once(command)
        for _ in range(args.n):
            for name, command in commands.items():
                measured, code = run_once(command)
                figures[name].append(measured)
                failed[name] += code != 0
    except OSError as e:  # a command that cannot be started
        usage_error(f"cannot start {e.filename}: {e.strerror}")
    print(f"{args.n} counted runs each after {args.warmup} warm-up; columns: min, median, max")
    for name in commands:
        for key in ("cpu s", "wall s", "peak MiB"):
            print(row(f"{name} {key}", [m[key] for m in figures[name]]))
    if "B" in commands:
        for key in ("cpu s", "wall s"):
            ratios = [x[key] / y[key] for x, y in zip(figures["A"], figures["B"]) if y[key] > 0]
            print(row(f"A/B {key.split()[0]}", ratios))
    for name, count in failed.items():
        if count:
            print(f"note: {count} of {args.n} runs of {name} exited with a non-zero status", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
