#!/usr/bin/env python3
"""Writes a scene of spheres poured into a box (JSON for `coulomb run`): the dense, redundant,
degenerate contact problems of docs/solvers.md, "Sphere packings". Standard library only.

    bench/make_sphere_packing.py 150 1 packing.json   # spheres, seed, output
    bench/make_sphere_packing.py 10000 1 spheres.json 2.0   # [half width of the box, m: 0.35]
    build/bin/coulomb run packing.json --steps 101 --capture captured --capture-step 100
"""
import json
import random
import sys


def main() -> int:
    if len(sys.argv) not in (4, 5):
        print(__doc__)
        return 2
    count, seed, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    random.seed(seed)
    radius = 0.05  # sphere radius [m]
    half = float(sys.argv[4]) if len(sys.argv) == 5 else 0.35  # inner half width of the box [m]
    bodies = [{"name": "ground", "type": "static", "shapes": [{"type": "plane", "material": "m"}]}]
    walls = [("wall_x_plus", [half + 0.05, 0, 0.6], [0.05, half + 0.1, 0.6]),
             ("wall_x_minus", [-half - 0.05, 0, 0.6], [0.05, half + 0.1, 0.6]),
             ("wall_y_plus", [0, half + 0.05, 0.6], [half + 0.1, 0.05, 0.6]),
             ("wall_y_minus", [0, -half - 0.05, 0.6], [half + 0.1, 0.05, 0.6])]
    for name, position, extents in walls:
        bodies.append({"name": name, "type": "static", "position": position,
                       "shapes": [{"type": "box", "half_extents": extents, "material": "m"}]})
    per_row = int(2 * half / (2.2 * radius))
    inertia = 0.4 * radius * radius  # solid sphere of 1 kg
    for i in range(count):
        layer, cell = divmod(i, per_row * per_row)
        row, column = divmod(cell, per_row)
        jitter = lambda: random.uniform(-0.01, 0.01)
        position = [-half + 1.1 * radius + column * 2.2 * radius + jitter(),
                    -half + 1.1 * radius + row * 2.2 * radius + jitter(),
                    radius + 0.01 + layer * 2.3 * radius]
        bodies.append({"name": f"sphere{i}", "position": position, "mass": 1.0,
                       "inertia": [inertia] * 3,
                       "linear_velocity": [random.uniform(-0.2, 0.2), random.uniform(-0.2, 0.2), 0.0],
                       "shapes": [{"type": "sphere", "radius": radius, "material": "m"}]})
    scene = {"name": "sphere_packing", "description": f"{count} spheres poured into a box (seed {seed})",
             "time_step": 0.01, "steps": 200,
             "materials": {"m": {"friction": 0.5, "restitution": 0.0}}, "bodies": bodies}
    with open(out, "w", encoding="utf-8") as f:
        json.dump(scene, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
