#!/usr/bin/env python3
"""Writes the jointed scenes of issue 9 into samples/scenes/*.json, built exactly as
docs/scene-specifications.md specifies them: A6 chain (N=10, N=50, maximal), B8 pendulum (maximal),
B9 double_pendulum (release_horizontal, maximal), B10 four_bar (hinges, redundant; rssr), plus a
rope bridge of hinged planks carrying three boxes (one island of joints and contacts). Joint
anchors and axes are written in world coordinates at t = 0 (docs/scene-format.md "Joints").
Numbers are written with repr(), which round-trips exactly.

Usage: python3 scripts/generate_joint_scenes.py [output_dir]   (default: samples/scenes)
"""
import json
import math
import os
import sys

NO_COLLISION = {"category": 0, "mask": 0}  # docs/scene-specifications.md: "no contacts" / "capsules do not collide"


def rot_y(angle):
    """Quaternion [w, x, y, z] of R_y(angle) (docs/scene-specifications.md section 0): x -> (cos a, 0, -sin a)."""
    return [math.cos(angle / 2), 0.0, math.sin(angle / 2), 0.0]


def capsule_x(radius, half_length, **extra):
    """A capsule along the body's local x (geometry's capsule lies along z: rotate by R_y(90))."""
    shape = {"type": "capsule", "radius": radius, "half_length": half_length,
             "orientation": rot_y(math.pi / 2)}
    shape.update(extra)
    return shape


def body(name, position, mass, inertia, shapes, orientation=None):
    b = {"name": name, "position": list(position), "mass": mass, "inertia": list(inertia)}
    if orientation is not None:
        b["orientation"] = orientation
    b["shapes"] = shapes
    return b


def scene(name, description, bodies, joints, steps=1000, dt=0.01, **extra):
    s = {"name": name, "description": description, "gravity": [0, 0, -9.81], "time_step": dt,
         "steps": steps}
    s.update(extra)
    s["bodies"] = bodies
    s["joints"] = joints
    return s


def chain(n):
    """docs/scene-specifications.md A6: capsuleX(r 0.01, hl 0.04, 0.1 kg) links released horizontal along +x."""
    inertia = [4.857143e-6, 7.557143e-5, 7.557143e-5]
    bodies, joints = [], []
    for i in range(n):
        bodies.append(body(f"link{i}", [(i + 0.5) * 0.1, 0.0, 0.0], 0.1, inertia,
                           [capsule_x(0.01, 0.04, filter=NO_COLLISION)]))
        joints.append({"name": f"j{i}", "type": "ball",
                       "body_a": "world" if i == 0 else f"link{i - 1}", "body_b": f"link{i}",
                       "anchor": [0.1 * i, 0.0, 0.0]})
    return scene(f"chain_{n}",
                 f"docs/scene-specifications.md A6 maximal: {n} capsule links (0.1 kg, 0.1 m) on ball joints, released "
                 "horizontal; gap 0 and energy constant in the model (10 s at dt 0.01).",
                 bodies, joints)


def pendulum():
    """docs/scene-specifications.md B8 maximal: 1 kg sphere bob (I 0.001) at (1, 0, 0), ball joint at the origin."""
    return scene("pendulum",
                 "docs/scene-specifications.md B8 maximal: a 1 kg bob 1 m from a ball joint at the origin, released "
                 "horizontal; period 2.369025573 s (elliptic integral).",
                 [body("bob", [1.0, 0.0, 0.0], 1.0, [0.001] * 3,
                       [{"type": "sphere", "radius": 0.05, "filter": NO_COLLISION}])],
                 [{"name": "pivot", "type": "ball", "body_b": "bob", "anchor": [0.0, 0.0, 0.0]}])


def double_pendulum():
    """docs/scene-specifications.md B9 release_horizontal, maximal: two 0.5 m capsules on hinges about world y."""
    inertia = [1.978082e-4, 0.01985808, 0.01985808]
    shape = [capsule_x(0.02, 0.23, filter=NO_COLLISION)]
    return scene("double_pendulum",
                 "docs/scene-specifications.md B9 release_horizontal, maximal: two 1 kg, 0.5 m capsules on hinges about "
                 "y, released horizontal (chaotic; energy constant, gaps 0).",
                 [body("link1", [0.25, 0.0, 0.0], 1.0, inertia, shape),
                  body("link2", [0.75, 0.0, 0.0], 1.0, inertia, shape)],
                 [{"name": "shoulder", "type": "hinge", "body_b": "link1",
                   "anchor": [0.0, 0.0, 0.0], "axis": [0, 1, 0], "normal": [1, 0, 0]},
                  {"name": "elbow", "type": "hinge", "body_a": "link1", "body_b": "link2",
                   "anchor": [0.5, 0.0, 0.0], "axis": [0, 1, 0], "normal": [1, 0, 0]}])


