#!/usr/bin/python3
"""Writes the acceptance scenes with known physics answers (fixed seeds, the
same bytes on every run) into this folder, beside abound.json and gas.json:

  fast_box.json        20 balls at speed 1e5 in a unit box of four zero-thickness
                       walls, ~1e6 events: none may escape, energy is kept.
  two_mass_gas.json    150 light (m = 1) and 150 heavy (m = 4) disks; the heavy
                       ones start at rest: equipartition, <KE> equal per species.
  dense_gas_2000.json  2000 equal hard disks, packing fraction 0.35, kT = 1:
                       wall pressure against the hard-disk equation of state.
  dense_gas_400.json   the same at N = 400, run twice as long (smaller box:
                       larger finite-size effects, the sharper check of the
                       finite-box prediction in gas_observables.py).
  newtons_cradle.json  five equal balls in a row, gaps of 1e-9, one striking.
  resting_pile.json    six balls, restitution 0.5, dropped at random abscissae
                       into a narrow bin under gravity: they come to rest on
                       the floor and on each other.
  funnel.json          balls falling through a V funnel of two walls into a box.

The analysis is analysis/gas_observables.py; the tests are tests/physics/.
Every scene is checked here for overlaps (ball-ball and ball-wall, with a
margin) before it is written; numbers are rounded to a few significant digits
first and the check is made on the rounded values, which are what the file
holds.

Regenerate: /usr/bin/python3 datasets/scenes/make_scenes.py
"""
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))


def num(x, digits=10):
    """Compact text of x rounded to `digits` significant digits (what the file holds)."""
    x = float(x)
    if x == 0:
        return "0"
    text = "%.*g" % (digits, x)
    if "e" in text:
        mantissa, exponent = text.split("e")
        text = mantissa + "e" + str(int(exponent))
    return text


def rounded(x, digits=10):
    return float(num(x, digits))


def point_segment_distance(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    s = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)
    s = max(0.0, min(1.0, s))
    return math.hypot(p[0] - a[0] - s * dx, p[1] - a[1] - s * dy)


def check_no_overlap(scene, margin):
    """Every ball is at least `margin` clear of every other ball and wall.
    Balls are sorted into cells so that 2000 of them check quickly."""
    balls = scene["balls"]
    r_max = max(b["radius"] for b in balls)
    cell = 2 * r_max + margin
    grid = {}
    for i, b in enumerate(balls):
        key = (math.floor(b["position"][0] / cell), math.floor(b["position"][1] / cell))
        grid.setdefault(key, []).append(i)
    for i, b in enumerate(balls):
        (x, y), r = b["position"], b["radius"]
        cx, cy = math.floor(x / cell), math.floor(y / cell)
        for gx in (cx - 1, cx, cx + 1):
            for gy in (cy - 1, cy, cy + 1):
                for k in grid.get((gx, gy), ()):
                    if k <= i:
                        continue
                    o = balls[k]
                    gap = math.hypot(o["position"][0] - x, o["position"][1] - y) - r - o["radius"]
                    if gap < margin:
                        raise SystemExit(f"{scene['name']}: balls[{i}] and balls[{k}] are {gap:.3g} apart")
        for w, wall in enumerate(scene["walls"]):
            gap = point_segment_distance((x, y), wall["a"], wall["b"]) - r
            if gap < margin:
                raise SystemExit(f"{scene['name']}: balls[{i}] is {gap:.3g} from walls[{w}]")


def write_scene(scene, filename, margin):
    check_no_overlap(scene, margin)

    def value_text(value):
        if isinstance(value, list):
            return "[" + ", ".join(num(v) for v in value) + "]"
        return num(value)

    def obj(d):
        parts = []
        for key, value in d.items():
            if isinstance(value, list):
                text = value_text(value)
            elif isinstance(value, bool):
                text = "true" if value else "false"
            else:
                text = num(value)
            parts.append(f'"{key}": {text}')
        return "{" + ", ".join(parts) + "}"

    lines = ["{", f' "name": "{scene["name"]}",']
    for key in ("gravity", "duration", "restitution"):
        if key in scene:
            lines.append(f' "{key}": {value_text(scene[key])},')
    lines.append(' "record": ' + obj(scene["record"]) + ",")
    lines.append(' "walls": [')
    lines += ["  " + obj(w) + ("," if i + 1 < len(scene["walls"]) else "") for i, w in enumerate(scene["walls"])]
    lines.append(" ],")
    lines.append(' "balls": [')
    lines += ["  " + obj(b) + ("," if i + 1 < len(scene["balls"]) else "") for i, b in enumerate(scene["balls"])]
    lines.append(" ]")
    lines.append("}")
    with open(os.path.join(HERE, filename), "w") as f:
        f.write("\n".join(lines) + "\n")


def box_walls(x0, y0, x1, y1):
    """Four zero-thickness walls, counter-clockwise from the bottom."""
    return [{"a": [x0, y0], "b": [x1, y0]}, {"a": [x1, y0], "b": [x1, y1]},
            {"a": [x1, y1], "b": [x0, y1]}, {"a": [x0, y1], "b": [x0, y0]}]


