#!/usr/bin/python3
"""Gas observables of a collide2d run file (SPEC.md "Run file (HDF5)").

  gas_observables.py RUN.h5 [--json] [--window F]

Measured over a window, the last (1 - F) of the run (default F = 0.5: the
second half, skipping equilibration):

  pressure    P = sum of the impulses of the ball-wall events (kind 1: mass x
              change of normal speed, the momentum given to the wall) divided
              by (window length x total wall length); per wall too.
  kT          mean kinetic energy per moving ball, averaged over the window's
              frames (2D: <1/2 m v^2> = kT).
  Z           reduced pressure P A / (N kT), for two areas: A the box of the
              walls' ends (L^2) and A_acc the area open to centres,
              (W - 2r)(H - 2r); eta = N pi r^2 / A for each, and Henderson's
              (1975) hard-disk equation of state Z_H = (1 + eta^2/8) / (1 - eta)^2;
              for equal disks also Z expected in this finite box (A = box):
              Henderson in the bulk plus the walls' O(r/L) adsorption and
              tension from scaled particle theory (finite_size_prediction).
  species     per distinct mass: number, mean KE over the window with a
              block-average standard error, and the ratio of the heaviest
              species' mean KE to the lightest's.
  virial      the virial identity over the window (no gravity): the change of
              sum x.p equals 2 int K dt plus every collision's impulse times
              its lever arm; its residual (relative) is rounding unless an
              impulse is missing or wrong (see analyse()).
  energy      largest relative change of /observables/energy over all frames.
  escape      the largest distance any centre gets outside [x_min + r, x_max - r]
              x [y_min + r, y_max - r] of the walls' bounding box, over all
              frames, relative to the box size (negative: the closest approach).

Standard errors are block averages: the window is cut into 20 blocks of equal
length, the quantity is measured in each, and the error is the sample standard
deviation of the 20 block values divided by sqrt(20) (block_error).
--json prints one JSON object (for the tests); otherwise a readable summary.
Exit codes: 0 success, 2 bad input (one line on stderr).
"""
import argparse
import json
import math
import os
import sys

import h5py
import numpy as np
from cli_support import InputError, finite_or_null, text_of  # noqa: E402

PROG = "gas_observables.py"
BLOCKS = 20


def henderson(eta):
    """Henderson (1975) equation of state of hard disks, Z = PA / (N kT)."""
    return (1 + eta * eta / 8) / (1 - eta) ** 2


def finite_size_prediction(n_balls, r, width, height, kt):
    """Wall pressure expected in a finite box of hard walls, from Henderson's
    bulk equation of state and the wall's surface terms in scaled particle
    theory (SPT, Helfand, Frisch & Lebowitz 1961), for equal disks of radius r.

    Two O(r/L) effects make the wall pressure P_w of a finite box differ from
    the bulk pressure at the mean density N/A:
      - adsorption: the density near a hard wall is not the bulk density; with
        the dividing line at the centres' exclusion line (distance r from the
        wall) SPT's wall tension is gamma_acc = -kT eta^2 / (pi r (1 - eta)^2)
        and Gibbs' equation (Gamma = -d gamma / d mu, d mu = dP / n at fixed T)
        gives Gamma_acc = 2 n r eta / (1 + eta) disks per unit length more than
        the bulk density would put there, so
            N = n_b (W - 2r)(H - 2r) + Gamma_acc(n_b) 2 (W + H - 4r);
      - tension: the force on a wall is the momentum flux through a line
        across the box, P_b per unit length in the bulk but less within the
        layers along the two perpendicular walls, by gamma_phys = gamma_acc +
        P_b r each (the tension with the dividing line at the wall itself; no
        centre, so no stress, lies within r of it). Over all four walls:
            P_w = P_b - 4 gamma_phys / (W + H).
    For an ideal gas (gamma_acc = Gamma_acc = 0) this is exact: P_w = n kT
    (W + H - 4r) / (W + H) with n = N / ((W - 2r)(H - 2r)); in a square,
    P_w L (L - 2r) = N kT. Corners (O(r^2/L^2)) are neglected. SPT gives the
    surface terms, Henderson the bulk pressure (SPT's own, 1 / (1 - eta)^2, is
    1.5 % lower at eta = 0.35: a 0.03 % change of a 2 % correction).
    Returns (P_w, eta_bulk), with P_b = n_b kT Z_H(eta_b)."""
    area_disk = math.pi * r * r
    a_acc = (width - 2 * r) * (height - 2 * r)
    perimeter_acc = 2 * (width + height - 4 * r)
    lo, hi = 0.0, min(n_balls / a_acc, 0.9 / area_disk)
    for _ in range(200):  # N(n_b) increases with n_b: bisection
        n_b = 0.5 * (lo + hi)
        eta = n_b * area_disk
        if n_b * a_acc + 2 * n_b * r * eta / (1 + eta) * perimeter_acc < n_balls:
            lo = n_b
        else:
            hi = n_b
    n_b = 0.5 * (lo + hi)
    eta_b = n_b * area_disk
    p_b = n_b * kt * henderson(eta_b)
    gamma_phys = -kt * eta_b ** 2 / (math.pi * r * (1 - eta_b) ** 2) + p_b * r
    return p_b - 4 * gamma_phys / (width + height), eta_b


