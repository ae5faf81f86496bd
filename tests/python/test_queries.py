"""Scene queries of coulomb.World (docs/python.md "Scene queries"): hits where the bodies are
after stepping, against analytic answers; filters; errors."""
import math

import numpy as np
import pytest

import coulomb

SCENE = {
    "name": "queries",
    "bodies": [
        {"name": "floor", "type": "static", "shapes": [{"type": "plane"}]},
        {"name": "box", "position": [0, 0, 1.0],
         "shapes": [{"type": "box", "half_extents": [0.1, 0.1, 0.1]}]},
        {"name": "ghost", "type": "static", "position": [3, 0, 0.5],
         "shapes": [{"type": "sphere", "radius": 0.2, "filter": {"category": 2, "mask": 2}}]},
    ],
}


def box_top(world):
    return world.positions()[1, 2] + 0.1


def test_ray_follows_the_falling_box():
    world = coulomb.World(SCENE)
    for _ in range(30):
        world.step()
        hit = world.cast_ray([0.05, 0, 3], [0, 0, -5])
        assert hit["body"] == 1
        assert hit["point"][2] == pytest.approx(box_top(world), abs=1e-12)
        assert hit["fraction"] == pytest.approx((3 - box_top(world)) / 5, abs=1e-12)
        np.testing.assert_allclose(hit["normal"], [0, 0, 1], atol=1e-9)
    hits = world.cast_ray_all([0.05, 0, 3], [0, 0, -5])
    assert [h["body"] for h in hits] == [1, 0]


def test_shape_cast_overlap_aabb_and_closest_points():
    world = coulomb.World(SCENE)
    world.step()
    top = box_top(world)
    hit = world.cast_shape({"type": "sphere", "radius": 0.05}, [0, 0, 3], [0, 0, -5])
    assert hit["body"] == 1
    assert 3 - 5 * hit["fraction"] - 0.05 == pytest.approx(top, abs=1e-5)
    turned = [math.cos(math.pi / 8), 0, 0, math.sin(math.pi / 8)]  # 45 deg about z
    assert world.cast_shape({"type": "box", "half_extents": [0.1, 0.1, 0.1]}, [0, 0, 3],
                            [0, 0, -5], rotation=turned)["body"] == 1
    inside = world.overlap({"type": "sphere", "radius": 0.05}, [0, 0, top - 0.05])
    assert inside == [{"body": 1, "collider": 1}]
    assert world.query_aabb([-0.5, -0.5, 0.2], [0.5, 0.5, 2]) == [{"body": 1, "collider": 1}]
    distance, on_floor, on_box = world.closest_points(0, 1)
    assert distance == pytest.approx(top - 0.2, abs=1e-9)
    assert on_floor[2] == pytest.approx(0, abs=1e-12)


def test_category_and_mask_choose_what_a_query_sees():
    world = coulomb.World(SCENE)
    ray = ([3, 0, 3], [0, 0, -5])
    assert world.cast_ray(*ray)["body"] == 0  # the ghost (category 2, mask 2) is not seen
    assert world.cast_ray(*ray, category=2, mask=2)["body"] == 2
    assert world.cast_ray(*ray, mask=0) is None


def test_bad_query_input_is_refused():
    world = coulomb.World(SCENE)
    with pytest.raises(ValueError):
        world.cast_ray([0, 0], [0, 0, -1])
    with pytest.raises(coulomb.Error):
        world.cast_ray([math.nan, 0, 0], [0, 0, -1])
    with pytest.raises(coulomb.Error):
        world.cast_shape({"type": "sphere", "radius": -1}, [0, 0, 3], [0, 0, -5])
    with pytest.raises(coulomb.Error):
        world.overlap({"type": "plane"}, [0, 0, 0])
    with pytest.raises(coulomb.Error):
        world.closest_points(0, 99)
