"""Coulomb: rigid-body contact with exact Coulomb friction (docs/python.md).

Contact problems and their solvers:

    import numpy as np, coulomb
    problem = coulomb.ContactProblem(W, q, mu)          # W dense, scipy.sparse or (rows, cols, values)
    result = coulomb.solve(problem, "ac_newton", tol=1e-10)
    result.impulses, result.status, result.iterations, result.residual

Errors from the engine are coulomb.Error (a ValueError) with the engine's message; a wrong array
shape or dtype is a ValueError naming the expected shape.
"""
from ._coulomb import (  # noqa: F401
    Block,
    CapturedProblem,
    ConformanceResult,
    ContactProblem,
    Error,
    Robot,
    RunResult,
    SolveResult,
    World,
    capture_problems,
    conformance_cases,
    parse_fc3d,
    read_fc3d,
    residual,
    run,
    run_batch,
    run_conformance,
    scenes,
    solve,
    solvers,
    velocity,
    write_fc3d,
)

__all__ = [
    "Block", "CapturedProblem", "ConformanceResult", "ContactProblem", "Error", "Robot", "RunResult",
    "SolveResult", "capture_problems", "conformance_cases", "parse_fc3d", "read_fc3d", "residual",
    "run", "run_batch", "run_conformance", "scenes", "solve", "solvers", "velocity", "World",
    "write_fc3d",
]
