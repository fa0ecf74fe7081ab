"""Wrench helpers: the cross product's two forms and per-boat sums, against numpy references."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from boat_dynamics.physics.body.wrench import Wrench, cross, sum_by_owner, wrench_at

finite = st.floats(-1e3, 1e3)


@settings(max_examples=200, deadline=None)
@given(n=st.integers(1, 80), data=st.data())
def test_cross_equals_numpy_in_both_layouts_and_both_sizes(n, data):
    # n <= 50 vectors take the einsum form, more take the written-out products
    a = data.draw(arrays(np.float64, (n, 3), elements=finite))
    b = data.draw(arrays(np.float64, (n, 3), elements=finite))
    ref = np.cross(a, b)
    np.testing.assert_allclose(cross(a, b), ref, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(cross(a.T, b.T, axis=0), ref.T, rtol=1e-12, atol=1e-9)
    # the two forms round the same way: identical bits, whichever the size
    assert np.array_equal(cross(a, b), cross(a.T.copy(), b.T.copy(), axis=0).T)


def test_cross_broadcasts_and_refuses_other_axes():
    r = np.array([1.0, 0.0, 0.0])
    f = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    np.testing.assert_array_equal(cross(r, f), [[0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
    with pytest.raises(ValueError, match="axis 1 is not allowed"):
        cross(np.zeros((3, 3)), np.zeros((3, 3)), axis=1)


@settings(max_examples=150, deadline=None)
@given(count=st.integers(1, 60), t=st.integers(0, 500), seed=st.integers(0, 2**32 - 1))
def test_sum_by_owner_is_the_per_boat_sum(count, t, seed):
    # covers one boat, the 0/1-matrix path (count * T <= 20,000) and the bincount path
    rng = np.random.default_rng(seed)
    owner = rng.integers(0, count, t)
    values = rng.normal(size=(t, 3))
    out = sum_by_owner(values, owner, count)
    assert out.shape == (count, 3)
    for b in range(count):
        np.testing.assert_allclose(out[b], values[owner == b].sum(axis=0), atol=1e-12)


def test_wrench_at_is_force_sum_and_moment_about_the_com():
    # a couple: no net force, torque F d about z
    forces = np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]])
    points = np.array([[0.0, -0.5, 0.0], [0.0, 0.5, 0.0]])
    w = wrench_at(forces, points)
    np.testing.assert_array_equal(w.force, [0.0, 0.0, 0.0])
    np.testing.assert_allclose(w.torque, [0.0, 0.0, 1.0])
    total = w + Wrench(np.ones(3), np.zeros(3))
    np.testing.assert_array_equal(total.force, np.ones(3))
