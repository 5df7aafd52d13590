"""The physics checks' verdict: each check prints ok or FAIL with what it
claims; the test fails (exit 1) if any check failed."""
import sys

failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def finish():
    sys.exit(1 if failures else 0)
