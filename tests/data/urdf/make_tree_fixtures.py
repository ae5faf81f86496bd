#!/usr/bin/env python3
"""Write tests/data/urdf/<model>/tree.json from a shared URDF and its reference_dynamics.json.

Usage: make_tree_fixtures.py SHARED_URDF_DIR OUT_DIR model...
The fixture is the model exactly as the DART reference built it (see the shared README): links
in a parent-before-child order (depth first from the root, children in document order), the
non-world root welded to the world at the identity, joint origins (xyz, rpy -> quaternion
w x y z, R = Rz(yaw) Ry(pitch) Rx(roll)) and unit axes from the URDF, and each link's mass, COM
and inertia about the COM in the link frame taken from the reference's `dart_links` (inertial
rpy already applied there). Joint types: revolute, continuous, prismatic, fixed.
"""
import json
import math
import os
import sys
import xml.etree.ElementTree as ET


def quaternion_from_rpy(r, p, y):
    cr, sr = math.cos(r / 2), math.sin(r / 2)
    cp, sp = math.cos(p / 2), math.sin(p / 2)
    cy, sy = math.cos(y / 2), math.sin(y / 2)
    return [cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy]


def numbers(text, default):
    return [float(v) for v in text.split()] if text else default


def convert(shared, out, model):
    ref = json.load(open(os.path.join(shared, model, "reference_dynamics.json")))
    root = ET.parse(os.path.join(shared, model, ref["urdf"])).getroot()
    joints = []
    for j in root.findall("joint"):
        origin = j.find("origin")
        xyz = numbers(origin.get("xyz") if origin is not None else None, [0.0, 0.0, 0.0])
        rpy = numbers(origin.get("rpy") if origin is not None else None, [0.0, 0.0, 0.0])
        axis_el = j.find("axis")
        axis = numbers(axis_el.get("xyz") if axis_el is not None else None, [1.0, 0.0, 0.0])
        norm = math.sqrt(sum(a * a for a in axis))
        joints.append({"name": j.get("name"), "type": j.get("type"),
                       "parent": j.find("parent").get("link"),
                       "child": j.find("child").get("link"), "xyz": xyz,
                       "quaternion_wxyz": quaternion_from_rpy(*rpy),
                       "axis": [a / norm for a in axis]})
    children = {j["child"] for j in joints}
    roots = [l.get("name") for l in root.findall("link") if l.get("name") not in children]
    assert len(roots) == 1, roots
    links, order = [], {}

    def add(name, parent, joint):
        if name != "world":
            order[name] = len(links)
            dart = ref["dart_links"][name]
            links.append({"name": name, "parent": order.get(parent, -1), "joint": joint,
                          "mass": dart["mass"], "com": dart["com"],
                          "inertia_about_com": dart["inertia_about_com"]})
        for j in joints:
            if j["parent"] == name:
                add(j["child"], name, j)

    weld = {"name": "world_weld", "type": "fixed", "xyz": [0.0, 0.0, 0.0],
            "quaternion_wxyz": [1.0, 0.0, 0.0, 0.0], "axis": [1.0, 0.0, 0.0]}
    add(roots[0], None, None if roots[0] == "world" else weld)
    for link in links:
        for key in ("parent", "child"):
            link["joint"].pop(key, None)
    samples = [{k: s[k] for k in ("q", "qdot", "tau", "qddot", "mass_matrix", "bias_forces")}
               for s in ref["samples"]]
    os.makedirs(os.path.join(out, model), exist_ok=True)
    with open(os.path.join(out, model, "tree.json"), "w") as f:
        json.dump({"model": model, "urdf": ref["urdf"], "gravity": ref["gravity"],
                   "dof_names": ref["dof_names"], "links": links, "samples": samples}, f, indent=1)


if __name__ == "__main__":
    for m in sys.argv[3:]:
        convert(sys.argv[1], sys.argv[2], m)
