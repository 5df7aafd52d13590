#!/usr/bin/python3
"""Writes queries.jsonl: 3000 time-of-impact queries of every kind (ball-wall
faces and ends, ball-ball linear and quartic, moving and fixed, with and
without gravity, grazing and near-miss), fixed seed. The determinism tests
answer them in strict and fixed mode and compare with answers_*.csv, written
by a gcc -O3 build; CI compares a clang -O0 build against the same files.

Regenerate: /usr/bin/python3 make_queries.py > queries.jsonl
"""
import json
import math
import random

rng = random.Random(20261122)


def u(lo, hi):
    return rng.uniform(lo, hi)


def overlaps(ball, other=None, wall=None):
    px, py = ball["position"]
    if other is not None:
        qx, qy = other["position"]
        return math.hypot(px - qx, py - qy) <= ball["radius"] + other["radius"]
    (ax, ay), (bx, by) = wall["a"], wall["b"]
    dx, dy = bx - ax, by - ay
    s = max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)))
    return math.hypot(px - ax - s * dx, py - ay - s * dy) <= ball["radius"]


def ball_wall(gravity):
    while True:
        cx, cy, ang, half = u(-5, 5), u(-5, 5), u(0, math.pi), u(0.5, 5)
        wall = {"a": [cx - half * math.cos(ang), cy - half * math.sin(ang)],
                "b": [cx + half * math.cos(ang), cy + half * math.sin(ang)]}
        ball = {"position": [u(-6, 6), u(-6, 6)], "radius": u(0.05, 1.0)}
        aim = rng.choice([(cx, cy), tuple(wall["a"]), tuple(wall["b"]), (u(-6, 6), u(-6, 6))])
        speed = u(0.5, 10)
        dx, dy = aim[0] - ball["position"][0], aim[1] - ball["position"][1]
        n = math.hypot(dx, dy) or 1.0
        ball["velocity"] = [speed * dx / n, speed * dy / n]
        if not overlaps(ball, wall=wall):
            q = {"horizon": u(0.5, 3), "balls": [ball], "walls": [wall]}
            if gravity:
                q["gravity"] = [0, -9.81]
            return q


def ball_ball(kind):
    while True:
        a = {"position": [u(-6, 6), u(-6, 6)], "radius": u(0.05, 1.0)}
        b = {"position": [u(-6, 6), u(-6, 6)], "radius": u(0.05, 1.0)}
        dx, dy = b["position"][0] - a["position"][0], b["position"][1] - a["position"][1]
        n = math.hypot(dx, dy) or 1.0
        # Aim at an impact parameter near the contact distance: grazes and near misses.
        R = a["radius"] + b["radius"]
        offset = R * u(0.9, 1.1)
        speed = u(0.5, 10)
        tx, ty = dx / n, dy / n
        aimx, aimy = dx - ty * offset, dy + tx * offset
        m = math.hypot(aimx, aimy) or 1.0
        a["velocity"] = [speed * aimx / m, speed * aimy / m]
        q = {"horizon": u(0.5, 3), "balls": [a, b]}
        if kind == "fixed_gravity":
            b["fixed"] = True
            q["gravity"] = [0, -9.81]
        elif kind == "moving_gravity":
            b["velocity"] = [u(-3, 3), u(-3, 3)]
            q["gravity"] = [0, -9.81]
        elif kind == "different_acceleration":
            b["velocity"] = [u(-3, 3), u(-3, 3)]
            a["acceleration"] = [u(-10, 10), u(-10, 10)]
            b["acceleration"] = [u(-10, 10), u(-10, 10)]
        if not overlaps(a, other=b):
            return q


makers = [lambda: ball_wall(False), lambda: ball_wall(True), lambda: ball_ball("linear"),
          lambda: ball_ball("fixed_gravity"), lambda: ball_ball("moving_gravity"),
          lambda: ball_ball("different_acceleration")]
for i in range(3000):
    print(json.dumps(makers[i % len(makers)]()))