def gaussian(rng):
    """Box-Muller from rng.random() alone (its sequence is fixed across Python versions)."""
    u1 = 1.0 - rng.random()
    u2 = rng.random()
    return math.sqrt(-2.0 * math.log(u1)) * math.cos(2.0 * math.pi * u2)


def place_randomly(rng, radii, x0, y0, x1, y1, margin, existing=()):
    """Random non-overlapping centres in the box (rejection), rounded."""
    placed = list(existing)
    out = []
    for r in radii:
        for _ in range(100000):
            p = [rounded(rng.uniform(x0 + r + margin, x1 - r - margin), 8),
                 rounded(rng.uniform(y0 + r + margin, y1 - r - margin), 8)]
            if all(math.hypot(p[0] - q[0], p[1] - q[1]) >= r + s + margin for q, s in placed):
                placed.append((p, r))
                out.append(p)
                break
        else:
            raise SystemExit("could not place the balls")
    return out


def fast_box():
    # 20 balls at speed 1e5 in the unit box. Wall hits per ball per second
    # ~ (|vx| + |vy|) / (1 - 2r) ~ 1.3e5; ball-ball ~ v / mean free path
    # (~1.2) ~ 0.8e5: ~3.9e6 events per second measured, ~1e6 in 0.25 s;
    # 2000 frames.
    rng = random.Random(101)
    n, speed = 20, 1e5
    radii = [rounded(rng.uniform(0.01, 0.02), 4) for _ in range(n)]
    centres = place_randomly(rng, radii, 0, 0, 1, 1, 1e-3)
    balls = []
    for r, p in zip(radii, centres):
        angle = rng.uniform(0, 2 * math.pi)
        balls.append({"position": p, "velocity": [rounded(speed * math.cos(angle)), rounded(speed * math.sin(angle))],
                      "radius": r})
    return {"name": "fast_box", "duration": 0.25, "restitution": 1.0, "record": {"interval": 1.25e-4},
            "walls": box_walls(0, 0, 1, 1), "balls": balls}


def two_mass_gas():
    # 150 light (m = 1, r = 0.006) and 150 heavy (m = 4, r = 0.01) disks in the
    # unit box, packing fraction 0.064. The light ones carry all the energy at
    # the start (Maxwell speeds scaled to mean KE 2, so that kT = 1 once it is
    # shared); the heavy ones are at rest. Each disk has ~14 collisions per
    # unit time (measured): equipartition within a few units; 400 units in
    # all, ~1e6 events, the second half measured (tests/physics).
    rng = random.Random(202)
    n_light, n_heavy = 150, 150
    specs = [(1.0, 0.006)] * n_light + [(4.0, 0.01)] * n_heavy
    order = list(range(len(specs)))
    rng.shuffle(order)
    specs = [specs[i] for i in order]
    centres = place_randomly(rng, [r for _, r in specs], 0, 0, 1, 1, 1e-3)
    vel = []
    for m, _ in specs:
        vel.append([gaussian(rng), gaussian(rng)] if m == 1.0 else [0.0, 0.0])
    ke = sum(0.5 * m * (v[0] ** 2 + v[1] ** 2) for (m, _), v in zip(specs, vel))
    scale = math.sqrt(2.0 * n_light / ke)  # mean KE of a light disk: 2
    balls = []
    for (m, r), p, v in zip(specs, centres, vel):
        ball = {"position": p, "velocity": [rounded(v[0] * scale), rounded(v[1] * scale)], "radius": r}
        if m != 1.0:
            ball["mass"] = m
        balls.append(ball)
    return {"name": "two_mass_gas", "duration": 400.0, "restitution": 1.0, "record": {"interval": 0.5},
            "walls": box_walls(0, 0, 1, 1), "balls": balls}


def dense_gas(n, eta, seed, duration, interval):
    # n disks of diameter 1 (r = 0.5, m = 1) in a square box of side
    # L = sqrt(n pi r^2 / eta) rounded to 4 significant digits (eta is then
    # within 1e-4 of the target), on a square lattice of the smallest side
    # holding n sites, velocities Gaussian with zero total momentum scaled so
    # that the mean KE per disk is kT = 1 (2D; to the 7 digits written).
    # Collisions per disk per unit time (Enskog, 2D): 2 n sigma g(sigma)
    # sqrt(pi kT / m) ~ 3.2 at eta = 0.35: ~3200 per unit time for n = 2000
    # (measured: 3196), so 320 units give ~1e6 collisions and ~19000 wall hits
    # in the second half.
    rng = random.Random(seed)
    r = 0.5
    side = rounded(math.sqrt(n * math.pi * r * r / eta), 4)
    k = math.ceil(math.sqrt(n))
    spacing = side / k
    if spacing < 2 * r + 0.05:
        raise SystemExit("dense_gas: lattice too tight")
    sites = [(i, j) for j in range(k) for i in range(k)]
    rng.shuffle(sites)
    sites = sorted(sites[:n], key=lambda s: (s[1], s[0]))
    vel = [[gaussian(rng), gaussian(rng)] for _ in range(n)]
    mean = [sum(v[c] for v in vel) / n for c in (0, 1)]
    vel = [[v[0] - mean[0], v[1] - mean[1]] for v in vel]
    ke = sum(0.5 * (v[0] ** 2 + v[1] ** 2) for v in vel)
    scale = math.sqrt(n / ke)
    balls = [{"position": [rounded((i + 0.5) * spacing, 8), rounded((j + 0.5) * spacing, 8)],
              "velocity": [rounded(v[0] * scale, 7), rounded(v[1] * scale, 7)], "radius": r}
             for (i, j), v in zip(sites, vel)]
    return {"name": f"dense_gas_{n}", "duration": duration, "restitution": 1.0, "record": {"interval": interval},
            "walls": box_walls(0, 0, side, side), "balls": balls}


