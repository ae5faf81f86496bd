#!/usr/bin/env python3
"""Copies the shared URDF corpus into tests/data/urdf for tests/engine/UrdfLoaderTest.cpp.

    python3 tests/data/urdf/copy_urdf_corpus.py $CORPUS/urdf tests/data/urdf

Per model: the URDF byte for byte, the <collision> meshes of the models listed in WITH_MESHES
(at the same relative paths; visual meshes are never read by the loader), and
reference_dynamics.json re-written compactly without samples[].link_world_poses (numbers are
re-printed by Python's shortest round-trip repr, i.e. the same doubles).
"""
import json
import os
import shutil
import sys
import xml.etree.ElementTree as ET

MODELS = ["pendulum", "acrobot", "double_pendulum", "cartpole", "r2d2", "kuka_iiwa", "bravo7",
          "solo12", "anymal_c", "pr2", "humanoid"]
WITH_MESHES = ["r2d2", "kuka_iiwa", "bravo7", "pr2"]  # ~1.3 MB; double_pendulum, solo12 skipped


def mesh_paths(model_dir, urdf):
    try:
        root = ET.parse(os.path.join(model_dir, urdf)).getroot()
    except ET.ParseError:
        return []
    paths = set()
    for collision in root.iter("collision"):
        for mesh in collision.iter("mesh"):
            name = mesh.get("filename")
            if name.startswith("package://"):
                paths.add(name[len("package://"):].lstrip("/").split("/", 1)[1])
            else:
                paths.add(os.path.join(os.path.dirname(urdf), name))
    return sorted(paths)


def main(shared, out):
    corpus = json.load(open(os.path.join(shared, "corpus.json")))
    for entry in corpus["models"]:
        model = entry["name"]
        if model not in MODELS:
            continue
        source_dir = os.path.join(shared, model)
        target_dir = os.path.join(out, model)
        os.makedirs(target_dir, exist_ok=True)
        urdf = os.path.relpath(entry["urdf"], model)
        shutil.copyfile(os.path.join(source_dir, urdf), os.path.join(target_dir, urdf))
        if model in WITH_MESHES:
            for path in mesh_paths(source_dir, urdf):
                os.makedirs(os.path.dirname(os.path.join(target_dir, path)), exist_ok=True)
                shutil.copyfile(os.path.join(source_dir, path), os.path.join(target_dir, path))
        reference = os.path.join(source_dir, "reference_dynamics.json")
        if os.path.exists(reference):
            data = json.load(open(reference))
            for sample in data["samples"]:
                sample.pop("link_world_poses", None)
            with open(os.path.join(target_dir, "reference_dynamics.json"), "w") as f:
                json.dump(data, f, separators=(",", ":"))
                f.write("\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
