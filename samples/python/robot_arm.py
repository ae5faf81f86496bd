#!/usr/bin/env python3
"""A KUKA iiwa arm from its URDF: joint motors driven from Python, joint state read back.

    PYTHONPATH=build/python python3 samples/python/robot_arm.py [--steps N]

The arm's base is fixed on a floor, position motors hold every joint (hold=True); each second
the script sends new targets and prints how close the joints got and how still they are.
"""
import argparse
import pathlib

import numpy as np

import coulomb

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100, help="steps per target (dt = 0.01 s)")
    args = parser.parse_args()
    world = coulomb.World({"name": "floor", "materials": {"floor": {"friction": 0.8}},
                           "bodies": [{"name": "floor", "type": "static",
                                       "shapes": [{"type": "plane", "material": "floor"}]}]})
    arm = world.load_urdf(str(ROOT / "samples/robots/kuka_iiwa/model.urdf"), hold=True,
                          on_floor=0.0)
    print(f"{len(arm.joint_names)} joints: {', '.join(arm.joint_names)}")
    for targets in ([0.3, 0.5, 0.0, -1.0, 0.0, 0.5, 0.0], [-0.3, 0.8, 0.2, -1.5, 0.3, 0.2, 0.1]):
        for joint, target in zip(arm.joint_names, targets):
            arm.set_motor_target(joint, target)
        world.step(args.steps)
        error = np.abs(arm.q - targets).max()
        print(f"t = {world.time:.2f} s: largest joint error {error:.2e} rad, "
              f"largest joint speed {np.abs(arm.qd).max():.2e} rad/s")


if __name__ == "__main__":
    main()
