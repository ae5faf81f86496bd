"""coulomb.run, run_batch and the conformance cases: the same worlds as the CLI, bit for bit."""
import json
import math
import pickle
import re
import subprocess

import numpy as np
import pytest

import coulomb

CASES = ["box_incline/B_slide", "sphere_slide", "mass_ratio/100kg_on_0.1kg"]


def cli_hash(cli, *args):
    out = subprocess.run([cli, "run", *args], check=True, capture_output=True, text=True).stdout
    return re.search(r"state hash ([0-9a-f]{16})", out).group(1)


@pytest.mark.parametrize("scene", ["box_incline_B_slide", "chain_10", "newton_cradle"])
def test_run_matches_coulomb_run(cli, scene):
    result = coulomb.run(scene, steps=150)
    assert result.state_hash_hex == cli_hash(cli, scene, "--steps", "150")
    assert result.steps == 150 and result.time == pytest.approx(150 * result.time_step)
    assert result.positions.shape == (len(result.bodies), 3)
    assert result.quaternions.shape == (len(result.bodies), 4)
    np.testing.assert_allclose(np.linalg.norm(result.quaternions, axis=1), 1.0, atol=1e-12)


def test_overrides_match_the_cli(cli):
    result = coulomb.run("box_incline_B_slide", steps=80, solver="pgs!", mu=0.5, dt=0.005)
    assert result.state_hash_hex == cli_hash(cli, "box_incline_B_slide", "--steps", "80",
                                             "--solver", "pgs!", "--mu", "0.5", "--dt", "0.005")


def test_joint_energy_override_keeps_a_chain_s_energy(cli):
    """A6 chain_10 at dt 0.01 (S = m g L N^2 / 2 = 4.905 J released): with `exact` (the symmetric
    step, docs/tuning.md) E ends where it started; without a target the whips lose part of it.
    The CLI's --joint-energy gives the same run."""
    released = 0.1 * 9.81 * 0.1 * 10 * 10 / 2
    exact = coulomb.run("chain_10", steps=300, joint_energy="exact")
    plain = coulomb.run("chain_10", steps=300, joint_energy="none")
    assert abs(exact.energy_end - exact.energy_start) < 1e-6 * released
    assert plain.energy_end - plain.energy_start < -0.05 * released
    assert exact.max_joint_gap < 1e-6
    assert exact.state_hash_hex == cli_hash(cli, "chain_10", "--steps", "300", "--joint-energy",
                                            "exact")
    assert exact.state_hash_hex != plain.state_hash_hex


def test_friction_threshold_of_the_incline():
    """20 degree incline: mu = 0.30 < tan 20 = 0.364 slides at g (sin 20 - mu cos 20); mu = 0.45
    sticks."""
    a_exact = 9.81 * (math.sin(math.radians(20)) - 0.30 * math.cos(math.radians(20)))
    slides = coulomb.run("box_incline_B_slide", mu=0.30, steps=100)
    box = slides.bodies.index("box")
    assert np.linalg.norm(slides.linear_velocities[box]) / slides.time == pytest.approx(
        a_exact, rel=1e-6)
    sticks = coulomb.run("box_incline_B_slide", mu=0.45, steps=100)
    assert np.linalg.norm(sticks.linear_velocities[box]) < 1e-6


def test_a_scene_dict_is_the_same_scene_as_its_file(tmp_path):
    scene = {
        "name": "drop", "time_step": 0.01, "steps": 60,
        "materials": {"m": {"friction": 0.5, "restitution": 0.0}},
        "bodies": [
            {"name": "ground", "type": "static", "shapes": [{"type": "plane", "material": "m"}]},
            {"name": "ball", "position": [0.0, 0.0, 0.5], "mass": 1.0,
             "inertia": [0.004, 0.004, 0.004],
             "shapes": [{"type": "sphere", "radius": 0.1, "material": "m"}]},
        ],
    }
    path = tmp_path / "drop.json"
    path.write_text(json.dumps(scene))
    from_dict, from_file = coulomb.run(scene), coulomb.run(str(path))
    assert from_dict.state_hash == from_file.state_hash and from_dict.steps == 60
    assert from_dict.bodies == ["ground", "ball"]
    assert from_dict.positions[1, 2] == pytest.approx(0.1, abs=1e-6)  # resting on the ground


def test_run_batch_equals_one_by_one():
    scenes = ["box_incline_B_slide", "chain_10", "box_on_plane", "newton_cradle", "sphere_slide"]
    alone = [coulomb.run(s, steps=100) for s in scenes]
    for threads in [1, 2, 0, 16]:
        batch = coulomb.run_batch(scenes, threads=threads, steps=100)
        assert [r.state_hash for r in batch] == [r.state_hash for r in alone], threads
        for a, b in zip(alone, batch):
            np.testing.assert_array_equal(a.positions, b.positions)


def test_run_batch_errors():
    with pytest.raises(ValueError, match="threads"):
        coulomb.run_batch(["box_on_plane"], threads=-1)
    with pytest.raises(coulomb.Error, match="no_such_scene"):
        coulomb.run_batch(["box_on_plane", "no_such_scene"], steps=1)
    assert coulomb.run_batch([], threads=2) == []
    with pytest.raises(ValueError, match="a list of scenes or worlds, got one scene"):
        coulomb.run_batch("box_on_plane", steps=1)


def test_run_errors():
    with pytest.raises(ValueError, match="scene: expected a built-in name, a file path or a dict"):
        coulomb.run(42)
    with pytest.raises(coulomb.Error, match="solver override"):
        coulomb.run("box_on_plane", solver="pgs!,bgs")
    with pytest.raises(coulomb.Error, match="time step override"):
        coulomb.run("box_on_plane", dt=-0.01)
    with pytest.raises(coulomb.Error, match="friction override"):
        coulomb.run("box_on_plane", mu=float("nan"))
    with pytest.raises(coulomb.Error, match="joint energy override: must be none, modified or exact"):
        coulomb.run("chain_10", joint_energy="exactly")
    with pytest.raises(coulomb.Error, match=r"<scene dict 'x'>: bodies\[0\]"):
        coulomb.run({"name": "x", "bodies": [{"mass": 1.0}]})


def test_run_result_pickles():
    result = coulomb.run("box_on_plane", steps=10)
    back = pickle.loads(pickle.dumps(result))
    assert back.state_hash == result.state_hash and back.bodies == result.bodies
    np.testing.assert_array_equal(back.quaternions, result.quaternions)
    assert back.to_dict().keys() == result.to_dict().keys()


def test_conformance_cases_are_listed():
    names = [c["name"] for c in coulomb.conformance_cases()]
    assert set(CASES) <= set(names)
    with pytest.raises(coulomb.Error, match="no conformance case"):
        coulomb.run_conformance("box_incline_B")


def test_conformance_matches_the_cli(cli):
    """Three cases from Python, exactly as `coulomb conformance` runs them: verdict, figures
    and state hash."""
    out = subprocess.run([cli, "conformance", "--cases", ",".join(CASES), "--solvers", "auto"],
                         check=True, capture_output=True, text=True).stdout
    for case in CASES:
        line = next(l for l in out.splitlines() if l.startswith(case + "  auto  "))
        result = coulomb.run_conformance(case, "auto")
        assert result.passed and "  pass  " in line
        assert f"state {result.state_hash_hex}" in line
        assert f"[{result.detail}]" in line
        assert f"fallbacks {result.fallbacks}" in line
