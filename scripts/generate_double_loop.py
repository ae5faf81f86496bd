#!/usr/bin/env python3
"""Writes samples/scenes/double_loop.json, docs/scene-specifications.md B11 (the Alart-Curnier paper's figure 9, after
Kaufman et al. 2005): two rails curled into two loops, each a chain of 1720 static capsules, and a
ball spinning at 180 rad/s with no translational velocity. Built exactly as docs/scene-specifications.md B11 says:

  midline  C(phi) = (A phi + B sin phi, D phi / (2 pi), B (1 - cos phi)), phi in [-pi/2, 4 pi],
           A = 0.4, B = 1.0, D = 0.4 m; then a straight exit of 2 m along the tangent at 4 pi
  frame    t = C'/|C'|, b = normalize(y - (y.t) t), n = t x b
  rails    C(phi) +- (w/2) b(phi), w = 0.1; capsules of radius 0.01 between consecutive points
           phi_j = -pi/2 + j pi/360 (j = 0..1620), then 100 exit pieces of 0.02 m
  ball     rho 0.1 m, 1 kg, I 0.004, centre (0, 0, z0) touching both chains, omega = 180 b(0)

The rails are one static body with 3440 capsule shapes (geometry's capsule lies along local z, so
each shape is rotated from z onto its segment). The ball's height z0 is solved here so the ball
touches the polygonal chains (docs/scene-specifications.md gives 0.0979805 m; the smooth-rail value is 0.0979796).
The friction in the file is mu = 1.0 and the solver ac_newton (the paper's); `coulomb run double_loop --mu X` and the conformance cases
set the others. Elastic turning is on (docs/tuning.md, "Elastic turning": without it the step loses
(1/2) m v^2 (v h / R)^2 per step on the curved rails and mu = 1.0 falls before the top of loop 2 at
dt 0.01). samples/conformance/DoubleLoopTrack.cpp evaluates the same midline in C++.

Usage: python3 scripts/generate_double_loop.py [output_dir]   (default: samples/scenes)
"""
import json
import math
import os
import sys

A, B, DRIFT = 0.4, 1.0, 0.4
WIDTH, RAIL_RADIUS = 0.1, 0.01
BALL_RADIUS, OMEGA0 = 0.1, 180.0
EXIT_LENGTH, EXIT_PIECES = 2.0, 100
PHI_START, PHI_END, PER_PI = -math.pi / 2, 4 * math.pi, 360


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def scale(s, a):
    return [s * x for x in a]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def norm(a):
    return math.sqrt(dot(a, a))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def midline(phi):
    return [A * phi + B * math.sin(phi), DRIFT * phi / (2 * math.pi), B * (1 - math.cos(phi))]


def tangent(phi):
    d = [A + B * math.cos(phi), DRIFT / (2 * math.pi), B * math.sin(phi)]
    return scale(1 / norm(d), d)


def lateral(t):
    y = [0.0, 1.0, 0.0]
    b = sub(y, scale(dot(y, t), t))
    return scale(1 / norm(b), b)


def rail_points(side):
    """Consecutive capsule end points of one rail (side = +1 or -1)."""
    points = []
    for j in range(round((PHI_END - PHI_START) * PER_PI / math.pi) + 1):
        phi = PHI_START + j * math.pi / PER_PI
        points.append(add(midline(phi), scale(side * WIDTH / 2, lateral(tangent(phi)))))
    t_end = tangent(PHI_END)
    exit_start = add(midline(PHI_END), scale(side * WIDTH / 2, lateral(t_end)))
    for k in range(1, EXIT_PIECES + 1):
        points.append(add(exit_start, scale(k * EXIT_LENGTH / EXIT_PIECES, t_end)))
    return points


def quat_z_to(d):
    """Unit quaternion [w, x, y, z] rotating local z onto the unit vector d (d never -z here)."""
    q = [1.0 + d[2], -d[1], d[0], 0.0]
    return scale(1 / norm(q), q)


def capsule(p, q):
    d = sub(q, p)
    length = norm(d)
    return {"type": "capsule", "radius": RAIL_RADIUS, "half_length": length / 2,
            "position": scale(0.5, add(p, q)), "orientation": quat_z_to(scale(1 / length, d)),
            "material": "scene"}


def segment_distance(c, p, q):
    d = sub(q, p)
    s = min(1.0, max(0.0, dot(sub(c, p), d) / dot(d, d)))
    return norm(sub(c, add(p, scale(s, d))))


def chain_distance(c, points, near):
    return min(segment_distance(c, points[i], points[i + 1]) for i in near)


def touching_height(rails):
    """z of the ball centre above C(0) at which it touches both chains (bisection)."""
    start = round(-PHI_START * PER_PI / math.pi)  # index of phi = 0
    near = range(start - 5, start + 5)
    lo, hi = 0.09, 0.11
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        gap = min(chain_distance([0.0, 0.0, mid], r, near) for r in rails) - BALL_RADIUS - RAIL_RADIUS
        lo, hi = (mid, hi) if gap < 0 else (lo, mid)
    return hi


def rounded(values):
    return [float(f"{v:.12g}") for v in values]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "samples", "scenes")
    rails = [rail_points(+1), rail_points(-1)]
    z0 = touching_height(rails)
    shapes = []
    for points in rails:
        for p, q in zip(points[:-1], points[1:]):
            shape = capsule(p, q)
            # 12 significant digits keep the file under 1 MB; a capsule end then moves < 1e-12 m.
            for key in ("position", "orientation"):
                shape[key] = rounded(shape[key])
            shape["half_length"] = float(f"{shape['half_length']:.12g}")
            shapes.append(shape)
    omega = scale(OMEGA0, lateral(tangent(0.0)))
    ball = {"name": "ball", "position": [0.0, 0.0, z0], "angular_velocity": omega, "mass": 1.0,
            "inertia": [0.004] * 3,
            "shapes": [{"type": "sphere", "radius": BALL_RADIUS, "material": "scene"}]}
    rails_body = {"name": "rails", "type": "static", "shapes": shapes}
    lines = ["{", '  "name": "double_loop",',
             '  "description": ' + json.dumps(
                 "docs/scene-specifications.md B11 double_loop (Alart-Curnier 2011 fig. 9): a ball spinning at "
                 "180 rad/s on two rails of 1720 static capsules curled into two loops; mu 1.0 "
                 "(--mu 0.1, 0.3, 0.6 for the others) rolls through both loops.") + ",",
             '  "time_step": 0.01,', '  "steps": 500,',
             '  "materials": {"scene": {"friction": 1.0, "restitution": 0.0}},',
             '  "solver": {"name": "ac_newton"},',
             '  "bodies": [', "    " + json.dumps(ball) + ",",
             '    {"name": "rails", "type": "static", "shapes": [']
    lines += ["      " + json.dumps(s) + ("," if i + 1 < len(shapes) else "")
              for i, s in enumerate(shapes)]
    lines += ["    ]}", "  ]", "}"]
    del rails_body
    path = os.path.join(directory, "double_loop.json")
    with open(path, "w", encoding="utf-8") as out:
        out.write("\n".join(lines) + "\n")
    print(f"wrote {path} ({len(shapes)} capsules, ball z0 = {z0!r}, size {os.path.getsize(path)} B)")


if __name__ == "__main__":
    main()
