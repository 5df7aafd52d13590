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
  pile_50.json         50 balls of two sizes (restitution 0.9) dropped into a box
                       4 wide with one slanted wall across a bottom corner: a
                       pile that must come to rest (60 s).
  pyramid_groove.json  15 equal balls (restitution 0.5) stacked as a pyramid of
                       rows 5, 4, 3, 2, 1 in a flat-bottomed channel, every gap
                       to a neighbour, the floor or a side wall 1e-9: a pile
                       already at rest, which must stay at rest (60 s).
  hopper_300.json      300 balls of three sizes (masses by area, restitution
                       0.8) poured through a V hopper with a neck 4.5 large
                       diameters wide into a box below (60 s).
  corner_ball.json     one ball (restitution 0.52) in a 2 x 2 box, gravity
                       (-1, -1.75) pointing into the lower left corner, where
                       it must come to rest on two walls at once (60 s).

The analysis is analysis/gas_observables.py; the tests are tests/physics/.
Every scene is checked here for overlaps (ball-ball and ball-wall, with a
margin) before it is written; numbers are rounded to a few significant digits
first and the check is made on the rounded values, which are what the file
holds (pyramid_groove.json, placed to the ulp, holds its doubles exactly).

Regenerate: /usr/bin/python3 datasets/scenes/make_scenes.py
"""
import math
import os
import random
from fractions import Fraction

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


def exact_num(x):
    """num(x) if that reads back as the double x, else the shortest text that
    does (Python's repr)."""
    x = float(x)
    text = num(x)
    return text if float(text) == x else repr(x)


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


def write_scene(scene, filename, margin, exact=False):
    """Writes the scene as JSON, numbers to 10 significant digits, or with
    exact=True as the shortest text that reads back as the same double (for
    scenes whose gaps are placed to the ulp)."""
    check_no_overlap(scene, margin)
    number = exact_num if exact else num

    def value_text(value):
        if isinstance(value, list):
            return "[" + ", ".join(number(v) for v in value) + "]"
        return number(value)

    def obj(d):
        parts = []
        for key, value in d.items():
            if isinstance(value, list):
                text = value_text(value)
            elif isinstance(value, bool):
                text = "true" if value else "false"
            else:
                text = number(value)
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


def jittered_ball(rng, x, y, jitter, speed, r, r_unit):
    """A ball near (x, y) (uniform jitter), with a uniform random velocity of
    components below `speed`, and mass (r / r_unit)^2 (one per unit disc
    area) unless r is the unit radius."""
    ball = {"position": [rounded(x + rng.uniform(-jitter, jitter), 6), rounded(y + rng.uniform(-jitter, jitter), 6)],
            "velocity": [rounded(rng.uniform(-speed, speed), 6), rounded(rng.uniform(-speed, speed), 6)],
            "radius": r}
    if r != r_unit:
        ball["mass"] = rounded((r / r_unit) ** 2)
    return ball


def pile_50():
    # 50 balls, radii 0.15 and 0.25 (masses by area: 0.36 and 1), on a
    # jittered 7 x 8 grid (56 sites, 50 used; spacing 0.55 across, 0.6 up)
    # from y = 1.5 to 5.7, with random velocities up to 0.5, in a closed box
    # 4 wide and 8 tall; a slanted wall from (3.2, 0) to (4, 0.8) cuts off the
    # lower right corner. Restitution 0.9 everywhere, 0.81 per contact: a
    # bounce keeps 0.81^2 = 66 % of its height, so a free ball stops bouncing
    # within seconds; the pile (about 2 deep) has most of the 60 s to settle.
    rng = random.Random(505)
    walls = box_walls(0, 0, 4, 8) + [{"a": [3.2, 0], "b": [4, 0.8]}]
    sites = [(i, j) for j in range(8) for i in range(7)]
    rng.shuffle(sites)
    sites = sorted(sites[:50], key=lambda s: (s[1], s[0]))
    balls = []
    for i, j in sites:
        r = 0.25 if rng.random() < 0.5 else 0.15
        balls.append(jittered_ball(rng, 0.35 + 0.55 * i, 1.5 + 0.6 * j, 0.02, 0.5, r, 0.25))
    return {"name": "pile_50", "gravity": [0.0, -9.81], "duration": 60.0, "restitution": 0.9,
            "record": {"interval": 0.02}, "walls": walls, "balls": balls}


def exact_gap(p, q, reach):
    """|p - q| - reach from the doubles p and q (rationals: no rounding), to
    first order: (|p - q|^2 - reach^2) / (2 reach), off by ~(|p - q| -
    reach)^2 / (2 reach), ~1e-33 for the pyramid's distances."""
    dx, dy = Fraction(p[0]) - Fraction(q[0]), Fraction(p[1]) - Fraction(q[1])
    return (dx * dx + dy * dy - reach * reach) / (2 * reach)


def nearest_doubles(point, cost, steps=3):
    """The double point within `steps` ulps of `point` (each coordinate) of
    least cost(candidate)."""
    def around(x):
        out, lo, hi = [x], x, x
        for _ in range(steps):
            lo, hi = math.nextafter(lo, -math.inf), math.nextafter(hi, math.inf)
            out += [lo, hi]
        return out
    return min(((x, y) for x in around(point[0]) for y in around(point[1])), key=cost)


def pyramid_groove():
    # 15 balls of radius r = 0.1 in rows of 5, 4, 3, 2, 1, hexagonally packed
    # with every gap g = 1e-9: the bottom row g above the floor y = 0, its
    # end balls g from the side walls x = 0 and x = W, each higher ball g
    # from the two balls it sits on and from its neighbours in its row
    # (centres D = 2r + g apart, rows D sqrt(3)/2 apart). Exact centres are
    # irrational; each is rounded to doubles and then moved by a few ulps to
    # where the gaps, computed exactly from the doubles written (rationals),
    # are closest to g: all 37 come out within 6e-17 of 1e-9, about half
    # an ulp of the coordinates (printed by main). Frictionless, yet at rest: every ball rests on two below (or on
    # the floor), the end balls of the bottom row are held by the side walls.
    # Restitution 0.5. Nothing should move more than the 1e-9 gaps allow.
    r, g = 0.1, 1e-9
    fr, fg = Fraction(r), Fraction(g)
    reach_ball, reach_wall = 2 * fr + fg, fr + fg
    bottom = [(float(reach_wall), float(reach_wall))]  # along the floor, left to right
    for _ in range(4):
        bottom.append((float(Fraction(bottom[-1][0]) + reach_ball), float(reach_wall)))
    rows = [bottom]
    height = math.sqrt(3) / 2 * (2 * r + g)
    for level in range(1, 5):
        below, row = rows[-1], []
        for k in range(5 - level):
            a, b = below[k], below[k + 1]
            guess = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2 + height)
            neighbours = [a, b] + row[-1:]
            row.append(nearest_doubles(
                guess, lambda p: max(abs(exact_gap(p, q, reach_ball)) for q in neighbours)))
        rows.append(row)
    width = float(Fraction(rows[0][-1][0]) + reach_wall)
    walls = [{"a": [0, 0], "b": [width, 0]}, {"a": [width, 0], "b": [width, 1.2]},
             {"a": [0, 1.2], "b": [0, 0]}]
    balls = [{"position": list(p), "velocity": [0.0, 0.0], "radius": r} for row in rows for p in row]
    return {"name": "pyramid_groove", "gravity": [0.0, -9.81], "duration": 60.0, "restitution": 0.5,
            "record": {"interval": 0.02}, "walls": walls, "balls": balls}


