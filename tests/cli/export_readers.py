#!/usr/bin/python3
"""collide2d export, read back by the tools it is for.

A short run of the built-in scene is exported as h5md3d and extxyz; MDAnalysis
opens the first, ASE the second, and both must give the run's frames, frame
for frame: same count, same times and steps, x and y exactly as in the run
file (MDAnalysis keeps coordinates in float32, so there they equal the float32
of the run's doubles; the h5md3d file itself, read with h5py, holds the
doubles), z = 0. Then the errors: exit 2 with one line naming the file, and
nothing left under the output name. A missing MDAnalysis or ASE is a failure,
not a skip: CI installs both (.ci/install-deps).

Usage: export_readers.py COLLIDE2D
"""
import pathlib
import subprocess
import sys
import tempfile
import warnings

import h5py
import numpy as np

with warnings.catch_warnings():  # MDAnalysis's deprecation notices on import
    warnings.simplefilter("ignore")
    import ase.io
    import MDAnalysis as mda

EXE = sys.argv[1]


def collide2d(*args):
    return subprocess.run([EXE, *map(str, args)], capture_output=True, text=True)


def check(condition, message):
    if not condition:
        sys.exit("FAIL: " + message)


def equal(a, b):
    """Bit for bit (so -0 and 0 differ, as they would in a replay)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def read_run(path):
    with h5py.File(path, "r") as f:
        g = f["particles/balls"]
        return {"position": g["position/value"][...], "velocity": g["velocity/value"][...],
                "time": g["position/time"][...], "step": g["position/step"][...],
                "mass": f["parameters/mass"][...], "radius": f["parameters/radius"][...]}


def check_h5md3d_file(path, run):
    """The exported file itself, as any H5MD reader sees it."""
    with h5py.File(path, "r") as f:
        check(list(f["h5md"].attrs["version"]) == [1, 1], "h5md3d: /h5md version is not [1, 1]")
        check(f["h5md/creator"].attrs["name"] == b"collide2d", "h5md3d: creator name")
        box = f["particles/balls/box"]
        check(box.attrs["dimension"] == 3, "h5md3d: box dimension is not 3")
        check([b.decode() for b in box.attrs["boundary"]] == ["none"] * 3, "h5md3d: boundary is not none x3")
        for element in ("position", "velocity"):
            value = f[f"particles/balls/{element}/value"][...]
            check(equal(value[:, :, :2], run[element]), f"h5md3d: {element} x, y differ from the run's")
            check(not value[:, :, 2].any(), f"h5md3d: {element} z is not 0")
            check(equal(f[f"particles/balls/{element}/time"][...], run["time"]), f"h5md3d: {element} time")
            check(equal(f[f"particles/balls/{element}/step"][...], run["step"]), f"h5md3d: {element} step")
        check(equal(f["particles/balls/mass"][...], run["mass"]), "h5md3d: mass")
        check(equal(f["particles/balls/radius"][...], run["radius"]), "h5md3d: radius")


def check_mdanalysis(path, run):
    n = run["position"].shape[1]
    # MDAnalysis 2.4 needs the atom count for an H5MD file without a topology
    # file, and convert_units=False because the file states no units.
    u = mda.Universe(path, format="H5MD", topology_format="MINIMAL", n_atoms=n, convert_units=False)
    check(len(u.atoms) == n, f"MDAnalysis: {len(u.atoms)} atoms, the run has {n}")
    check(u.trajectory.n_frames == len(run["time"]),
          f"MDAnalysis: {u.trajectory.n_frames} frames, the run has {len(run['time'])}")
    for i, ts in enumerate(u.trajectory):
        check(ts.time == run["time"][i] and ts.data["step"] == run["step"][i], f"MDAnalysis: frame {i} time or step")
        for name, got in (("position", ts.positions), ("velocity", ts.velocities)):
            check(equal(got[:, :2], run[name][i].astype(np.float32)), f"MDAnalysis: frame {i} {name} x, y differ")
            check(not got[:, 2].any(), f"MDAnalysis: frame {i} {name} z is not 0")
        check(ts.dimensions is None, "MDAnalysis: a box with dimensions (it would be taken as periodic)")


def check_ase(path, run):
    frames = ase.io.read(path, index=":")
    check(len(frames) == len(run["time"]), f"ASE: {len(frames)} frames, the run has {len(run['time'])}")
    for i, atoms in enumerate(frames):
        check(atoms.info["Time"] == run["time"][i] and atoms.info["Step"] == run["step"][i], f"ASE: frame {i} time/step")
        check(equal(atoms.positions[:, :2], run["position"][i]), f"ASE: frame {i} positions differ from the run's")
        check(equal(atoms.arrays["velo"][:, :2], run["velocity"][i]), f"ASE: frame {i} velocities differ")
        check(not atoms.positions[:, 2].any() and not atoms.arrays["velo"][:, 2].any(), f"ASE: frame {i} z is not 0")
        check(equal(atoms.get_masses(), run["mass"]), f"ASE: frame {i} masses")
        check(equal(atoms.arrays["radius"], run["radius"]), f"ASE: frame {i} radii")
        check(not atoms.pbc.any(), f"ASE: frame {i} is periodic")


def check_refused(args, names, leaves_nothing_at, why):
    """Exit 2, one line on stderr naming the file, no output file left."""
    r = collide2d("export", *args)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2, f"{why}: exit {r.returncode}, not 2 ({r.stderr.strip()})")
    check(len(lines) == 1 and str(names) in lines[0], f"{why}: stderr is not one line naming {names}: {r.stderr!r}")
    for p in (leaves_nothing_at, pathlib.Path(str(leaves_nothing_at) + ".partial")):
        check(not p.exists(), f"{why}: {p} was left behind")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        run_file = tmp / "r.h5"
        r = collide2d("run", "-o", run_file, "--until", 2)
        check(r.returncode == 0, "the run failed: " + r.stderr)
        run = read_run(run_file)

        h5md, xyz = tmp / "x.h5md", tmp / "x.xyz"
        for fmt, out in (("h5md3d", h5md), ("extxyz", xyz)):
            r = collide2d("export", run_file, "--format", fmt, "-o", out)
            check(r.returncode == 0 and out.exists(), f"export {fmt} failed: {r.stderr}")
            check(not pathlib.Path(str(out) + ".partial").exists(), f"export {fmt} left its .partial file")
        check_h5md3d_file(h5md, run)
        check_mdanalysis(h5md, run)
        check_ase(xyz, run)

        # A run file from before mass, radius and wall restitution were stored
        # (and before the event columns were described) still exports and replays.
        old = tmp / "old.h5"
        old.write_bytes(run_file.read_bytes())
        with h5py.File(old, "r+") as f:
            for name in ("particles/balls/mass", "particles/balls/radius", "parameters/wall_restitution"):
                del f[name]
            del f["events/kind"].attrs["labels"]
        check(collide2d("replay", old).returncode == 0, "replay of a run file without the newer datasets failed")
        r = collide2d("export", old, "--format", "extxyz", "-o", tmp / "old.xyz")
        check(r.returncode == 0, "export of a run file without the newer datasets failed: " + r.stderr)
        check_ase(tmp / "old.xyz", run)

        garbage = tmp / "garbage.h5"
        garbage.write_bytes(b"not HDF5 at all" * 100)
        check_refused([garbage, "--format", "extxyz", "-o", tmp / "g.xyz"], garbage, tmp / "g.xyz", "unreadable run file")
        check_refused([tmp / "missing.h5", "--format", "h5md3d", "-o", tmp / "m.h5md"], tmp / "missing.h5",
                      tmp / "m.h5md", "missing run file")
        check_refused([run_file, "--format", "pdb", "-o", tmp / "p.pdb"], run_file, tmp / "p.pdb", "unknown format")
        check_refused([run_file, "--format", "extxyz", "-o", tmp / "no" / "such" / "dir.xyz"], tmp / "no" / "such",
                      tmp / "no" / "such" / "dir.xyz", "unwritable output")
        before = run_file.read_bytes()
        r = collide2d("export", run_file, "--format", "h5md3d", "-o", tmp / "." / "r.h5")
        check(r.returncode == 2 and run_file.read_bytes() == before, "export onto its own run file was not refused")
        check("--format" in collide2d("export", "--help").stdout, "export --help says nothing of --format")
    print("export: MDAnalysis and ASE read every frame of the run exactly; errors refused")


if __name__ == "__main__":
    main()
