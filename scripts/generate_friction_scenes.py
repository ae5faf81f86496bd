#!/usr/bin/env python3
"""Writes the friction scenes of issue 8 into samples/scenes/*.json, built exactly as
docs/scene-specifications.md specifies them: A1 sphere_slide, B5 spin_decay, B6 backspin and B7
painleve_rod (mu 1.0 and 1.5). Geometry, masses, explicit principal inertias, one (mu, e) per scene,
poses, velocities, dt and duration as written there; numbers with repr() (exact round trip).
(A2 box_incline is written by generate_contact_scenes.py; B11 double_loop by
generate_double_loop.py.)

Usage: python3 scripts/generate_friction_scenes.py [output_dir]   (default: samples/scenes)
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_json import write_scene  # noqa: E402


def rot_y(angle):
    """Quaternion [w, x, y, z] of R_y(angle) (docs/scene-specifications.md section 0): x -> (cos a, 0, -sin a)."""
    return [math.cos(angle / 2), 0.0, math.sin(angle / 2), 0.0]


def ground():
    return {"name": "ground", "type": "static", "shapes": [{"type": "plane", "material": "scene"}]}


def scene(name, description, dt, duration, mu, bodies):
    return {"name": name, "description": description, "time_step": dt,
            "steps": round(duration / dt),
            "materials": {"scene": {"friction": mu, "restitution": 0.0}}, "bodies": bodies}


def sphere(velocity, angular_velocity=None):
    """docs/scene-specifications.md A1: sphere r 0.1 m, 1 kg, I = 0.4 m r^2 = 0.004, COM (0, 0, 0.1)."""
    body = {"name": "sphere", "position": [0.0, 0.0, 0.1], "linear_velocity": velocity}
    if angular_velocity is not None:
        body["angular_velocity"] = angular_velocity
    body.update({"mass": 1.0, "inertia": [0.004] * 3,
                 "shapes": [{"type": "sphere", "radius": 0.1, "material": "scene"}]})
    return body


def sphere_slide():
    return scene("sphere_slide",
                 "docs/scene-specifications.md A1 sphere_slide v0=2 mu=0.3: a sliding ball starts rolling at "
                 "t* = 0.194165 s and rolls at 5 v0 / 7 = 1.428571 m/s.",
                 0.01, 1.0, 0.3, [ground(), sphere([2.0, 0.0, 0.0])])


def spin_decay():
    h, m = 0.1, 1.0
    box = {"name": "box", "position": [0.0, 0.0, 0.1], "angular_velocity": [0.0, 0.0, 20.0],
           "mass": m, "inertia": [m * 8.0 * h * h / 12.0] * 3,
           "shapes": [{"type": "box", "half_extents": [h, h, h], "material": "scene"}]}
    return scene("spin_decay",
                 "docs/scene-specifications.md B5 spin_decay box mu=0.1 w0=20: a box spinning on its face slows at "
                 "-20.810153 rad/s^2 (four-corner torsional friction) and stops at 0.961069 s.",
                 0.01, 1.5, 0.1, [ground(), box])


def backspin():
    return scene("backspin",
                 "docs/scene-specifications.md B6 backspin sphere v0=2 w0=100 mu=0.3: the ball stops at 0.679579 m, "
                 "comes back and rolls home at -1.428571 m/s.",
                 0.01, 2.0, 0.3, [ground(), sphere([2.0, 0.0, 0.0], [0.0, -100.0, 0.0])])


def capsule_x_inertia(r, hl, m):
    """docs/scene-specifications.md 'capsuleX(r, hl, m)': exact solid capsule, mass split by volume."""
    h = 2.0 * hl
    v_c, v_s = math.pi * r * r * h, 4.0 / 3.0 * math.pi * r ** 3
    m_c, m_s = m * v_c / (v_c + v_s), m * v_s / (v_c + v_s)
    ix = m_c * r * r / 2.0 + m_s * 0.4 * r * r
    iy = m_c * (r * r / 4.0 + h * h / 12.0) + m_s * (0.4 * r * r + h * h / 4.0 + 3.0 * h * r / 8.0)
    return [ix, iy, iy]


def painleve_rod(mu, file_name):
    r, hl, m = 0.02, 0.48, 1.0
    theta0 = math.atan(2.0)
    rod = {"name": "rod", "position": [0.0, 0.0, hl * math.sin(theta0) + r],
           "orientation": rot_y(-theta0), "linear_velocity": [-1.0, 0.0, 0.0],
           "mass": m, "inertia": capsule_x_inertia(r, hl, m),
           # geometry's capsule lies along local z: R_y(90 deg) puts it along the body's x.
           "shapes": [{"type": "capsule", "radius": r, "half_length": hl,
                       "orientation": rot_y(math.pi / 2), "material": "scene"}]}
    outcome = ("slides with P_n = P_t = 0.2581559 N s in the first step" if mu < 1.3 else
               "is in the Painleve region: the foot sticks in the first step, "
               "P_n = 0.3773438, P_t = 0.4154954 N s")
    document = scene(file_name,
                     f"docs/scene-specifications.md B7 painleve_rod mu={mu}: a 1 m rod at atan 2 from the floor, foot "
                     f"sliding at 1 m/s, {outcome}.", 0.01, 1.0, mu, [ground(), rod])
    # The upper end lands at ~5 m/s (5 cm per step): a 0.1 m speculative margin (instead of 5 mm)
    # lets the velocity step stop it at the floor instead of 2.6 cm inside it, whose correction
    # would raise the energy. It changes no rest geometry (docs/scene-specifications.md section 0).
    document["solver"] = {"speculative_margin": 0.1}
    return document


def write(directory, document):
    write_scene(document, directory)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "samples", "scenes")
    for document in (sphere_slide(), spin_decay(), backspin(),
                     painleve_rod(1.0, "painleve_rod_mu1_0"), painleve_rod(1.5, "painleve_rod_mu1_5")):
        write(directory, document)


if __name__ == "__main__":
    main()