def pyramid_gaps(scene, g=1e-9):
    """How far each gap of about g in the scene (ball-ball, ball-floor, ball-
    side wall) is from g, exactly from its doubles: for the report in main."""
    balls, fg, out = scene["balls"], Fraction(g), []
    for i, b in enumerate(balls):
        p, r = b["position"], Fraction(b["radius"])
        for o in balls[i + 1:]:
            off = exact_gap(p, o["position"], r + Fraction(o["radius"]) + fg)
            if abs(off) < g:
                out.append(off)
        for wall in scene["walls"]:
            a, c = wall["a"], wall["b"]
            if a[0] == c[0]:  # a vertical side wall
                off = abs(Fraction(p[0]) - Fraction(a[0])) - r - fg
            else:  # the floor
                off = Fraction(p[1]) - Fraction(a[1]) - r - fg
            if abs(off) < g:
                out.append(off)
    return out


def hopper_300():
    # 300 balls, radii 0.03, 0.045 and 0.06 in equal numbers (shuffled),
    # masses by area (0.25, 0.5625, 1), on a loose 18 x 17 grid (306 sites,
    # spacing 0.16, jitter 0.015: at least 0.01 clear) from y = 2.7 up, with
    # random velocities up to 0.3, above a V hopper: two walls from
    # (-1.5, 2.5) and (1.5, 2.5) down to (-0.27, 1.8) and (0.27, 1.8), a neck
    # of 0.54, 4.5 large diameters. Below and around it a closed box
    # [-1.5, 1.5] x [0, 6]. Restitution 0.8 (0.64 per contact). The balls
    # cover 2.05 units of area: packed at ~0.8 they fill the box below the
    # neck (3 x 1.8) to a depth of ~0.9, unless an arch jams the neck.
    rng = random.Random(606)
    walls = box_walls(-1.5, 0, 1.5, 6) + [{"a": [-1.5, 2.5], "b": [-0.27, 1.8]}, {"a": [0.27, 1.8], "b": [1.5, 2.5]}]
    radii = [0.03, 0.045, 0.06] * 100
    rng.shuffle(radii)
    sites = [(i, j) for j in range(17) for i in range(18)]
    rng.shuffle(sites)
    sites = sorted(sites[:300], key=lambda s: (s[1], s[0]))
    balls = []
    for (i, j), r in zip(sites, radii):
        balls.append(jittered_ball(rng, -1.36 + 0.16 * i, 2.7 + 0.16 * j, 0.015, 0.3, r, 0.06))
    return {"name": "hopper_300", "gravity": [0.0, -9.81], "duration": 60.0, "restitution": 0.8,
            "record": {"interval": 0.02}, "walls": walls, "balls": balls}