def block_error(values):
    """Standard error of the mean of `values` (one per block, equal weights)."""
    values = np.asarray(values, dtype=float)
    if len(values) < 2:
        return float("nan")
    return float(np.std(values, ddof=1) / math.sqrt(len(values)))


def load(path):
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise InputError(f"{path}: not an HDF5 file (or not readable)")
    with f:
        need = ["particles/balls/position/time", "particles/balls/position/value",
                "particles/balls/velocity/value", "observables/energy/value",
                "events/time", "events/kind", "events/a", "events/b", "events/impulse",
                "parameters/mass", "parameters/radius", "parameters/walls", "parameters/scene_json"]
        for name in need:
            if name not in f or not isinstance(f[name], h5py.Dataset):
                raise InputError(f"{path}: missing dataset /{name}")
        run = {
            "t": f[need[0]][:], "pos": f[need[1]][:], "vel": f[need[2]][:], "energy": f[need[3]][:],
            "ev_t": f[need[4]][:], "ev_kind": f[need[5]][:], "ev_a": f[need[6]][:], "ev_b": f[need[7]][:],
            "ev_j": f[need[8]][:], "mass": f[need[9]][:], "radius": f[need[10]][:],
            "walls": f[need[11]][:].reshape(-1, 4),
        }
        try:
            run["scene"] = json.loads(text_of(f[need[12]]))
        except ValueError as e:
            raise InputError(f"{path}: /parameters/scene_json is not JSON: {e}")
        summary = f["observables/summary"] if "observables/summary" in f else None
        run["summary"] = json.loads(text_of(summary)) if summary is not None else {}
    if len(run["t"]) < 2:
        raise InputError(f"{path}: fewer than two frames")
    if run["vel"].shape != run["pos"].shape or run["pos"].shape[1] != len(run["mass"]):
        raise InputError(f"{path}: position, velocity and mass disagree in shape")
    return run


