"""coulomb.solve against analytic answers, and against `coulomb solve` (bit-identical)."""
import json
import subprocess

import numpy as np
import pytest

import coulomb

CONE_SOLVERS = ["pgs", "bgs", "nncg", "bgs_nncg", "ac_newton", "prox", "fb_newton", "staggered"]


def one_contact(mu):
    """A unit-mass point pressed into the ground (q_N = -1) and pushed sideways (q_T1 = 0.5).

    With W = I the answer is r_N = 1 (u_N = 0). The push needs r_T1 = -0.5 to stick; the cone
    allows |r_T| <= mu r_N, so mu = 1 sticks (u_T = 0) and mu = 0.3 slides: r_T1 = -0.3 and
    u_T1 = 0.2 (docs/solvers.md: the maximal-dissipation answer opposes the slip).
    """
    return coulomb.ContactProblem(np.eye(3), np.array([-1.0, 0.5, 0.0]), [mu])


@pytest.mark.parametrize("solver", CONE_SOLVERS)
@pytest.mark.parametrize("mu, r_t, u_t", [(1.0, -0.5, 0.0), (0.3, -0.3, 0.2)])
def test_stick_and_slip_of_one_contact(solver, mu, r_t, u_t):
    result = coulomb.solve(one_contact(mu), solver, tol=1e-12)
    assert result.converged, result.message
    assert result.solver == solver and result.attempts == [solver]
    np.testing.assert_allclose(result.impulses, [1.0, r_t, 0.0], atol=1e-9)
    np.testing.assert_allclose(result.velocities, [0.0, u_t, 0.0], atol=1e-9)
    assert result.residual <= 1e-12


def test_equality_and_bounded_rows():
    """u = W r + q with an equality row and a box row [-1, 1]. Unbounded, r = W^-1 (-q) =
    (-2/3, 7/3): r_1 leaves the box, so r_1 = 1 (its upper bound, u_1 = -2 <= 0) and the equality
    row gives 2 r_0 + 1 - 1 = 0, r_0 = 0."""
    W = np.array([[2.0, 1.0], [1.0, 2.0]])
    blocks = [coulomb.Block.equality(), coulomb.Block.bounded(-1.0, 1.0)]
    p = coulomb.ContactProblem(W, np.array([-1.0, -4.0]), blocks=blocks)
    for solver in ["ac_newton", "pgs", "auto"]:
        result = coulomb.solve(p, solver, tol=1e-12)
        assert result.converged, (solver, result.message)
        np.testing.assert_allclose(result.impulses, [0.0, 1.0], atol=1e-10)
        np.testing.assert_allclose(result.velocities, [0.0, -2.0], atol=1e-10)


def test_result_fields_agree_with_the_free_functions():
    p = coulomb.read_fc3d(str(pytest.importorskip("conftest").DATA_DIR / "fc3d" / "Rover1039.fc3d"))
    result = coulomb.solve(p, "ac_newton", record_history=True)
    assert result.status == "converged" and result.converged
    assert result.residual == coulomb.residual(p, result.impulses)
    assert result.absolute_residual == coulomb.residual(p, result.impulses, absolute=True)
    np.testing.assert_array_equal(result.velocities, coulomb.velocity(p, result.impulses))
    assert result.history.shape == (result.iterations, 3)
    assert result.history[-1, 2] == pytest.approx(result.residual, rel=1e-6)
    assert result.native_residual_name and result.seconds >= 0.0
    assert "ac_newton" in repr(result)


def test_a_start_at_the_answer_needs_no_iteration(fc3d_files):
    p = coulomb.read_fc3d(str(fc3d_files[0]))
    first = coulomb.solve(p, "ac_newton", tol=1e-10)
    again = coulomb.solve(p, "ac_newton", tol=1e-10, start=first.impulses)
    assert again.iterations == 0 and again.residual <= 1e-10
    cold = coulomb.solve(p, "ac_newton", tol=1e-10, use_warm_start=False)
    assert cold.iterations == first.iterations


def test_auto_reports_its_plan(fc3d_files):
    result = coulomb.solve(coulomb.read_fc3d(str(fc3d_files[0])), "auto")
    assert result.plan_reason.startswith("auto: ")
    assert result.attempts and result.attempts[0] in coulomb.solvers()
    chain = coulomb.solve(one_contact(0.3), "pgs,ac_newton")
    assert chain.attempts[0] == "pgs" and chain.converged


def test_solvers_lists_the_registry():
    table = coulomb.solvers()
    for name in CONE_SOLVERS + ["lemke", "ldlt", "auto"]:
        assert name in table and table[name]


@pytest.mark.parametrize("solver", ["ac_newton", "bgs", "auto"])
def test_same_answer_as_the_cli(cli, fc3d_files, solver):
    """Each result equals `coulomb solve`'s JSON line exactly: status, iterations, residual."""
    for path in fc3d_files:
        line = subprocess.run([cli, "solve", str(path), "--solver", solver], check=True,
                              capture_output=True, text=True).stdout.strip().splitlines()[-1]
        expected = json.loads(line)
        got = coulomb.solve(coulomb.read_fc3d(str(path)), solver)
        assert got.status == expected["status"], path.name
        assert got.iterations == expected["iterations"], path.name
        assert got.residual == expected["residual"], path.name
        if solver == "auto":
            assert got.attempts == expected["attempts"], path.name
