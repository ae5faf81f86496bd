#!/usr/bin/env python3
"""Writes the contact scenes of issue 7 into samples/scenes/*.json, built exactly as
docs/scene-specifications.md specifies them (section 0 rules, A2, A3, A4, B1): geometry, masses,
explicit principal inertias, one (mu, e) per scene, dt, duration and body order. Positions are
computed in double precision with the same expressions as the peer harness (peers/engines/bench.cpp)
and written with repr(), which round-trips exactly, so bodies placed exactly touching stay so.

Usage: python3 scripts/generate_contact_scenes.py [output_dir]   (default: samples/scenes)
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_json import write_scene  # noqa: E402

G = 9.81


def box_inertia(h, m):
    """docs/scene-specifications.md 'box(h, m)': cube of half side h, I = m 8 h^2 / 12 on every axis."""
    return m * 8.0 * h * h / 12.0


def rot_y(angle):
    """Quaternion [w, x, y, z] of R_y(angle) (docs/scene-specifications.md section 0)."""
    return [math.cos(angle / 2), 0.0, math.sin(angle / 2), 0.0]


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return [w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2]


def ground(orientation=None):
    body = {"name": "ground", "type": "static"}
    if orientation is not None:
        body["orientation"] = orientation
    body["shapes"] = [{"type": "plane", "material": "scene"}]
    return body


def box(name, position, h, m, orientation=None, velocity=None):
    body = {"name": name, "position": position}
    if orientation is not None:
        body["orientation"] = orientation
    if velocity is not None:
        body["linear_velocity"] = velocity
    body["mass"] = m
    body["inertia"] = [box_inertia(h, m)] * 3
    body["shapes"] = [{"type": "box", "half_extents": [h, h, h], "material": "scene"}]
    return body


def scene(name, description, dt, duration, mu, e, bodies):
    return {"name": name, "description": description, "time_step": dt,
            "steps": round(duration / dt),
            "materials": {"scene": {"friction": mu, "restitution": e}}, "bodies": bodies}


def box_on_plane():
    return scene("box_on_plane",
                 "A 0.2 m, 1 kg box resting on the ground (mu 0.5): it must not move and its "
                 "contacts must carry exactly its weight.",
                 0.01, 10.0, 0.5, 0.0,
                 [ground(), box("box", [0.0, 0.0, 0.1], 0.1, 1.0)])


def box_incline(variant):
    """docs/scene-specifications.md A2."""
    theta = math.radians(20.0)
    if variant == "C":
        a = math.radians(22.5)
        return scene("box_incline_C_flat_22_5deg",
                     "docs/scene-specifications.md A2 C_flat_22.5deg: a box pushed at 22.5 deg to its axes on flat "
                     "ground (mu 0.5) slides straight and stops after 0.097 m (dt 0.01).",
                     0.01, 1.0, 0.5, 0.0,
                     [ground(), box("box", [0.0, 0.0, 0.1], 0.1, 1.0,
                                    velocity=[math.cos(a), math.sin(a), 0.0])])
    n = [math.sin(theta), 0.0, math.cos(theta)]  # R_y(20 deg) z
    p0 = [0.1 * c for c in n]
    if variant == "A":
        mu, name, duration = math.tan(theta) + 0.05, "box_incline_A_stick", 5.0
        text = ("docs/scene-specifications.md A2 A_stick: a box on a 20 deg incline with mu = tan 20 + 0.05 "
                "sticks (no creep).")
    else:
        mu, name, duration = math.tan(theta) - 0.1, "box_incline_B_slide", 2.0
        text = ("docs/scene-specifications.md A2 B_slide: a box on a 20 deg incline with mu = tan 20 - 0.1 slides "
                "at a = g (sin 20 - mu cos 20) = 0.9218385 m/s^2.")
    return scene(name, text, 0.01, duration, mu, 0.0,
                 [ground(rot_y(theta)), box("box", p0, 0.1, 1.0, orientation=rot_y(theta))])


def box_stack(n):
    """docs/scene-specifications.md A3: N boxes h 0.1, 0.008 kg, box i at (0, 0, 0.1 + 0.2 i), touching exactly."""
    bodies = [ground()]
    for i in range(n):
        bodies.append(box(f"box{i}", [0.0, 0.0, 0.1 + 0.2 * i], 0.1, 0.008))
    return scene(f"box_stack_{n}",
                 f"docs/scene-specifications.md A3 box_stack N={n}: a tower of {n} boxes (0.2 m, 8 g, mu 0.6) that "
                 "must stand still without sleep.",
                 0.01, 10.0, 0.6, 0.0, bodies)


def pyramid(base):
    """docs/scene-specifications.md A4: row k holds base - k boxes at ((j - (n-1)/2) 0.21, 0, 0.1 + 0.2 k)."""
    bodies = [ground()]
    for k in range(base):
        n = base - k
        for j in range(n):
            bodies.append(box(f"box_r{k}_{j}", [(j - (n - 1) / 2) * 0.21, 0.0, 0.1 + 0.2 * k],
                              0.1, 0.008))
    count = base * (base + 1) // 2
    return scene(f"pyramid_{base}",
                 f"docs/scene-specifications.md A4 pyramid base={base}: {count} boxes (0.2 m, 8 g, mu 0.6) in "
                 "staggered rows with 1 cm gaps; it must stand still without sleep.",
                 0.01, 10.0, 0.6, 0.0, bodies)


def box_pile_1000():
    """docs/scene-specifications.md B1: a lattice of 1000 yawed and tilted 1 kg boxes dropped into a container."""
    def wall(name, centre, half):
        return {"name": name, "type": "static", "position": centre,
                "shapes": [{"type": "box", "half_extents": half, "material": "scene"}]}
    bodies = [ground(),
              wall("wall_x_plus", [1.9, 0.0, 0.75], [0.1, 2.0, 0.75]),
              wall("wall_x_minus", [-1.9, 0.0, 0.75], [0.1, 2.0, 0.75]),
              wall("wall_y_plus", [0.0, 1.9, 0.75], [2.0, 0.1, 0.75]),
              wall("wall_y_minus", [0.0, -1.9, 0.75], [2.0, 0.1, 0.75])]
    for i in range(1000):
        ix, iy, iz = i % 10, (i // 10) % 10, i // 100
        psi = math.fmod(2.399963229728653 * i, 2.0 * math.pi)
        tau = 0.1 * math.sin(1.7 * i)
        yaw = [math.cos(psi / 2), 0.0, 0.0, math.sin(psi / 2)]
        tilt = [math.cos(tau / 2), math.sin(tau / 2), 0.0, 0.0]
        q = quat_mul(yaw, tilt)  # R_z(psi) R_x(tau)
        norm = math.sqrt(sum(c * c for c in q))
        bodies.append(box(f"box{i}", [(ix - 4.5) * 0.35, (iy - 4.5) * 0.35, 0.15 + 0.35 * iz],
                          0.1, 1.0, orientation=[c / norm for c in q]))
    return scene("box_pile_1000",
                 "docs/scene-specifications.md B1 box_pile_1000 container: 1000 yawed, tilted 0.2 m boxes (1 kg, "
                 "mu 0.6) fall into a 3.6 x 3.6 m container and settle into one large island.",
                 0.01, 10.0, 0.6, 0.0, bodies)


def write(directory, document):
    write_scene(document, directory)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "samples", "scenes")
    for document in (box_on_plane(), box_incline("A"), box_incline("B"), box_incline("C"),
                     box_stack(10), box_stack(20), pyramid(10), pyramid(20), box_pile_1000()):
        write(directory, document)


if __name__ == "__main__":
    main()