def analyse(run, window):
    t, vel, pos = run["t"], run["vel"], run["pos"]
    mass, radius, walls = run["mass"], run["radius"], run["walls"]
    balls = run["scene"].get("balls", [])
    moving = np.array([not b.get("fixed", False) for b in balls] if len(balls) == len(mass) else [True] * len(mass))
    n = int(moving.sum())
    t_end = float(t[-1])
    t0 = float(t[0]) + window * (t_end - float(t[0]))
    frames = t >= t0
    out = {"name": run["scene"].get("name", ""), "balls": n, "walls": int(len(walls)), "frames": int(len(t)),
           "duration": t_end, "window": [t0, t_end], "window_frames": int(frames.sum()),
           "events": int(len(run["ev_t"])), "ball_ball_events": int(np.sum(run["ev_kind"] == 0)),
           "ball_wall_events": int(np.sum(run["ev_kind"] == 1))}

    # Kinetic energy per frame and ball.
    ke = 0.5 * mass[None, :] * np.sum(vel * vel, axis=2)  # frames x N
    ke_total = ke[:, moving].sum(axis=1)
    kt_frames = ke_total[frames] / n
    kt = float(kt_frames.mean())
    out["kT"] = kt
    out["kT_first_frame"] = float(ke_total[0] / n)

    # Block index of each window frame (equal time blocks).
    span = t_end - t0
    def block_of(times):
        return np.minimum(((times - t0) / span * BLOCKS).astype(int), BLOCKS - 1)
    frame_blocks = block_of(t[frames])

    # Wall pressure over the window.
    lengths = np.hypot(walls[:, 2] - walls[:, 0], walls[:, 3] - walls[:, 1])
    total_length = float(lengths.sum())
    hits = (run["ev_kind"] == 1) & (run["ev_t"] > t0) & (run["ev_t"] <= t_end)
    impulses = run["ev_j"][hits]
    pressure = float(impulses.sum() / (span * total_length)) if total_length > 0 else float("nan")
    per_wall = [float(run["ev_j"][hits & (run["ev_b"] == w)].sum() / (span * lengths[w])) for w in range(len(walls))]
    hit_blocks = block_of(run["ev_t"][hits])
    block_p = [impulses[hit_blocks == k].sum() / (span / BLOCKS * total_length) for k in range(BLOCKS)]
    out["wall_hits"] = int(hits.sum())
    out["pressure"] = pressure
    out["pressure_per_wall"] = per_wall
    # Independent hits: relative error sqrt(sum J^2) / sum J; blocks: correlations included.
    out["pressure_rel_error_poisson"] = float(math.sqrt(np.sum(impulses ** 2)) / impulses.sum()) if len(impulses) else None
    out["pressure_rel_error_blocks"] = block_error(block_p) / pressure if pressure > 0 else None

    # Box and areas.
    xs = np.concatenate([walls[:, 0], walls[:, 2]]) if len(walls) else np.zeros(1)
    ys = np.concatenate([walls[:, 1], walls[:, 3]]) if len(walls) else np.zeros(1)
    width, height = float(xs.max() - xs.min()), float(ys.max() - ys.min())
    area = width * height
    r_moving = radius[moving]
    equal_radii = bool(np.all(r_moving == r_moving[0]))
    r_acc = float(r_moving[0]) if equal_radii else float(r_moving.mean())
    area_acc = (width - 2 * r_acc) * (height - 2 * r_acc)
    disk_area = float(np.sum(math.pi * r_moving ** 2))
    out["box"] = {"width": width, "height": height, "area": area, "area_accessible": area_acc,
                  "radius_for_accessible": r_acc, "equal_radii": equal_radii}
    if area > 0 and kt > 0:
        eta, eta_acc = disk_area / area, disk_area / area_acc
        z, z_acc = pressure * area / (n * kt), pressure * area_acc / (n * kt)
        out["eos"] = {"eta": eta, "Z": z, "Z_henderson": henderson(eta), "Z_over_henderson": z / henderson(eta),
                      "eta_accessible": eta_acc, "Z_accessible": z_acc, "Z_henderson_accessible": henderson(eta_acc),
                      "Z_accessible_over_henderson": z_acc / henderson(eta_acc)}
        if equal_radii:
            p_pred, eta_b = finite_size_prediction(n, r_acc, width, height, kt)
            z_pred = p_pred * area / (n * kt)
            out["eos"].update({"eta_bulk_predicted": eta_b, "Z_predicted_finite_box": z_pred,
                               "Z_over_predicted": z / z_pred,
                               "Z_predicted_over_henderson": z_pred / henderson(eta)})

    # Per species (distinct masses of moving balls).
    species = []
    for m in sorted(set(float(x) for x in mass[moving])):
        sel = moving & (mass == m)
        per_frame = ke[frames][:, sel].mean(axis=1)
        blocks = [per_frame[frame_blocks == k].mean() for k in range(BLOCKS) if np.any(frame_blocks == k)]
        species.append({"mass": m, "count": int(sel.sum()), "mean_ke": float(per_frame.mean()),
                        "mean_ke_error": block_error(blocks),
                        "mean_ke_first_frame": float(ke[0, sel].mean())})
    out["species"] = species
    if len(species) >= 2:
        light, heavy = species[0], species[-1]
        ratio = heavy["mean_ke"] / light["mean_ke"]
        # Blocks of the ratio itself (the two means are anti-correlated at
        # fixed total energy, so the ratio's error is not the sum in quadrature).
        sel_l, sel_h = moving & (mass == light["mass"]), moving & (mass == heavy["mass"])
        ratio_blocks = []
        for k in range(BLOCKS):
            b = frame_blocks == k
            if np.any(b):
                ratio_blocks.append(ke[frames][b][:, sel_h].mean() / ke[frames][b][:, sel_l].mean())
        out["ke_ratio_heavy_light"] = float(ratio)
        out["ke_ratio_error"] = block_error(ratio_blocks)

    # The virial identity over the window (no acceleration): d/dt sum x.p =
    # 2K + sum x.F, so, integrated over the window with every collision an
    # instantaneous impulse,
    #   [sum (x - c).p] from t0 to t_end = 2 int K dt + sum_bb J (r_a + r_b)
    #                                     + sum_wall J n_in.(c_contact - c),
    # where J is the recorded impulse, c the box centre, n_in the wall's normal
    # towards the box centre and, for a face hit, n_in.(c_contact - c) =
    # n_in.(a - c) + r (the centre is r from the wall line). Exact up to
    # rounding when K is constant between frames (elastic collisions; int K dt
    # is taken as the window's mean K times its length): every impulse and
    # every contact distance enters, so a missed, doubled or wrong impulse
    # shows. Reported as the residual relative to 2 int K dt. Needs every ball
    # moving (a fixed ball's reaction is not recorded) and no acceleration.
    scene = run["scene"]
    accelerated = any(x != 0 for x in scene.get("gravity", [0, 0])) or any("acceleration" in b for b in balls)
    if not accelerated and len(walls) and moving.all():
        centre = np.array([0.5 * (xs.min() + xs.max()), 0.5 * (ys.min() + ys.max())])
        first, last = np.argmax(frames), len(t) - 1
        def xp(k):
            return float(np.sum(mass[moving] * np.sum((pos[k, moving] - centre) * vel[k, moving], axis=1)))
        boundary = xp(last) - xp(first)
        window_events = (run["ev_t"] > t[first]) & (run["ev_t"] <= t_end)
        bb = window_events & (run["ev_kind"] == 0)
        bb_virial = float(np.sum(run["ev_j"][bb] * (radius[run["ev_a"][bb]] + radius[run["ev_b"][bb]])))
        d = walls[:, 2:4] - walls[:, 0:2]
        normal = np.stack([-d[:, 1], d[:, 0]], axis=1) / lengths[:, None]
        side = np.sign(np.sum(normal * (centre - walls[:, 0:2]), axis=1))
        n_in = normal * side[:, None]
        offset = np.sum(n_in * (walls[:, 0:2] - centre), axis=1)  # n_in.(a - c), negative inside
        ww = window_events & (run["ev_kind"] == 1)
        wall_virial = float(np.sum(run["ev_j"][ww] * (offset[run["ev_b"][ww]] + radius[run["ev_a"][ww]])))
        kinetic = 2 * float(ke_total[frames].mean()) * (t_end - float(t[first]))
        out["virial"] = {"kinetic": kinetic, "ball_ball": bb_virial, "wall": wall_virial, "boundary": boundary,
                         "residual_rel": (boundary - kinetic - bb_virial - wall_virial) / kinetic}

    # Energy conservation over the whole run.
    e = run["energy"]
    scale = abs(e[0]) if e[0] != 0 else 1.0
    out["energy_first"] = float(e[0])
    out["energy_last"] = float(e[-1])
    out["energy_max_rel_change"] = float(np.max(np.abs(e - e[0])) / scale)
    out["ke_max_rel_change"] = float(np.max(np.abs(ke_total - ke_total[0])) / ke_total[0]) if ke_total[0] > 0 else None

    # Escape from the walls' bounding box (meaningful for a box of walls).
    size = max(width, height, 1e-300)
    r = radius[None, :]
    outside = np.maximum.reduce([xs.min() + r - pos[:, :, 0], pos[:, :, 0] - (xs.max() - r),
                                 ys.min() + r - pos[:, :, 1], pos[:, :, 1] - (ys.max() - r)])
    out["escape_max_rel"] = float(outside[:, moving].max() / size)
    worst = np.unravel_index(np.argmax(np.where(moving[None, :], outside, -np.inf)), outside.shape)
    out["escape_worst"] = {"frame": int(worst[0]), "ball": int(worst[1])}

    out["deepest_overlap"] = run["summary"].get("deepest_overlap")
    out["wall_seconds"] = run["summary"].get("wall_seconds")
    return out


