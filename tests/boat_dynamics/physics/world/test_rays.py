"""Rays against closed-form geometry: a wall, a cylinder, a box hull, the sea."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.hull import BoxHull, box_mesh
from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.world.footprints import Footprints
from boat_dynamics.physics.world.obstacles import Cylinder, Prism, World
from boat_dynamics.physics.world.rays import cast, hull_ranges, water_range

WALL = Prism.make("wall", [[10.0, -50.0], [11.0, -50.0], [11.0, 50.0], [10.0, 50.0]], 2.0)


def _rays(azimuths, elevation=0.0, origin=(0.0, 0.0, 1.0)):
    az = np.asarray(azimuths, dtype=float)
    d = np.stack([np.cos(az) * math.cos(elevation), np.sin(az) * math.cos(elevation),
                  np.full(az.shape, math.sin(elevation))], axis=1)
    return np.tile(origin, (az.shape[0], 1)).astype(float), d


@settings(max_examples=40, deadline=None)
@given(az=st.floats(-1.3, 1.3), el=st.floats(-0.05, 0.05))
def test_a_wall_is_at_its_distance_over_the_cosine(az, el):
    o, d = _rays([az], el)
    r = cast(World((WALL,)), o, d, 1000.0)[0]
    horizontal = 10.0 / math.cos(az)  # to x = 10
    expected = horizontal / math.cos(el)
    if 1.0 + expected * math.sin(el) > 2.0 or abs(horizontal * math.sin(az)) > 50.0:
        assert math.isinf(r)  # over the top, or past its end
    else:
        assert r == pytest.approx(expected, rel=1e-12)


def test_over_a_wall_a_ray_lands_on_its_top_or_misses_it():
    o, d = _rays([0.0, 0.0], origin=(0.0, 0.0, 5.0))
    d[0] = [math.cos(-0.3), 0.0, math.sin(-0.3)]  # down at 0.3 rad: crosses z = 2 at x 9.66
    d[1] = [math.cos(-0.25), 0.0, math.sin(-0.25)]  # lands at x = 3 / tan 0.25 = 12.24: beyond
    r = cast(World((WALL,)), o, d, 1000.0)
    assert r[0] == pytest.approx(10.0 / math.cos(0.3))  # the wall's face, below its top
    assert math.isinf(r[1])
    d2 = np.array([[math.cos(-0.29), 0.0, math.sin(-0.29)]])  # lands on the top: x = 10.04
    assert cast(World((WALL,)), o[:1], d2, 1000.0)[0] == pytest.approx(3.0 / math.sin(0.29))


@settings(max_examples=40, deadline=None)
@given(az=st.floats(-0.2, 0.2))
def test_a_cylinder_is_at_its_chord(az):
    # From the origin toward a pile at L = 20 m of radius 1: r = L cos a - sqrt(R^2 - L^2 sin^2 a)
    pile = Cylinder("pile", np.array([20.0, 0.0]), 1.0, 3.0)
    o, d = _rays([az])
    r = cast(World((pile,)), o, d, 1000.0)[0]
    gap = 1.0 - (20.0 * math.sin(az)) ** 2
    if gap < 0.0:
        assert math.isinf(r)
    else:
        assert r == pytest.approx(20.0 * math.cos(az) - math.sqrt(gap), rel=1e-12)


def test_the_nearest_of_two_obstacles_and_the_range_limit():
    pile = Cylinder("pile", np.array([5.0, 0.0]), 0.5, 3.0)
    o, d = _rays([0.0, 0.0, 0.5])
    r = cast(World((WALL, pile)), o, d, 1000.0)
    assert r[0] == pytest.approx(4.5) and r[2] == pytest.approx(10.0 / math.cos(0.5))
    assert math.isinf(cast(World((WALL, pile)), o, d, 4.0)[0])


@pytest.mark.parametrize(("yaw_deg", "face"), [(0.0, 13.0), (90.0, 14.0), (180.0, 13.0)])
def test_another_boats_hull_is_at_its_face(yaw_deg, face):
    # A 4 m x 2 m x 1 m box whose middle is 15 m ahead: its near face at 15 - 2 (end on) or
    # 15 - 1 (broadside); a ray over it or under it misses.
    fp = Footprints.build([box_mesh(BoxHull(4.0, 2.0, 1.0)).vertices])
    rot = rotation_matrix(np.array([[0.0, 0.0, math.sin(math.radians(yaw_deg) / 2),
                                     math.cos(math.radians(yaw_deg) / 2)]]))
    ref = np.array([[15.0, 0.0, 0.0]])
    o, d = _rays([0.0, 0.0, 0.0], origin=(0.0, 0.0, 0.2))
    o[1, 2], o[2, 2] = 0.6, -0.6
    r = hull_ranges(fp, rot, ref, o, d)
    assert r[0] == pytest.approx(face, abs=1e-9)
    assert math.isinf(r[1]) and math.isinf(r[2])
    inside = hull_ranges(fp, rot, ref, np.array([[15.0, 0.0, 0.0]]), d[:1])
    assert math.isinf(inside[0])  # from inside: no hit


@settings(max_examples=30, deadline=None)
@given(depression=st.floats(0.05, 1.5), height=st.floats(0.5, 10.0))
def test_a_ray_meets_flat_water_at_height_over_the_sine(depression, height):
    o, d = _rays([0.3], -depression, origin=(1.0, 2.0, height))
    r = water_range(o, d, lambda xy: np.zeros(xy.shape[0]))
    assert r[0] == pytest.approx(height / math.sin(depression), rel=1e-12)
    up = water_range(o, -d, lambda xy: np.zeros(xy.shape[0]))
    assert math.isinf(up[0])


def test_a_ray_meets_a_wave_where_the_surface_is():
    # a long swell, eta = 0.5 cos(k x): the hit is on it to a millimetre
    k = 2 * math.pi / 60.0
    o, d = _rays([0.0], -0.4, origin=(0.0, 0.0, 4.0))

    def eta(xy):
        return 0.5 * np.cos(k * xy[:, 0])

    r = water_range(o, d, eta)[0]
    hit = o[0] + r * d[0]
    assert abs(hit[2] - eta(hit[None, :2])[0]) < 1e-3
