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
     "allowed keys here: name, type, top, points, slope"),
    ({"obstacles": [{"name": "p", "type": "cylinder", "radius": 0.0}]},
     "world.obstacles[0].radius", "(0, 1000]"),
    ({"obstacles": [{"name": "p", "type": "cylinder", "center": [0, math.inf]}]},
     "world.obstacles[0].center", "finite"),
    ({"obstacles": [{**PIER, "top": math.nan}]}, "world.obstacles[0].top", "finite"),
    ({"obstacles": [{**PIER, "slope": 0.0}]}, "world.obstacles[0].slope", "(0, 10]"),
    ({"obstacles": [{**PIER, "slope": math.inf}]}, "world.obstacles[0].slope", "(0, 10]"),
    ({"obstacles": [{"name": "p", "type": "cylinder", "slope": 0.1}]},
     "world.obstacles[0].slope", "allowed keys here: name, type, top, center, radius"),
    ({"obstacles": "pier"}, "world.obstacles", "a list"),
    ({"contact": {"frequency_hz": 10.5}}, "world.contact.frequency_hz", "(0, 10]"),
    ({"contact": {"restitution": 0.1}}, "world.contact.restitution", "[0.2, 1]"),
    ({"contact": {"friction": -1}}, "world.contact.friction", "[0, 2]"),
    ({"walls": []}, "world.walls", "allowed keys here: obstacles, buoys, contact"),
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


def _buoys(buoys, ocean=None, boats=None):
    return parse_scenario({"ocean": ocean or {}, "world": {"buoys": buoys},
                           "boats": boats or [{"name": "usv"}]})


def test_a_buoy_is_a_moored_cylinder_of_the_fleet_without_commands():
    sc = _buoys([{"name": "red", "position": [8, 20], "radius": 0.5, "height": 2.0,
                  "draft": 0.8, "anchor_depth": 6.0}], ocean={"depth": 30.0})
    usv, red = sc.boats
    assert (usv.kind, red.kind) == ("boat", "buoy")
    p = red.params
    assert p.hull.height == 2.0 and p.hull.length == 1.0  # the cylinder's bounding box
    # floats at its draft: its mass is the water the 24-gon's lower 0.8 m displaces
    volume = 12 * 0.5**2 * math.sin(2 * math.pi / 24) * 2.0
    assert math.isclose(p.mass, 1025.0 * volume * 0.8 / 2.0, rel_tol=1e-9)
    line = p.anchor_line
    np.testing.assert_array_equal(line.anchor, [8, 20, -6.0])
    np.testing.assert_array_equal(line.fairlead, [0, 0, -1.0])  # the bottom's middle
    assert math.isclose(line.length, 1.05 * (6.0 - 0.8))
    assert red.commands is not None and red.commands.at(0.0) == (0.0, 0.0)  # no thrust
    assert p.rudder.model == "none" and p.hydro is None


def test_a_boat_may_ride_on_an_anchor_line_of_its_own():
    sc = _buoys([], ocean={"depth": 12.0}, boats=[
        {"name": "usv", "anchor_line": {"anchor": [0, 30, -12.0], "length": 30.0,
                                        "fairlead": [2.0, 0.0, 0.0]}}])
    line = sc.boats[0].params.anchor_line
    assert line.length == 30.0 and line.stiffness == 2e4
    assert math.isclose(line.damping, 2 * 0.1 * math.sqrt(2e4 * sc.boats[0].params.mass))


@pytest.mark.parametrize(("buoys", "key", "says"), [
    ([{"position": [0, 0]}], "world.buoys[0].name", "ROS name"),
    ([{"name": "usv"}], "world.buoys[0].name", "unique among the boats and buoys"),
    ([{"name": "b", "draft": 1.5, "height": 1.5}], "world.buoys[0].draft", "less than"),
    ([{"name": "b", "radius": 0.0}], "world.buoys[0].radius", "[0.05, 50]"),
    ([{"name": "b", "anchor_depth": 40.0}], "world.buoys[0].anchor_depth", "(0.75, 30]"),
    ([{"name": "b", "line_length": 1.0}], "world.buoys[0].line_length", "[9.25, 92.5]"),
    ([{"name": "b", "position": [0, math.nan]}], "world.buoys[0].position", "finite"),
    ([{"name": "b", "colour": "red"}], "world.buoys[0].colour", "allowed keys here"),
    ("red", "world.buoys", "a list"),
])
def test_a_bad_buoy_is_refused_by_key(buoys, key, says):
    with pytest.raises(ScenarioError) as err:
        _buoys(buoys, ocean={"depth": 30.0})
    assert err.value.key == key
    assert says in str(err.value)


@pytest.mark.parametrize(("line", "key", "says"), [
    ({"length": 5.0}, "boats[0].anchor_line.anchor", "is required"),
    ({"anchor": [0, 0, -5.0]}, "boats[0].anchor_line.length", "is required"),
    ({"anchor": [0, 0, 1.0], "length": 5.0}, "boats[0].anchor_line.anchor", "[-30, 0)"),
    ({"anchor": [0, 0, -31.0], "length": 5.0}, "boats[0].anchor_line.anchor", "sea floor"),
    ({"anchor": [0, 0, -5.0], "length": 5.0, "stiffness": 1e9},
     "boats[0].anchor_line.stiffness", "mass x (2 pi simulation.rate_hz / 10)^2"),
    ({"anchor": [0, 0, -5.0], "length": -1.0}, "boats[0].anchor_line.length", "(0, 10000]"),
    ({"anchor": [0, 0, -5.0], "length": 5.0, "fairlead": [500, 0, 0]},
     "boats[0].anchor_line.fairlead", "hull sizes"),
])
def test_a_bad_anchor_line_is_refused_by_key(line, key, says):
    with pytest.raises(ScenarioError) as err:
        _buoys([], ocean={"depth": 30.0}, boats=[{"name": "usv", "anchor_line": line}])
    assert err.value.key == key
    assert says in str(err.value)


@pytest.mark.parametrize(("hull", "key", "says"), [
    ({"type": "cylinder", "length": 2.0}, "boats[0].hull.length", "only for hull type box"),
    ({"type": "box", "radius": 2.0}, "boats[0].hull.radius", "only for hull type cylinder"),
    ({"type": "cylinder", "radius": 0.001}, "boats[0].hull.radius", "[0.005, 500]"),
])
def test_a_bad_cylinder_hull_is_refused_by_key(hull, key, says):
    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"hull": hull}]})
    assert err.value.key == key
    assert says in str(err.value)
