"""The compiled clip against its numpy oracle (``clip_parts`` and ``SubmergedTriangles.of``).

:func:`boat_dynamics.physics.body.clip.clip_hulls` runs the compiled kernel; the numpy
functions it replaced for the step stay as the oracle, and the two must agree to the last bit
(the same table, the same arithmetic in the same order).
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.clip import SubmergedTriangles, clip_hulls, clip_parts
from boat_dynamics.physics.body.clip_kernel import wet_centroids_f64
from boat_dynamics.physics.body.hull import BoxHull, box_mesh


def _oracle(faces, vertices, depths, heads):
    corners = faces.T
    xyz, d, h, source = clip_parts(vertices.T.take(corners, axis=1), depths.take(corners),
                                   None if heads is None else heads.take(corners))
    return SubmergedTriangles.of(xyz, d, source, h)


def _same(a: SubmergedTriangles, b: SubmergedTriangles) -> None:
    for name in ("xyz", "depths", "vector_areas", "faces", "heads"):
        x, y = getattr(a, name), getattr(b, name)
        assert x.shape == y.shape, name
        np.testing.assert_array_equal(x, y, err_msg=name)


@settings(max_examples=200, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), vertices=st.integers(3, 40), faces=st.integers(0, 80),
       zeros=st.floats(0.0, 0.5), with_heads=st.booleans())
def test_the_compiled_clip_equals_numpys_to_the_last_bit(seed, vertices, faces, zeros,
                                                         with_heads):
    rng = np.random.default_rng(seed)
    xyz = rng.normal(size=(vertices, 3)) * rng.uniform(0.01, 100.0)
    depths = rng.normal(size=vertices)
    depths[rng.random(vertices) < zeros] = 0.0  # on the waterline: dry, and equal depths
    depths[rng.random(vertices) < zeros / 2] = depths[0]  # ties: an edge with no drop
    tri = rng.integers(0, vertices, size=(faces, 3))
    heads = depths + rng.normal(size=vertices) if with_heads else None
    got = clip_hulls(tri, xyz, depths, heads)
    want = _oracle(tri, xyz, depths, heads)
    _same(got, want)
    if heads is None:
        assert got.heads is got.depths  # as the oracle: the depths themselves


def test_a_box_clips_as_numpy_does_and_keeps_the_volume_under_the_plane():
    mesh = box_mesh(BoxHull(4.0, 2.0, 1.0), subdivisions=3)  # centred: z in [-0.5, 0.5]
    for angle, level in ((0.0, 0.1), (0.3, 0.1), (1.2, -0.2)):
        c, s = np.cos(angle), np.sin(angle)
        world = mesh.vertices @ np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]).T
        got = clip_hulls(mesh.faces, world, level - world[:, 2])
        _same(got, _oracle(mesh.faces, world, level - world[:, 2], None))
        if angle == 0.0:  # upright: the volume under z = 0.1 is 4 x 2 x 0.6 m^3
            volume = -(got.depths.mean(axis=0) * got.vector_areas[2]).sum()
            assert volume == pytest.approx(4.8, rel=1e-12)


def test_nothing_wet_gives_empty_arrays_of_the_right_shapes():
    mesh = box_mesh(BoxHull(4.0, 2.0, 1.0))
    wet = clip_hulls(mesh.faces, mesh.vertices, np.full(mesh.vertices.shape[0], -1.0))
    assert wet.xyz.shape == (3, 3, 0) and wet.depths.shape == (3, 0)
    assert wet.vector_areas.shape == (3, 0) and wet.faces.shape == (0,)


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), vertices=st.integers(3, 40), faces=st.integers(0, 80))
def test_the_wet_parts_centroids_heights_and_areas_equal_numpys(seed, vertices, faces):
    rng = np.random.default_rng(seed)
    xyz = rng.normal(size=(vertices, 3)) * rng.uniform(0.01, 100.0)
    depths = rng.normal(size=vertices)
    wet = clip_hulls(rng.integers(0, vertices, size=(faces, 3)), xyz, depths)
    centroids, eta, areas = wet_centroids_f64(wet.xyz, wet.depths, wet.vector_areas)
    np.testing.assert_array_equal(centroids, wet.centroids)
    np.testing.assert_array_equal(areas, wet.areas)
    np.testing.assert_allclose(eta, (wet.xyz[2] + wet.depths).mean(axis=0), rtol=1e-15,
                               atol=1e-13 * (np.abs(wet.xyz[2]).max(initial=0.0) + 1.0))
