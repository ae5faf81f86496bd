"""Bad input gives a Python exception with the engine's message, never a crash or a NaN."""
import numpy as np
import pytest

import coulomb
from conftest import SOURCE_DIR

ALL_SOLVERS = sorted(set(coulomb.solvers()) - {"auto"})


@pytest.mark.parametrize("W, q, mu, message", [
    (np.eye(3)[:, :2], np.zeros(3), [0.5], r"W: expected shape \(3, 3\), got \(3, 2\)"),
    (np.eye(3), np.zeros((3, 1)), [0.5], r"q: expected shape \(n,\), got \(3, 1\)"),
    (np.eye(3), np.zeros(3), [0.5, 0.5], r"mu: expected shape \(1,\), got \(2,\)"),
    (np.eye(4), np.zeros(4), [0.5], "3 unknowns per contact"),
    (np.eye(3) * 1j, np.zeros(3), [0.5], "W: expected a float array.*complex"),
    (np.eye(3), np.array(["a", "b", "c"]), [0.5], "q: expected a float array"),
    (np.eye(3), None, [0.5], "q: expected .* got None"),
    ((np.array([0, 5]), np.array([0, 0]), np.ones(2)), np.zeros(3), [0.5], "outside the 3 x 3"),
    ((np.array([0.5]), np.array([0]), np.ones(1)), np.zeros(3), [0.5], "W rows: expected an integer"),
])
def test_wrong_shapes_and_dtypes_are_value_errors(W, q, mu, message):
    with pytest.raises(ValueError, match=message):
        coulomb.ContactProblem(W, q, mu)


@pytest.mark.parametrize("W, q, mu, message", [
    (np.diag([1.0, np.nan, 1.0]), np.zeros(3), [0.5], "not finite"),
    (np.eye(3), np.array([np.inf, 0, 0]), [0.5], "not finite"),
    (np.eye(3), np.zeros(3), [-0.5], "mu"),
    (-np.eye(3), np.zeros(3), [0.5], "diagonal"),
])
def test_invalid_problems_are_engine_errors(W, q, mu, message):
    with pytest.raises(coulomb.Error, match=message) as error:
        coulomb.ContactProblem(W, q, mu)
    assert str(error.value).startswith("ContactProblem: ")
    assert isinstance(error.value, ValueError)


def test_mu_and_blocks_are_exclusive():
    with pytest.raises(ValueError, match="either mu"):
        coulomb.ContactProblem(np.eye(3), np.zeros(3))
    with pytest.raises(ValueError, match="add up to 1 unknowns, q has 3"):
        coulomb.ContactProblem(np.eye(3), np.zeros(3), blocks=[coulomb.Block.equality()])


def test_bad_solver_and_options():
    p = coulomb.ContactProblem(np.eye(3), np.array([-1.0, 0, 0]), [0.5])
    with pytest.raises(coulomb.Error, match="unknown solver 'newton'; known: .*ac_newton"):
        coulomb.solve(p, "newton")
    with pytest.raises(coulomb.Error, match="unknown solver 'nope'"):
        coulomb.solve(p, "pgs,nope")
    with pytest.raises(coulomb.Error, match="tolerance"):
        coulomb.solve(p, "pgs", tol=-1.0)
    with pytest.raises(ValueError, match=r"start: expected shape \(3,\)"):
        coulomb.solve(p, "pgs", start=np.zeros(2))


def test_fc3d_errors_name_the_file_and_line(tmp_path):
    with pytest.raises(FileNotFoundError, match="missing.fc3d"):
        coulomb.read_fc3d(str(tmp_path / "missing.fc3d"))
    with pytest.raises(coulomb.Error, match=r"text.fc3d:2: "):
        coulomb.parse_fc3d("fc3d-text 1\nnonsense\n", source="text.fc3d")
    mixed = coulomb.ContactProblem(np.eye(1), np.zeros(1), blocks=[coulomb.Block.equality()])
    with pytest.raises(coulomb.Error):
        mixed.to_fc3d()


def test_scene_errors_name_the_scene(tmp_path):
    with pytest.raises(coulomb.Error, match="no_such_scene"):
        coulomb.capture_problems("no_such_scene", steps=1)
    bad = tmp_path / "bad.json"
    bad.write_text('{"bodies": [{"mass": -1, "inertia": [1, 1, 1], "shapes": [{"type": "sphere", "radius": 0.1}]}]}')
    with pytest.raises(coulomb.Error, match=r"bad.json: bodies\[0\].mass"):
        coulomb.capture_problems(str(bad), steps=1)


def assert_finite_answers(problem):
    for solver in ALL_SOLVERS:
        result = coulomb.solve(problem, solver, max_iterations=50, time_limit=1.0)
        assert np.all(np.isfinite(result.impulses)), solver
        assert np.all(np.isfinite(result.velocities)), solver


def test_fuzz_regressions_replayed():
    """The fuzzers' regression inputs (fuzz/regressions) through the Python entry points."""
    regressions = SOURCE_DIR / "fuzz" / "regressions"
    for path in sorted((regressions / "fc3d").iterdir()):
        try:
            problem = coulomb.parse_fc3d(path.read_text(errors="replace"), source=path.name)
        except coulomb.Error:
            continue
        assert_finite_answers(problem)
    for path in sorted((regressions / "scene").iterdir()):
        try:
            coulomb.capture_problems(str(path), steps=3)
        except coulomb.Error as error:
            assert path.name in str(error)
    for path in sorted((regressions / "urdf").iterdir()):
        world = coulomb.World()
        try:
            world.load_urdf(str(path))
        except coulomb.Error:
            continue
        world.step(3)
        assert np.all(np.isfinite(world.positions()))


def test_random_problems_never_crash():
    """Small problems with extreme and non-finite entries: an exception at construction, or a
    finite answer from every solver."""
    rng = np.random.default_rng(2026)
    specials = np.array([0.0, -0.0, 1e-300, 1e300, np.inf, -np.inf, np.nan, 1e-12, -1.0])
    for _ in range(60):
        contacts = int(rng.integers(1, 4))
        n = 3 * contacts
        A = rng.normal(size=(n, n))
        W = A @ A.T * rng.choice([1e-8, 1.0, 1e8])
        q = rng.normal(size=n)
        mu = rng.uniform(0, 2, size=contacts)
        if rng.random() < 0.5:
            W[rng.integers(n), rng.integers(n)] = rng.choice(specials)
        if rng.random() < 0.3:
            q[rng.integers(n)] = rng.choice(specials)
        try:
            problem = coulomb.ContactProblem(W, q, mu)
        except ValueError:
            continue
        assert_finite_answers(problem)
