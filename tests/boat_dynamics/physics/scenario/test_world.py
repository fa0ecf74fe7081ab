"""The ``world`` section: obstacles and contact read, and every bad value refused by name."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.scenario import ScenarioError, parse_scenario
from boat_dynamics.physics.world.obstacles import Cylinder, Prism

PIER = {"name": "pier", "points": [[8, -20], [8.5, -20], [8.5, 20], [8, 20]], "top": 1.5}


def _world(world: dict, rate: float = 100.0):
    return parse_scenario({"simulation": {"rate_hz": rate}, "world": world}).world


def test_obstacles_and_contact_are_read():
    world = _world({"obstacles": [PIER, {"name": "pile", "type": "cylinder",
                                         "center": [3, 4], "radius": 0.3}],
                    "contact": {"restitution": 0.5, "friction": 0.1}})
    pier, pile = world.obstacles
    assert isinstance(pier, Prism) and isinstance(pile, Cylinder)
    np.testing.assert_array_equal(pier.points, PIER["points"])  # counter-clockwise already
    assert pier.top == 1.5 and pile.top == 2.0 and pile.radius == 0.3
    assert world.contact.frequency_hz == 10.0  # rate / 10
    assert (world.contact.restitution, world.contact.friction) == (0.5, 0.1)


def test_no_world_is_no_obstacles():
    assert parse_scenario({}).world.obstacles == ()


def test_clockwise_corners_are_turned():
    world = _world({"obstacles": [{**PIER, "points": PIER["points"][::-1]}]})
    np.testing.assert_array_equal(world.obstacles[0].points, PIER["points"])


@pytest.mark.parametrize(("world", "key", "says"), [
    ({"obstacles": [{**PIER, "points": [[0, 0], [1, 1], [1, 0], [0, 1]]}]},
     "world.obstacles[0].points", "edges 0 and 2 cross"),
    ({"obstacles": [{**PIER, "points": [[0, 0], [1, 1], [2, 2]]}]},
     "world.obstacles[0].points", "enclose an area"),
    ({"obstacles": [{**PIER, "points": [[0, 0], [1, 1]]}]},
     "world.obstacles[0].points", "3 to 1000"),
    ({"obstacles": [{**PIER, "points": [[0, 0], [1, math.nan], [1, 0]]}]},
     "world.obstacles[0].points", "finite"),
    ({"obstacles": [{**PIER, "points": [[0, 0], [1, 2e7], [1, 0]]}]},
     "world.obstacles[0].points", "within"),
    ({"obstacles": [{**PIER, "points": [[0, 0], [10**400, 1], [1, 0]]}]},
     "world.obstacles[0].points", "within"),
    ({"obstacles": [{**PIER, "points": [[0, 0], [1, 0], [1, 0], [0, 0]]}]},
     "world.obstacles[0].points", "3 distinct corners"),
    ({"obstacles": [{**PIER, "name": "9lives"}]}, "world.obstacles[0].name", "ROS name"),
    ({"obstacles": [{k: v for k, v in PIER.items() if k != "name"}]},
     "world.obstacles[0].name", "ROS name"),
    ({"obstacles": [PIER, PIER]}, "world.obstacles[1].name", "unique"),
    ({"obstacles": [{**PIER, "type": "sphere"}]}, "world.obstacles[0].type", "polygon"),
    ({"obstacles": [{**PIER, "radius": 1.0}]}, "world.obstacles[0].radius",
     "allowed keys here: name, type, top, points"),
    ({"obstacles": [{"name": "p", "type": "cylinder", "radius": 0.0}]},
     "world.obstacles[0].radius", "(0, 1000]"),
    ({"obstacles": [{"name": "p", "type": "cylinder", "center": [0, math.inf]}]},
     "world.obstacles[0].center", "finite"),
    ({"obstacles": [{**PIER, "top": math.nan}]}, "world.obstacles[0].top", "finite"),
    ({"obstacles": "pier"}, "world.obstacles", "a list"),
    ({"contact": {"frequency_hz": 10.5}}, "world.contact.frequency_hz", "(0, 10]"),
    ({"contact": {"restitution": 0.1}}, "world.contact.restitution", "[0.2, 1]"),
    ({"contact": {"friction": -1}}, "world.contact.friction", "[0, 2]"),
    ({"walls": []}, "world.walls", "allowed keys here: obstacles, contact"),
])
def test_a_bad_world_is_refused_by_key(world, key, says):
    with pytest.raises(ScenarioError) as err:
        _world(world)
    assert err.value.key == key
    assert says in str(err.value)


def test_a_closing_corner_counts_once():
    # GIS polygons repeat their first corner at the end: the same polygon, no empty edge
    closed = [*PIER["points"], PIER["points"][0]]
    world = _world({"obstacles": [{**PIER, "points": closed}]})
    np.testing.assert_array_equal(world.obstacles[0].points, PIER["points"])


def test_an_integer_too_large_for_a_float_is_refused_by_key():
    for data, key in (({"ocean": {"depth": 10**400}}, "ocean.depth"),
                      ({"boats": [{"center_of_mass": [10**400, 0, 0]}]},
                       "boats[0].center_of_mass")):
        with pytest.raises(ScenarioError) as err:
            parse_scenario(data)
        assert err.value.key == key


def test_the_stiffest_contact_follows_the_rate():
    assert _world({"contact": {"frequency_hz": 50.0}}, rate=500.0).contact.frequency_hz == 50.0
    with pytest.raises(ScenarioError, match=r"\(0, 5\] Hz"):
        _world({"contact": {"frequency_hz": 6.0}}, rate=50.0)