def report(o):
    lines = [f"scene {o['name']}: {o['balls']} balls, {o['walls']} walls, {o['frames']} frames to t = {o['duration']:.6g}",
             f"events {o['events']} (ball-ball {o['ball_ball_events']}, ball-wall {o['ball_wall_events']});"
             f" window t in [{o['window'][0]:.6g}, {o['window'][1]:.6g}], {o['window_frames']} frames",
             f"kT           {o['kT']:.6g} (first frame {o['kT_first_frame']:.6g})",
             f"pressure     {o['pressure']:.6g} from {o['wall_hits']} wall hits; rel. error "
             f"{o['pressure_rel_error_poisson'] or float('nan'):.3g} (independent hits), "
             f"{o['pressure_rel_error_blocks'] or float('nan'):.3g} (blocks)",
             "  per wall   " + ", ".join(f"{p:.5g}" for p in o["pressure_per_wall"])]
    if "eos" in o:
        e = o["eos"]
        lines.append(f"Z (A = box)        {e['Z']:.5f}  eta {e['eta']:.5f}  Henderson {e['Z_henderson']:.5f}"
                     f"  ratio {e['Z_over_henderson']:.5f}")
        lines.append(f"Z (A = (L-2r)^2)   {e['Z_accessible']:.5f}  eta {e['eta_accessible']:.5f}"
                     f"  Henderson {e['Z_henderson_accessible']:.5f}  ratio {e['Z_accessible_over_henderson']:.5f}")
        if "Z_predicted_finite_box" in e:
            lines.append(f"Z predicted for this finite box (Henderson + SPT wall terms) {e['Z_predicted_finite_box']:.5f}"
                         f" (bulk eta {e['eta_bulk_predicted']:.5f}); measured / predicted {e['Z_over_predicted']:.5f}")
    for s in o["species"]:
        lines.append(f"species m = {s['mass']:g}: {s['count']} balls, mean KE {s['mean_ke']:.6g} +- "
                     f"{s['mean_ke_error']:.2g} (first frame {s['mean_ke_first_frame']:.6g})")
    if "ke_ratio_heavy_light" in o:
        lines.append(f"KE ratio heavy/light {o['ke_ratio_heavy_light']:.5f} +- {o['ke_ratio_error']:.2g}")
    if "virial" in o:
        v = o["virial"]
        lines.append(f"virial       2 int K dt {v['kinetic']:.10g}, ball-ball {v['ball_ball']:.10g}, "
                     f"wall {v['wall']:.10g}, boundary {v['boundary']:.6g}: residual {v['residual_rel']:.3g}")
    lines.append(f"energy       {o['energy_first']:.17g} -> {o['energy_last']:.17g}, "
                 f"max rel. change {o['energy_max_rel_change']:.3g}")
    lines.append(f"escape       {o['escape_max_rel']:.3g} of the box (frame {o['escape_worst']['frame']}, "
                 f"ball {o['escape_worst']['ball']}; negative: inside)")
    lines.append(f"overlap      deepest {o['deepest_overlap']}; run took {o['wall_seconds']} s")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="run file (HDF5) written by collide2d run")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--window", type=float, default=0.5,
                        help="fraction of the run skipped before measuring (default 0.5)")
    args = parser.parse_args()
    try:
        if not 0 <= args.window < 1:
            raise InputError(f"--window {args.window}: must lie in [0, 1)")
        o = analyse(load(args.run), args.window)
    except InputError as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 2
    print(json.dumps(finite_or_null(o)) if args.json else report(o))
    return 0


if __name__ == "__main__":
    sys.exit(main())
