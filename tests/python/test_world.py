"""coulomb.World and coulomb.Robot: the same world as the CLI's, state arrays, bodies, forces,
contacts, snapshots and URDF robots, each against an analytic answer or an invariant."""
import math

import numpy as np
import pytest

import coulomb
from conftest import DATA_DIR

PENDULUM = DATA_DIR / "urdf" / "pendulum" / "Pendulum.urdf"


def test_world_steps_like_run():
    world = coulomb.World("box_incline_B_slide")
    for _ in range(50):
        world.step()
    world.step(100)
    assert world.step_count == 150 and world.time == pytest.approx(1.5)
    assert world.state_hash == coulomb.run("box_incline_B_slide", steps=150).state_hash
    assert world.state_hash_hex == coulomb.run("box_incline_B_slide", steps=150).state_hash_hex


def test_state_arrays_follow_the_body_order():
    world = coulomb.World("box_on_plane")
    world.step(20)
    assert world.body_names == ["ground", "box"] and len(world.bodies) == world.body_count == 2
    assert world.positions().shape == (2, 3) and world.quaternions().shape == (2, 4)
    assert world.linear_velocities().shape == world.angular_velocities().shape == (2, 3)
    assert world.positions()[1, 2] == pytest.approx(0.1, abs=1e-9)  # the 0.2 m box at rest
    np.testing.assert_allclose(world.quaternions()[1], [1, 0, 0, 0], atol=1e-12)


def test_added_ball_lands_and_handles_go_stale():
    world = coulomb.World("box_on_plane")
    ball = world.add_body({"name": "ball", "position": [1.0, 0.0, 0.5], "mass": 2.0,
                           "inertia": [0.008] * 3,
                           "shapes": [{"type": "sphere", "radius": 0.1, "material": "rubber"}]},
                          materials={"rubber": {"friction": 0.9, "restitution": 0.0}})
    assert world.find_body("ball") == ball and world.find_body("nothing") is None
    world.step(150)
    k = world.bodies.index(ball)
    assert world.positions()[k, 2] == pytest.approx(0.1, abs=1e-6)  # resting on its radius
    world.remove_body(ball)
    assert ball not in world.bodies and world.body_count == 2
    with pytest.raises(coulomb.Error, match="stale"):
        world.set_velocity(ball, [0, 0, 0], [0, 0, 0])
    with pytest.raises(ValueError, match="not JSON compliant"):  # NaN has no JSON form
        world.add_body({"name": "nan", "position": [float("nan"), 0, 0], "mass": 1.0,
                        "inertia": [1, 1, 1], "shapes": [{"type": "sphere", "radius": 0.1}]})
    with pytest.raises(coulomb.Error, match=r"bodies\[0\]"):
        world.add_body({"name": "bad", "mass": -1.0, "inertia": [1, 1, 1],
                        "shapes": [{"type": "sphere", "radius": 0.1}]})


