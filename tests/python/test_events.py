"""Contact and sensor events, kinematic targets and colliders on live bodies of coulomb.World
(docs/python.md "Contact events, sensors, kinematic bodies, colliders on live bodies"), against
analytic answers."""
import math

import numpy as np
import pytest

import coulomb

G = 9.81


def test_dropped_box_begins_once_with_the_free_fall_speed():
    world = coulomb.World({
        "name": "drop",
        "bodies": [
            {"name": "floor", "type": "static", "shapes": [{"type": "plane"}]},
            {"name": "box", "position": [0, 0, 0.3],
             "shapes": [{"type": "box", "half_extents": [0.1, 0.1, 0.1]}]},
        ],
    })
    begins = []
    for _ in range(200):
        world.step()
        events = world.contact_events()
        assert all(e["type"] != "end" for e in events)
        begins += [e for e in events if e["type"] == "begin"]
    assert len(begins) == 1
    assert begins[0]["body_b"] == world.find_body("box")
    assert begins[0]["approach_speed"] == pytest.approx(math.sqrt(2 * G * 0.2), abs=G * 0.01)
    assert begins[0]["points"].shape == (4, 3)
    resting = world.contact_events()[0]
    assert resting["type"] == "persist"
    mass = 1000 * 0.2 ** 3  # default density
    assert resting["normal_impulse"] == pytest.approx(mass * G * 0.01, rel=1e-4)


def test_sensor_reports_the_ball_and_does_not_push_it():
    world = coulomb.World({
        "name": "sensor",
        "bodies": [
            {"name": "zone", "type": "static",
             "shapes": [{"type": "box", "half_extents": [0.5, 0.5, 0.25], "sensor": True}]},
            {"name": "ball", "position": [0, 0, 1.0],
             "shapes": [{"type": "sphere", "radius": 0.05}]},
        ],
    })
    seen = []
    for _ in range(80):
        world.step()
        seen += world.sensor_events()
        assert world.contact_events() == []
    assert [e["begin"] for e in seen] == [True, False]
    assert all(e["visitor_body"] == world.find_body("ball") for e in seen)
    n, h = world.step_count, world.time_step  # semi-implicit Euler: z_n = z_0 - g h^2 n (n + 1) / 2
    assert world.positions()[1, 2] == pytest.approx(1.0 - G * h * h * n * (n + 1) / 2, abs=1e-12)


def test_kinematic_target_is_reached():
    world = coulomb.World({
        "name": "kinematic",
        "bodies": [{"name": "lift", "type": "kinematic",
                    "shapes": [{"type": "box", "half_extents": [0.5, 0.5, 0.05]}]},
                   {"name": "ball", "position": [5, 0, 5],
                    "shapes": [{"type": "sphere", "radius": 0.1}]}],
    })
    lift = world.find_body("lift")
    half = math.sqrt(0.5)
    world.set_kinematic_target(lift, [0.1, 0, 0.2], rotation=[half, 0, 0, half])
    world.step()
    np.testing.assert_allclose(world.positions()[0], [0.1, 0, 0.2], atol=1e-12)
    np.testing.assert_allclose(world.quaternions()[0], [half, 0, 0, half], atol=1e-12)
    with pytest.raises(coulomb.Error, match="not a kinematic body"):
        world.set_kinematic_target(world.find_body("ball"), [0, 0, 0])


def test_colliders_added_to_and_removed_from_a_live_body():
    world = coulomb.World({
        "name": "probe",
        "bodies": [
            {"name": "floor", "type": "static", "shapes": [{"type": "plane"}]},
            {"name": "probe", "position": [0, 0, 1.0], "mass": 2.0, "inertia": [0.01] * 3},
        ],
    })
    probe = world.find_body("probe")
    with pytest.raises(coulomb.Error, match="radius"):
        world.add_collider(probe, {"type": "sphere", "radius": -0.1})
    collider = world.add_collider(probe, {"type": "sphere", "radius": 0.1,
                                          "material": {"friction": 0.3, "restitution": 0.0}})
    world.step(200)
    assert world.positions()[1, 2] == pytest.approx(0.1, abs=1e-3)  # rests on its new sphere
    world.remove_collider(collider)
    with pytest.raises(coulomb.Error):
        world.remove_collider(collider)
    world.step()
    assert [e["type"] for e in world.contact_events()] == ["end"]
    world.step(50)
    assert world.positions()[1, 2] < -0.1  # nothing left to hold it
