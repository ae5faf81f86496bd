"""coulomb.capture_problems: island problems of a running world, as the solvers see them."""
import json
import subprocess

import numpy as np

import coulomb
from conftest import DATA_DIR


def test_box_on_plane_problem_carries_the_weight():
    """A 1 kg box resting on the ground (samples/scenes/box_on_plane.json, dt = 0.01): one island
    of 4 contacts whose normal impulses add up to m g dt = 0.0981 N s."""
    captured = coulomb.capture_problems("box_on_plane", at_step=10)
    assert len(captured) == 1
    c = captured[0]
    assert c.step == 10 and c.island == 0
    assert c.problem.contact_count == 4 and c.problem.name == "box_on_plane_step10_island0"
    np.testing.assert_array_equal(c.problem.mu, [0.5] * 4)
    assert c.problem.warm_start is not None  # the world's warm start is part of the problem
    result = coulomb.solve(c.problem, "ac_newton", tol=1e-12)
    assert result.converged
    r = result.impulses.reshape(-1, 3)
    # The weight's impulse, plus the small bias that holds the resting depth (1.6e-9 N s here).
    assert abs(r[:, 0].sum() - 1.0 * 9.81 * 0.01) < 1e-8
    # Four contacts are statically indeterminate: friction may hold a self-balancing twist, but
    # no net tangential impulse (nothing pushes the box sideways), and it stays inside the cone.
    assert np.abs(r[:, 1:].sum(axis=0)).max() < 1e-12
    assert np.all(np.hypot(r[:, 1], r[:, 2]) <= 0.5 * r[:, 0])


def test_every_step_is_captured_in_order():
    captured = coulomb.capture_problems("box_on_plane", steps=5)
    assert [c.step for c in captured] == sorted(c.step for c in captured)
    assert {c.step for c in captured} <= set(range(5)) and captured[-1].step == 4


def test_same_problem_as_the_cli_capture(cli, tmp_path):
    """`coulomb run --capture` writes the same problem, bit for bit."""
    subprocess.run([cli, "run", "box_on_plane", "--steps", "11", "--capture", str(tmp_path),
                    "--capture-step", "10"], check=True, capture_output=True)
    written = (tmp_path / "box_on_plane_step10_island0.fc3d").read_text()
    captured = coulomb.capture_problems("box_on_plane", at_step=10)[0].problem
    assert captured.to_fc3d(family="coulomb-capture") == written


def test_a_scene_file_with_joint_rows_keeps_every_row_kind(tmp_path):
    """Rows without an fc3d form (a pendulum's joint rows) are kept as blocks."""
    scene = {
        "name": "pendulum", "time_step": 0.01, "steps": 3,
        "bodies": [{"name": "bob", "position": [1.0, 0.0, 0.0], "mass": 1.0,
                    "inertia": [0.004, 0.004, 0.004],
                    "shapes": [{"type": "sphere", "radius": 0.1}]}],
        "joints": [{"type": "ball", "body_b": "bob", "anchor": [0.0, 0.0, 0.0]}],
    }
    path = tmp_path / "pendulum.json"
    path.write_text(json.dumps(scene))
    captured = coulomb.capture_problems(str(path))
    assert len(captured) == 3
    kinds = {b.kind for b in captured[0].problem.blocks}
    assert kinds == {"equality"}
    assert coulomb.solve(captured[0].problem, "auto").converged


def test_builtin_scene_names():
    names = coulomb.scenes()
    assert "box_on_plane" in names and names == sorted(names)
    assert (DATA_DIR / "fc3d").is_dir()