def test_forces_and_velocities_change_momentum_exactly():
    """No gravity: a force F on a 2 kg body for one step of h changes its velocity by F h / m;
    a torque about a principal axis changes the spin by T h / I."""
    world = coulomb.World(gravity=[0, 0, 0])
    body = world.add_body({"name": "b", "mass": 2.0, "inertia": [0.5, 0.5, 0.5],
                           "shapes": [{"type": "sphere", "radius": 0.1}]})
    world.set_velocity(body, [1.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    world.apply_force(body, [0.0, 4.0, 0.0])
    world.apply_torque(body, [0.0, 0.0, 1.0])
    world.step()
    h = world.time_step
    np.testing.assert_allclose(world.linear_velocities()[0], [1.0, 4.0 * h / 2.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(world.angular_velocities()[0], [0, 0, h / 0.5], atol=1e-15)
    # 0.1 m off the centre of mass (a world point): also spins it by (r x F) h / I.
    world.apply_force(body, [0.0, 0.0, 2.0], point=world.positions()[0] + [0.0, 0.1, 0.0])
    world.step()
    assert world.angular_velocities()[0, 0] == pytest.approx(0.1 * 2.0 * h / 0.5, rel=1e-12)


def test_contacts_carry_the_weight():
    """The resting 1 kg box: 4 points with normal +z whose normal impulses add up to m g h."""
    world = coulomb.World("box_on_plane")
    world.step(30)
    contacts = world.contacts()
    assert contacts.shape == (4,)
    ground, box = world.bodies
    assert set(contacts["body_a"]) == {ground} and set(contacts["body_b"]) == {box}
    np.testing.assert_allclose(contacts["normal"], np.tile([0.0, 0.0, 1.0], (4, 1)))
    assert contacts["normal_impulse"].sum() == pytest.approx(9.81 * world.time_step, rel=1e-6)
    assert np.all(contacts["friction"] == 0.5)
    islands = world.report()["islands"]
    assert len(islands) == 1 and islands[0]["contacts"] == 4
    assert islands[0]["status"] == "converged" and islands[0]["attempts"]


def test_snapshot_continues_bit_identically():
    world = coulomb.World("box_incline_B_slide")
    world.step(40)
    snapshot = world.save()
    assert isinstance(snapshot, bytes)
    world.step(60)
    expected = world.state_hash
    world.restore(snapshot)
    assert world.step_count == 40
    world.step(60)
    assert world.state_hash == expected
    with pytest.raises(coulomb.Error):
        world.restore(b"not a snapshot")


def pendulum_world():
    world = coulomb.World()
    return world, world.load_urdf(str(PENDULUM))


def test_pendulum_held_horizontal_by_its_gravity_torque():
    """Pendulum.urdf: 1 kg at 0.5 m below a revolute joint about y. Horizontal (q = pi/2) the
    weight's moment is m g l = 4.905 N m; applying it every step keeps the arm still, without
    it the arm falls."""
    world, robot = pendulum_world()
    assert robot.joint_names == ["theta"] and robot.nq == robot.nv == 1
    robot.set_state([math.pi / 2], [0.0])
    for _ in range(100):
        robot.apply_joint_forces([1.0 * 9.81 * 0.5])
        world.step()
    assert abs(robot.qd[0]) < 1e-9 and robot.q[0] == pytest.approx(math.pi / 2, abs=1e-9)
    world.step(10)
    assert robot.qd[0] < -0.5  # released: it swings down
    assert world.robots()[0].joint_names == ["theta"]


def test_robot_motor_targets_and_errors():
    world = coulomb.World()
    robot = world.load_urdf(str(PENDULUM), hold=True)
    assert robot.joint_q_index("theta") == robot.joint_v_index("theta") == 0
    robot.set_motor_target("theta", 0.3)
    world.step(300)
    assert robot.q[0] == pytest.approx(0.3, abs=1e-4)
    with pytest.raises(coulomb.Error, match="no joint 'elbow'; its moving joints: theta"):
        robot.set_motor_target("elbow", 0.1)
    with pytest.raises(ValueError, match=r"tau: expected shape \(1,\)"):
        robot.apply_joint_forces([1.0, 2.0])
    with pytest.raises(coulomb.Error):
        world.load_urdf("no_such_robot.urdf")
    assert "arm" in robot.link_names and robot.link_positions.shape == (len(robot.link_names), 3)


def test_maximal_joint_carries_the_hanging_weight():
    """A 2 kg bob hanging at rest 1 m below a ball joint to the world: the joint pulls it up with
    m g = 19.62 N and keeps it in place; removed, the bob falls."""
    world = coulomb.World()
    bob = world.add_body({"name": "bob", "position": [0.0, 0.0, -1.0], "mass": 2.0,
                          "inertia": [0.01] * 3, "shapes": [{"type": "sphere", "radius": 0.05}]})
    joint = world.add_joint({"name": "pivot", "type": "ball", "body_b": "bob",
                             "anchor": [0.0, 0.0, 0.0]})
    assert world.joint_count == 1
    world.step(50)
    force, torque = world.joint_reaction(joint)
    np.testing.assert_allclose(force, [0.0, 0.0, 2.0 * 9.81], atol=1e-6)
    np.testing.assert_allclose(world.positions()[0], [0.0, 0.0, -1.0], atol=1e-9)
    assert not world.joint_broken(joint)
    world.remove_joint(joint)
    world.step(10)
    assert world.linear_velocities()[world.bodies.index(bob), 2] < -0.9
    with pytest.raises(coulomb.Error, match="stale"):
        world.joint_reaction(joint)
    with pytest.raises(coulomb.Error, match="add_joint: joint.body_b: .*'bobb'"):
        world.add_joint({"type": "ball", "body_b": "bobb", "anchor": [0, 0, 0]})


def test_run_batch_steps_worlds_in_place():
    worlds = [coulomb.World("box_incline_B_slide"), coulomb.World("chain_10")]
    alone = [coulomb.World("box_incline_B_slide"), coulomb.World("chain_10")]
    for w in alone:
        w.step(80)
    results = coulomb.run_batch(worlds + ["newton_cradle"], threads=2, steps=80)
    assert [w.state_hash for w in worlds] == [w.state_hash for w in alone]
    assert [r.state_hash for r in results[:2]] == [w.state_hash for w in alone]
    assert results[2].state_hash == coulomb.run("newton_cradle", steps=80).state_hash
    with pytest.raises(ValueError, match="the same World twice"):
        coulomb.run_batch([worlds[0], worlds[0]], steps=1)
    with pytest.raises(ValueError, match="steps: required"):
        coulomb.run_batch(worlds)


def test_a_world_being_stepped_by_another_thread_refuses_access():
    """step() releases the GIL: a second thread touching the same world meanwhile gets
    coulomb.Error instead of a data race."""
    import threading
    world = coulomb.World("box_pile_1000")
    stepper = threading.Thread(target=world.step, args=(30,))
    stepper.start()
    refused = 0
    while stepper.is_alive():
        try:
            world.positions()
        except coulomb.Error as error:
            assert "being stepped by another thread" in str(error)
            refused += 1
    stepper.join()
    assert refused > 0
    assert world.step_count == 30 and np.all(np.isfinite(world.positions()))


def test_problems_captured_from_a_live_world():
    """step_capturing: each island's problem as the solver received it, the same problem that
    capture_problems takes from the scene at that step."""
    world = coulomb.World("box_on_plane")
    world.step(10)
    captured = world.step_capturing(1)
    assert [(c.step, c.island) for c in captured] == [(10, 0)]
    assert captured[0].problem.name == "world_step10_island0"
    reference = coulomb.capture_problems("box_on_plane", at_step=10)[0].problem
    np.testing.assert_array_equal(captured[0].problem.W, reference.W)
    np.testing.assert_array_equal(captured[0].problem.q, reference.q)
    assert world.step_count == 11
    world.step(1)  # the observer is gone: stepping captures nothing more
    assert coulomb.solve(captured[0].problem, "ac_newton").converged


def test_threads_give_the_same_state_as_one_thread():
    """World(threads=...) (docs/embedding.md "Threads"): islands run on several threads, each
    writing only its own bodies, so the state hash is the same for every count."""
    hashes = []
    for threads in (None, 2, "hardware"):
        world = coulomb.World("rope_bridge", threads=threads)
        assert world.threads >= 1
        world.step(30)
        hashes.append(world.state_hash)
    assert hashes[0] == hashes[1] == hashes[2]
    with pytest.raises(coulomb.Error, match="threads"):
        coulomb.World("rope_bridge", threads="all")
    with pytest.raises(coulomb.Error, match="threads"):
        coulomb.World("rope_bridge", threads=0)


def test_a_split_sweep_gives_the_same_state_for_every_thread_count():
    """solver.sweep_part_blocks (docs/tuning.md "Parallel sweeps"): a large island's Gauss-Seidel
    sweeps are split into parts that run on the threads; the split is the scene's setting, not
    the thread count's, so every count gives the same state, and another one than the block
    order."""
    def layer(part_blocks):
        # 12 x 12 spheres on the ground and 11 x 11 in their pockets: ~1 100 coupled contacts
        spots = [(0.2 * i, 0.2 * j, 0.1) for i in range(12) for j in range(12)]
        spots += [(0.2 * i + 0.1, 0.2 * j + 0.1, 0.1 + 0.02 ** 0.5)
                  for i in range(11) for j in range(11)]
        spheres = [{"name": f"s{k}", "position": list(p), "mass": 1.0,
                    "inertia": [0.004, 0.004, 0.004],
                    "shapes": [{"type": "sphere", "radius": 0.1, "material": "m"}]}
                   for k, p in enumerate(spots)]
        return {"name": "layer", "time_step": 0.01,
                "solver": {"name": "pgs!", "sweep_part_blocks": part_blocks},
                "materials": {"m": {"friction": 0.5}},
                "bodies": [{"name": "ground", "type": "static",
                            "shapes": [{"type": "plane", "material": "m"}]}] + spheres}
    hashes = []
    for part_blocks, threads in ((64, None), (64, 2), (64, "hardware"), (0, None)):
        world = coulomb.World(layer(part_blocks), threads=threads)
        world.step(20)
        hashes.append(world.state_hash)
    assert hashes[0] == hashes[1] == hashes[2]
    assert hashes[3] != hashes[0]
    with pytest.raises(coulomb.Error, match="sweep_part_blocks"):
        coulomb.World(layer(-1))


def test_chain_keeps_its_energy_by_default():
    """docs/scene-specifications.md A6 chain_10 at dt 0.01 for 5 s: the default energy projection
    keeps the energy within 10 % of the released energy S (without it the chain loses 50-90 %),
    and the report counts the projected island."""
    world = coulomb.World("chain_10")
    released = 0.1 * 9.81 * 0.1 * 10 * 10 / 2
    start = world.mechanical_energy
    projected = 0
    for _ in range(500):
        world.step()
        projected += world.report()["energy_projections"]
        assert abs(world.mechanical_energy - start) < 0.1 * released
    assert projected > 450
