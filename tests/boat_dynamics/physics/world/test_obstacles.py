"""The obstacles' geometry against closed forms: a square, a regular polygon, an L, a cylinder."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.world.obstacles import (
    Cylinder,
    Prism,
    World,
    penetration,
    signed_area,
)

SQUARE = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]]


def _probe(world, xy, z=None, velocity=None):
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    z = np.zeros(xy.shape[0]) if z is None else np.asarray(z, dtype=float)
    v = np.zeros_like(xy) if velocity is None else np.asarray(velocity, dtype=float)
    depth, normal, _ = penetration(world, xy, z, v)
    assert np.all(normal[:, 2] == 0.0)  # walls: the way out is horizontal
    return depth, normal[:, :2]


def test_a_point_in_a_square_leaves_through_its_nearest_side():
    world = World((Prism.make("dock", SQUARE, 1.0),))
    depth, normal = _probe(world, [[0.5, 2.0], [3.0, 3.9], [2.0, 1.0], [5.0, 2.0], [-0.1, 2.0]])
    np.testing.assert_allclose(depth, [0.5, 0.1, 1.0, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(normal, [[-1, 0], [0, 1], [0, -1], [0, 0], [0, 0]], atol=1e-12)


def test_clockwise_corners_are_the_same_prism():
    ccw, cw = Prism.make("a", SQUARE, 1.0), Prism.make("b", SQUARE[::-1], 1.0)
    assert signed_area(cw.points) == signed_area(ccw.points) == 16.0
    xy = np.array([[0.3, 2.0], [2.0, 3.5]])
    for prism in (ccw, cw):
        depth, normal = _probe(World((prism,)), xy)
        np.testing.assert_allclose(depth, [0.3, 0.5], atol=1e-12)
        np.testing.assert_allclose(normal, [[-1, 0], [0, 1]], atol=1e-12)


def test_above_the_top_is_outside():
    world = World((Prism.make("dock", SQUARE, 1.0), Cylinder("pile", np.array([9.0, 0.0]), 1.0,
                                                             -0.5)))
    depth, _ = _probe(world, [[2.0, 2.0], [2.0, 2.0], [9.0, 0.0], [9.0, 0.0]],
                      z=[0.99, 1.01, -0.6, -0.4])
    np.testing.assert_allclose(depth, [2.0, 0.0, 1.0, 0.0])


def test_the_notch_of_an_l_is_outside():
    ell = Prism.make("ell", [[0, 0], [4, 0], [4, 1], [1, 1], [1, 4], [0, 4]], 1.0)
    depth, normal = _probe(World((ell,)), [[3.0, 3.0], [0.3, 3.0], [3.0, 0.8], [0.8, 0.9]])
    # (0.8, 0.9): the inner corner (1, 1) is nearer than any side; out along either of its
    # two edges' normals
    np.testing.assert_allclose(depth, [0.0, 0.3, 0.2, math.hypot(0.2, 0.1)], atol=1e-12)
    np.testing.assert_allclose(normal[:3], [[0, 0], [-1, 0], [0, 1]], atol=1e-12)
    assert any(np.allclose(normal[3], n) for n in ([0, 1], [1, 0]))


def test_a_cylinder_pushes_out_radially_and_from_its_axis_against_the_motion():
    world = World((Cylinder("pile", np.array([1.0, 2.0]), 0.5, 2.0),))
    depth, normal = _probe(world, [[1.3, 2.4], [1.0, 2.0], [3.0, 2.0]],
                           velocity=[[0, 0], [0.0, -2.0], [0, 0]])
    np.testing.assert_allclose(depth, [0.0, 0.5, 0.0], atol=1e-12)  # |(0.3, 0.4)| = 0.5
    np.testing.assert_allclose(normal[1], [0.0, 1.0])
    depth, normal = _probe(world, [[1.15, 2.2]])
    np.testing.assert_allclose(depth, [0.25])
    np.testing.assert_allclose(normal, [[0.6, 0.8]])


def test_the_deepest_obstacle_decides_where_two_overlap():
    world = World((Prism.make("a", SQUARE, 1.0), Cylinder("b", np.array([2.0, 2.0]), 3.0, 1.0)))
    depth, normal, which = penetration(world, np.array([[2.0, 0.2], [4.5, 2.0], [9.0, 9.0]]),
                                       np.zeros(3), np.zeros((3, 2)))
    # the cylinder: 3 - 1.8, the square 0.2; then the cylinder alone; then neither
    np.testing.assert_allclose(depth, [1.2, 0.5, 0.0])
    np.testing.assert_allclose(normal, [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    np.testing.assert_array_equal(which, [1, 1, -1])


@settings(max_examples=60, deadline=None)
@given(sides=st.integers(3, 12), radius=st.floats(0.5, 50.0), turn=st.floats(0.0, 2 * math.pi),
       cx=st.floats(-1e3, 1e3), cy=st.floats(-1e3, 1e3), seed=st.integers(0, 2**31))
def test_a_regular_polygon_against_its_apothem(sides, radius, turn, cx, cy, seed):
    # Inside a convex polygon the way out is the nearest edge's line: depth =
    # min_k (apothem - (p - c) . n_k); outside (any term negative) nothing.
    angles = turn + 2 * math.pi * np.arange(sides) / sides
    corners = np.stack([cx + radius * np.cos(angles), cy + radius * np.sin(angles)], axis=1)
    xy = np.array([cx, cy]) + np.random.default_rng(seed).uniform(-1.2, 1.2, (200, 2)) * radius
    depth, normal = _probe(World((Prism.make("p", corners, 1.0),)), xy)
    mid = turn + 2 * math.pi * (np.arange(sides) + 0.5) / sides
    n = np.stack([np.cos(mid), np.sin(mid)], axis=1)
    slack = radius * math.cos(math.pi / sides) - (xy - [cx, cy]) @ n.T  # (N, sides)
    expected = np.where(slack.min(axis=1) > 0, slack.min(axis=1), 0.0)
    clear = np.abs(slack.min(axis=1)) > 1e-9 * radius  # not on the boundary itself
    np.testing.assert_allclose(depth[clear], expected[clear], atol=1e-9 * radius)
    inside = expected > 1e-9 * radius
    np.testing.assert_allclose(normal[inside], n[np.argmin(slack[inside], axis=1)], atol=1e-9)


def test_the_floor_shelves_to_zero_at_a_sloped_shore_and_nowhere_else():
    from boat_dynamics.physics.world.obstacles import Prism, World, floor_depth

    shore = Prism.make("shore", [[0, 0], [10, 0], [10, 10], [0, 10]], 2.0, 0.05)
    quay = Prism.make("quay", [[-30, 0], [-20, 0], [-20, 10]], 2.0)  # a wall: no shelving
    world = World((shore, quay))
    xy = np.array([[5.0, 5.0], [5.0, -20.0], [13.0, 14.0], [-25.0, -1.0], [5.0, -1000.0]])
    depth = floor_depth(world, xy, 40.0)
    # inside; 20 m south of its edge; 5 m from its corner; by the quay; far offshore
    np.testing.assert_allclose(depth, [0.0, 1.0, 0.25, 0.05 * math.hypot(25, 1), 40.0],
                               atol=1e-12)  # the quay's point is nearest the shore's corner
    assert np.all(floor_depth(World((quay,)), xy, 40.0) == 40.0)


def test_a_point_under_a_shelving_floor_is_pushed_up_the_slope():
    # shore east of x = 10, floor z = -0.1 (10 - x) west of it: at x = 5 it is 0.5 m deep
    shore = Prism.make("shore", [[10, -50], [60, -50], [60, 50], [10, 50]], 2.0, 0.1)
    world = World((shore,))
    xy = np.array([[5.0, 0.0], [5.0, 0.0], [-20.0, 0.0]])
    depth, normal, which = penetration(world, xy, np.array([-0.8, -0.3, -0.8]), np.zeros((3, 2)))
    # 0.3 m under the floor at x = 5, measured along its normal (-0.1, 0, 1) / sqrt(1.01);
    # above it; far offshore (3 m of water) above it
    np.testing.assert_allclose(depth, [0.3 / math.sqrt(1.01), 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(normal[0], np.array([-0.1, 0.0, 1.0]) / math.sqrt(1.01))
    np.testing.assert_array_equal(which, [0, -1, -1])
    assert world.shelving == 0.1 and World((Prism.make("q", SQUARE, 1.0),)).shelving == math.inf
