#!/usr/bin/env python3
"""Every solver on frictional-contact problems: status, iterations, residual and time side by side.

    PYTHONPATH=build/python python3 samples/python/compare_solvers.py [FC3D_FILES...]

Default: the Siconos problems of tests/data/fc3d, plus the 10-box tower's island at step 300
captured from a running world (a hard one: many sweeps stall where Newton converges).
"""
import pathlib
import sys

import coulomb

SOLVERS = ["pgs", "bgs", "nncg", "ac_newton", "prox", "fb_newton", "staggered", "lemke", "auto"]


def problems(paths):
    for path in paths:
        yield coulomb.read_fc3d(str(path))
    if not paths or "--with-tower" in sys.argv:
        yield coulomb.capture_problems("box_stack_10", at_step=300)[0].problem


def main():
    root = pathlib.Path(__file__).resolve().parents[2]
    paths = [pathlib.Path(a) for a in sys.argv[1:] if not a.startswith("--")]
    if not paths:
        paths = sorted((root / "tests" / "data" / "fc3d").glob("*.fc3d"))
    print("| problem | contacts | solver | status | iterations | e_rel | ms |")
    print("|---|---|---|---|---|---|---|")
    for problem in problems(paths):
        for solver in SOLVERS:
            r = coulomb.solve(problem, solver, tol=1e-8, time_limit=5.0)
            print(f"| {problem.name} | {problem.contact_count} | {solver} | {r.status} | "
                  f"{r.iterations} | {r.residual:.1e} | {1e3 * r.seconds:.3f} |")


if __name__ == "__main__":
    main()