def corner_ball():
    # One ball (r = 0.1) in the box [0, 2]^2 under gravity (-1, -1.75), which
    # points into the lower left corner (about 30 degrees off the floor's
    # normal): released at (1.1, 0.9) with velocity (0.6, 0.35), it bounces
    # between the floor and the left wall (restitution 0.52 each, 0.27 per
    # contact) and comes to rest in the corner touching both walls at once,
    # the case of a ball pressed into one wall by its acceleration while
    # resting on another.
    return {"name": "corner_ball", "gravity": [-1.0, -1.75], "duration": 60.0, "restitution": 0.52,
            "record": {"interval": 0.02}, "walls": box_walls(0, 0, 2, 2),
            "balls": [{"position": [1.1, 0.9], "velocity": [0.6, 0.35], "radius": 0.1}]}


def main():
    write_scene(fast_box(), "fast_box.json", 1e-3)
    write_scene(two_mass_gas(), "two_mass_gas.json", 1e-3)
    write_scene(dense_gas(2000, 0.35, 303, 320.0, 1.0), "dense_gas_2000.json", 0.05)
    write_scene(dense_gas(400, 0.35, 304, 640.0, 1.0), "dense_gas_400.json", 0.05)
    write_scene(newtons_cradle(), "newtons_cradle.json", 5e-10)
    write_scene(resting_pile(), "resting_pile.json", 1e-3)
    write_scene(funnel(), "funnel.json", 1e-3)
    write_scene(pile_50(), "pile_50.json", 1e-2)
    pyramid = pyramid_groove()
    write_scene(pyramid, "pyramid_groove.json", 5e-10, exact=True)
    offs = pyramid_gaps(pyramid)
    print(f"pyramid_groove: {len(offs)} gaps of 1e-9, off by at most {float(max(map(abs, offs))):.2g}")
    write_scene(hopper_300(), "hopper_300.json", 1e-2)
    write_scene(corner_ball(), "corner_ball.json", 1e-2)


if __name__ == "__main__":
    main()
