#!/usr/bin/env python3
"""What a solve costs from Python beyond the solver itself (docs/python.md "Cost").

For each problem: the median wall time of coulomb.solve(...) measured around the call, the median
of the solver's own clock (SolveResult.seconds, taken inside the C++ solve), and their difference:
the binding's overhead (argument checks, the problem's copy, the registry, the result object).
Also the cost of reading W, q and the impulses back as arrays. Usage:
    PYTHONPATH=build/python python3 bench/python/solve_overhead.py [FC3D_FILES...]
(default: the fixtures of tests/data/fc3d).
"""
import pathlib
import statistics
import sys
import time

import coulomb


def median_us(samples):
    return 1e6 * statistics.median(samples)


def measure(problem, solver, repeats):
    wall, inside = [], []
    for _ in range(repeats):
        start = time.perf_counter()
        result = coulomb.solve(problem, solver)
        wall.append(time.perf_counter() - start)
        inside.append(result.seconds)
    return result, median_us(wall), median_us(inside)


def main():
    root = pathlib.Path(__file__).resolve().parents[2]
    files = [pathlib.Path(a) for a in sys.argv[1:]] or sorted((root / "tests/data/fc3d").glob("*.fc3d"))
    print("| problem | contacts | solver | iterations | residual | wall [us] | solver [us] | overhead [us] |")
    print("|---|---|---|---|---|---|---|---|")
    for path in files:
        problem = coulomb.read_fc3d(str(path))
        for solver in ["ac_newton", "auto"]:
            result, wall, inside = measure(problem, solver, 200)
            print(f"| {problem.name} | {problem.contact_count} | {solver} | {result.iterations} | "
                  f"{result.residual:.1e} | {wall:.1f} | {inside:.1f} | {wall - inside:.1f} |")
    problem = coulomb.read_fc3d(str(files[0]))
    reads = []
    for _ in range(2000):
        start = time.perf_counter()
        problem.q, problem.W_triplets()  # noqa: B018 (what is timed is the conversion)
        reads.append(time.perf_counter() - start)
    print(f"\nreading q and W's triplets of {problem.name} ({problem.size} unknowns): "
          f"{median_us(reads):.1f} us")


if __name__ == "__main__":
    main()