def four_bar(variant):
    """docs/scene-specifications.md B10: crank 0.4, coupler 1.2, rocker 0.8, ground 1.0 m; theta2 = 90 deg, open
    branch, at rest. `hinges`: four hinges about y (3 redundant rows); `rssr`: balls at A and B."""
    a_pt = [0.0, 0.0, 0.4]
    b_pt = [1.135384473, 0.0, 0.788461188]
    theta3 = math.radians(18.887902666)
    theta4 = math.radians(80.256912829)

    def link(name, length, com, angle):
        m = 1.0 * length  # 1 kg per metre, 0.04 x 0.04 m section
        ix = m * (0.04 ** 2 + 0.04 ** 2) / 12.0
        iyz = m * (length ** 2 + 0.04 ** 2) / 12.0
        return body(name, com, m, [ix, iyz, iyz],
                    [{"type": "box", "half_extents": [length / 2, 0.02, 0.02],
                      "filter": NO_COLLISION}], orientation=rot_y(-angle))

    bodies = [link("crank", 0.4, [0.0, 0.0, 0.2], math.pi / 2),
              link("coupler", 1.2, [0.567692237, 0.0, 0.594230594], theta3),
              link("rocker", 0.8, [1.067692237, 0.0, 0.394230594], theta4)]
    mid = "ball" if variant == "rssr" else "hinge"

    def joint(name, kind, a, b, anchor):
        j = {"name": name, "type": kind, "body_a": a, "body_b": b, "anchor": anchor}
        if kind == "hinge":
            j.update({"axis": [0, 1, 0], "normal": [1, 0, 0]})
        return j

    joints = [joint("O2", "hinge", "world", "crank", [0.0, 0.0, 0.0]),
              joint("A", mid, "crank", "coupler", a_pt),
              joint("B", mid, "coupler", "rocker", b_pt),
              joint("O4", "hinge", "rocker", "world", [1.0, 0.0, 0.0])]
    name = "four_bar" if variant == "hinges" else "four_bar_rssr"
    what = ("four hinges about y: 20 rows for 18 DOF and one mobility, three redundant (singular "
            "Delassus matrix)" if variant == "hinges" else
            "hinges at the ground, ball joints at A and B (no redundant rows)")
    return scene(name,
                 f"docs/scene-specifications.md B10 {variant}: crank-rocker four-bar (0.4/1.2/0.8/1.0 m) released at "
                 f"theta2 = 90 deg; {what}. theta4 follows Freudenstein's closed form.",
                 bodies, joints)


def rope_bridge():
    """Eight hinged planks between two world anchors, sagging in a V, with three boxes resting on
    them: joints and contacts in one island (issue 9: solved by every solver)."""
    planks, length, slope = 8, 0.4, math.acos(0.95)
    m_plank, half = 2.0, [length / 2, 0.25, 0.02]
    i_plank = [m_plank * (4 * (half[1] ** 2 + half[2] ** 2)) / 12,
               m_plank * (4 * (half[0] ** 2 + half[2] ** 2)) / 12,
               m_plank * (4 * (half[0] ** 2 + half[1] ** 2)) / 12]
    plank_filter = {"category": 2, "mask": 0xfffffffd}  # planks do not touch each other
    bodies, joints = [], []
    end = [0.0, 0.0, 0.0]
    for i in range(planks):
        angle = slope if i < planks // 2 else -slope  # R_y(a): x -> (cos a, 0, -sin a)
        d = [math.cos(angle), 0.0, -math.sin(angle)]
        com = [end[k] + 0.5 * length * d[k] for k in range(3)]
        bodies.append(body(f"plank{i}", com, m_plank, i_plank,
                           [{"type": "box", "half_extents": half, "material": "scene",
                             "filter": plank_filter}], orientation=rot_y(angle)))
        joints.append({"name": f"rope{i}", "type": "hinge",
                       "body_a": "world" if i == 0 else f"plank{i - 1}", "body_b": f"plank{i}",
                       "anchor": list(end), "axis": [0, 1, 0], "normal": [1, 0, 0]})
        end = [end[k] + length * d[k] for k in range(3)]
    joints.append({"name": f"rope{planks}", "type": "hinge", "body_a": f"plank{planks - 1}",
                   "body_b": "world", "anchor": list(end), "axis": [0, 1, 0],
                   "normal": [1, 0, 0]})
    h, m_box = 0.1, 1.0
    i_box = m_box * 8 * h * h / 12
    bottom_x = planks // 2 * length * math.cos(slope)
    bottom_z = -planks // 2 * length * math.sin(slope)
    for k, dx in enumerate([-0.45, 0.0, 0.45]):
        surface = bottom_z + abs(dx) * math.tan(slope) + half[2] / math.cos(slope)
        bodies.append(body(f"box{k}", [bottom_x + dx, 0.0, surface + h + 0.05], m_box,
                           [i_box] * 3, [{"type": "box", "half_extents": [h] * 3,
                                         "material": "scene"}]))
    return scene("rope_bridge",
                 "Eight 2 kg planks on hinges between two anchors (3 redundant rows), sagging in a "
                 "V, with three 1 kg boxes dropped on them (mu 0.6): joints and contacts in one "
                 "island, solved by every solver.",
                 bodies, joints, steps=500,
                 materials={"scene": {"friction": 0.6, "restitution": 0.0}})


def write(directory, s):
    path = os.path.join(directory, s["name"] + ".json")
    lines = []
    for key, value in s.items():
        if isinstance(value, list) and value and isinstance(value[0], dict):
            items = ",\n".join("    " + json.dumps(v) for v in value)
            lines.append(f'  "{key}": [\n{items}\n  ]')
        else:
            lines.append(f"  {json.dumps(key)}: {json.dumps(value)}")
    with open(path, "w") as f:
        f.write("{\n" + ",\n".join(lines) + "\n}\n")
    print("wrote", path)


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else "samples/scenes"
    for s in [pendulum(), double_pendulum(), chain(10), chain(50), four_bar("hinges"),
              four_bar("rssr"), rope_bridge()]:
        write(directory, s)


if __name__ == "__main__":
    main()
