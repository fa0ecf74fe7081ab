"""The hulls as contact sees them: convex hulls, points round them, and pairs near enough."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.hull import BoxHull, box_mesh
from boat_dynamics.physics.world.footprints import (
    SPACING,
    Footprints,
    convex_hull,
    near_pairs,
    perimeter_points,
)
from boat_dynamics.physics.world.obstacles import signed_area


def test_a_box_is_its_own_footprint():
    fp = Footprints.build([box_mesh(BoxHull(4.0, 2.0, 1.0), 2).vertices])
    assert signed_area(fp.corners[0]) == pytest.approx(8.0)
    assert fp.corners[0].shape == (4, 2)
    np.testing.assert_allclose(fp.z, [[-0.5, 0.5]])
    assert fp.radius[0] == pytest.approx(np.hypot(2.0, 1.0))
    np.testing.assert_allclose(np.abs(fp.normals[0]).sum(axis=1), 1.0)  # axis-aligned


def test_points_round_a_prism_are_on_its_sides_and_close_together():
    corners = np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 1.0]])
    p = perimeter_points(corners, -1.0, 2.0)
    assert set(np.round(p[:, 2], 12)) == {-1.0, 0.5, 2.0}
    ring = p[p[:, 2] == 2.0, :2]
    gaps = np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T)
    assert gaps.max() <= SPACING + 1e-12
    # on a side: distance to the hull's boundary is zero
    on_hypotenuse = np.abs(ring[:, 0] / 3.0 + ring[:, 1] - 1.0) < 1e-12
    on_axes = (np.abs(ring[:, 0]) < 1e-12) | (np.abs(ring[:, 1]) < 1e-12)
    assert np.all(on_hypotenuse | on_axes)


@settings(max_examples=50, deadline=None)
@given(seed=st.integers(0, 2**31), n=st.integers(3, 60))
def test_the_convex_hull_holds_every_point_and_turns_left(seed, n):
    pts = np.random.default_rng(seed).normal(size=(n, 2)) * 5.0
    hull = convex_hull(pts)
    e = np.roll(hull, -1, axis=0) - hull
    turns = e[:, 0] * np.roll(e, -1, axis=0)[:, 1] - e[:, 1] * np.roll(e, -1, axis=0)[:, 0]
    assert np.all(turns > 0.0)  # counter-clockwise, no collinear corner
    normal = np.stack([e[:, 1], -e[:, 0]], axis=1)
    outside = np.einsum("npk,pk->np", pts[:, None] - hull[None], normal)
    assert np.all(outside <= 1e-9 * np.abs(normal).max() * 10.0)


def test_points_on_a_line_have_no_hull():
    with pytest.raises(ValueError, match="one line"):
        convex_hull(np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]))


@settings(max_examples=50, deadline=None)
@given(seed=st.integers(0, 2**31), n=st.integers(1, 120), spread=st.floats(1.0, 300.0))
def test_near_pairs_are_the_overlapping_circles(seed, n, spread):
    # small fleets check every pair, large ones (over 48) sweep along x: both here
    rng = np.random.default_rng(seed)
    xy, radius = rng.uniform(0.0, spread, (n, 2)), rng.uniform(0.5, 5.0, n)
    gap = np.hypot(*(xy[:, None] - xy[None]).transpose(2, 0, 1))
    i, j = np.nonzero(np.triu(gap <= radius[:, None] + radius[None], k=1))
    expected = sorted(zip(i.tolist(), j.tolist(), strict=True))
    assert sorted(map(tuple, near_pairs(xy, radius).tolist())) == expected