def newtons_cradle():
    # Ball 0 strikes a row of four at rest, gaps 1e-9 (a touching row is an
    # exact tie the engine orders by index; the gaps give the textbook order
    # too). Equal masses, elastic: after each chain one ball moves at speed 1
    # and the rest are at rest; the end balls bounce off the box's walls and
    # the chain runs back and forth.
    r, gap = 0.1, 1e-9
    balls = [{"position": [0.5, 0.5], "velocity": [1.0, 0.0], "radius": r}]
    for k in range(4):
        balls.append({"position": [1.0 + k * (2 * r + gap), 0.5], "velocity": [0.0, 0.0], "radius": r})
    return {"name": "newtons_cradle", "duration": 20.0, "restitution": 1.0, "record": {"interval": 0.01},
            "walls": box_walls(0, 0, 3, 1), "balls": balls}


def resting_pile():
    # Six balls (r = 0.1) dropped from rest, 0.3 apart in height, at random
    # abscissae (off centre, so none lands squarely on another), into a bin
    # 0.45 wide: two fit side by side on the floor, the rest settle in the
    # pockets above. Balls have restitution 0.5, walls 1: a contact has 0.5
    # against a wall, 0.25 between balls. Frictionless: horizontal motion dies
    # only through the walls and the other balls; they come to rest on the
    # floor and on each other within the 5 s.
    rng = random.Random(303)
    r, width = 0.1, 0.45
    walls = [{"a": [0, 0], "b": [width, 0], "restitution": 1.0},
             {"a": [width, 0], "b": [width, 3], "restitution": 1.0},
             {"a": [0, 3], "b": [0, 0], "restitution": 1.0}]
    balls = [{"position": [rounded(rng.uniform(r + 0.01, width - r - 0.01), 4), 0.3 + 0.3 * k],
              "velocity": [0.0, 0.0], "radius": r} for k in range(6)]
    return {"name": "resting_pile", "gravity": [0.0, -9.81], "duration": 5.0, "restitution": 0.5,
            "record": {"interval": 0.01}, "walls": walls, "balls": balls}


def funnel():
    # 40 balls (r = 0.04) on a jittered lattice above a V funnel (two walls
    # from (+-1, 2) down to (+-0.12, 1.2): an opening of 0.24, three
    # diameters), falling into the box [-1, 1] x [0, 1] below. Restitution 0.8
    # everywhere (0.64 per contact). Side walls above the funnel keep them in.
    rng = random.Random(404)
    r = 0.04
    walls = [{"a": [-1, 2], "b": [-0.12, 1.2]}, {"a": [0.12, 1.2], "b": [1, 2]},
             {"a": [-1, 2], "b": [-1, 3.5]}, {"a": [1, 2], "b": [1, 3.5]}]
    walls += [{"a": [-1, 0], "b": [1, 0]}, {"a": [1, 0], "b": [1, 1]}, {"a": [-1, 1], "b": [-1, 0]}]
    balls = []
    for j in range(4):
        for i in range(10):
            x = -0.81 + i * 0.18 + rng.uniform(-0.02, 0.02)
            y = 2.3 + j * 0.2 + rng.uniform(-0.02, 0.02)
            balls.append({"position": [rounded(x, 6), rounded(y, 6)],
                          "velocity": [rounded(rng.uniform(-0.2, 0.2), 6), rounded(rng.uniform(-0.2, 0.2), 6)],
                          "radius": r})
    return {"name": "funnel", "gravity": [0.0, -9.81], "duration": 4.0, "restitution": 0.8,
            "record": {"interval": 0.01}, "walls": walls, "balls": balls}


def main():
    write_scene(fast_box(), "fast_box.json", 1e-3)
    write_scene(two_mass_gas(), "two_mass_gas.json", 1e-3)
    write_scene(dense_gas(2000, 0.35, 303, 320.0, 1.0), "dense_gas_2000.json", 0.05)
    write_scene(dense_gas(400, 0.35, 304, 640.0, 1.0), "dense_gas_400.json", 0.05)
    write_scene(newtons_cradle(), "newtons_cradle.json", 5e-10)
    write_scene(resting_pile(), "resting_pile.json", 1e-3)
    write_scene(funnel(), "funnel.json", 1e-3)


if __name__ == "__main__":
    main()
