"""What every analysis script shares: one-line errors with exit 2, HDF5 strings
as text, and JSON without NaN or infinity. Imported by the scripts beside it
(run as /usr/bin/python3 analysis/NAME.py, this folder is on sys.path)."""
import argparse
import math
import sys


class InputError(Exception):
    """Bad input: reported as one line on stderr, exit 2."""


class OneLineParser(argparse.ArgumentParser):
    """Usage errors as one line on stderr, exit 2."""

    def error(self, message):
        sys.stderr.write(f"{self.prog}: {message} (see --help)\n")
        sys.exit(2)


def text_of(x):
    """An HDF5 string (a dataset, bytes or str, scalar or 1-element array) as str."""
    import h5py  # here, not above: a script may report a missing h5py itself
    import numpy as np

    if isinstance(x, h5py.Dataset):
        x = x[()]
    if isinstance(x, np.ndarray) and x.size == 1:
        x = x.item()
    return (x.decode("utf-8", "replace") if isinstance(x, bytes) else str(x)).rstrip("\0")


def finite_or_null(x):
    """x with every NaN or infinity replaced by None (strict JSON has neither)."""
    if isinstance(x, dict):
        return {k: finite_or_null(v) for k, v in x.items()}
    if isinstance(x, list):
        return [finite_or_null(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x
