#!/usr/bin/env python3
"""A parameter sweep on a Dask cluster: friction coefficient x solver on the sliding-box case.

The box of box_incline_B_slide (docs/conformance.md, A2) sits on a 20 degree incline. Analytic
answer: with mu < tan 20 it slides at a = g (sin 20 - mu cos 20); otherwise it sticks (a = 0).
Each task runs the scene once with one (mu, solver) pair and returns the measured acceleration,
its error against the analytic one, the solver's effort and the state hash; the table shows
which solvers keep the exact stick/slip threshold.

    PYTHONPATH=build/python python3 samples/python/sweep_dask.py              # a LocalCluster
    PYTHONPATH=build/python python3 samples/python/sweep_dask.py --scheduler tcp://host:8786

With --scheduler the same sweep runs unchanged on a cluster of many machines (each with the
coulomb module importable). The tasks are independent and deterministic: the results equal a
sequential run exactly (tests/python/test_samples.py checks the state hashes).
"""
import argparse
import math

import numpy as np

import coulomb

SCENE = "box_incline_B_slide"
INCLINE = math.radians(20.0)
GRAVITY = 9.81


def analytic_acceleration(mu):
    return max(0.0, GRAVITY * (math.sin(INCLINE) - mu * math.cos(INCLINE)))


def slide(mu, solver, steps):
    """One run: the box's acceleration along the incline from its speed at the end (it starts at
    rest and slides at a constant rate)."""
    result = coulomb.run(SCENE, mu=mu, solver=solver, steps=steps)
    box = result.bodies.index("box")
    acceleration = float(np.linalg.norm(result.linear_velocities[box])) / result.time
    return {
        "mu": mu, "solver": solver, "acceleration": acceleration,
        "error": abs(acceleration - analytic_acceleration(mu)),
        "iterations": result.iterations / max(1, result.island_solves),
        "max_residual": result.max_residual, "state_hash": result.state_hash,
        "ms_per_step": 1e3 * result.seconds / result.steps,
    }


def sweep(client, mus, solvers, steps):
    """Every (mu, solver) pair as one task on the cluster; results in input order."""
    pairs = [(mu, solver) for mu in mus for solver in solvers]
    futures = client.map(slide, [m for m, _ in pairs], [s for _, s in pairs],
                         [steps] * len(pairs), pure=False)
    return client.gather(futures)


def local_cluster(workers):
    """Worker processes on the loopback interface only, no dashboard."""
    from dask.distributed import LocalCluster
    return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                        host="127.0.0.1", dashboard_address=None)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scheduler", help="address of a running Dask scheduler")
    parser.add_argument("--workers", type=int, default=2, help="local worker processes")
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--solvers", default="auto,pgs!,bgs!,ac_newton!")
    args = parser.parse_args()
    from dask.distributed import Client

    mus = [round(float(m), 3) for m in np.linspace(0.05, 0.65, 13)]
    solvers = args.solvers.split(",")
    cluster = None if args.scheduler else local_cluster(args.workers)
    with Client(args.scheduler or cluster) as client:
        rows = sweep(client, mus, solvers, args.steps)
    if cluster is not None:
        cluster.close()
    print(f"tan 20 deg = {math.tan(INCLINE):.4f}: below it the box slides, above it sticks")
    print("| mu | a exact [m/s^2] | " + " | ".join(f"{s} error" for s in solvers) + " |")
    print("|---|---|" + "---|" * len(solvers))
    for mu in mus:
        errors = [r["error"] for r in rows if r["mu"] == mu]
        print(f"| {mu} | {analytic_acceleration(mu):.6f} | "
              + " | ".join(f"{e:.1e}" for e in errors) + " |")


if __name__ == "__main__":
    main()
