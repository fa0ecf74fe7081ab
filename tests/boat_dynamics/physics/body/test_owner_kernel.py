"""The compiled per-boat gathers and sums against numpy (their oracles)."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.owner_kernel import (
    _to_world_numpy,
    sum_by_owner_f64,
    to_world_f64,
    weighted_mean_by_owner_f64,
)
from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.body.wrench import sum_by_owner

_CASES = dict(seed=st.integers(0, 2**32 - 1), boats=st.integers(1, 12),
              elements=st.integers(0, 300))


def _fleet(seed, boats, elements):
    rng = np.random.default_rng(seed)
    owner = rng.integers(0, boats, size=elements).astype(np.intp)
    return rng, owner


@settings(max_examples=100, deadline=None)
@given(**_CASES)
def test_elements_move_to_the_world_frame_as_the_einsum_did(seed, boats, elements):
    rng, owner = _fleet(seed, boats, elements)
    q = rng.normal(size=(boats, 4))
    rot = rotation_matrix(q / np.linalg.norm(q, axis=1, keepdims=True))
    ref, body = rng.normal(size=(boats, 3)) * 100.0, rng.normal(size=(elements, 3)) * 5.0
    got = to_world_f64(rot, ref, owner, body)
    np.testing.assert_allclose(got, _to_world_numpy(rot, ref, owner, body), rtol=1e-12,
                               atol=1e-12 * 100.0)
    # a rigid motion: distances between one boat's elements are kept
    first = owner == owner[0] if elements else np.zeros(0, dtype=bool)
    a, b = body[first], got[first]
    np.testing.assert_allclose(np.linalg.norm(b[:, None] - b[None], axis=-1),
                               np.linalg.norm(a[:, None] - a[None], axis=-1), atol=1e-9)


@settings(max_examples=100, deadline=None)
@given(columns=st.integers(1, 7), **_CASES)
def test_per_boat_sums_equal_numpys(seed, boats, elements, columns):
    rng, owner = _fleet(seed, boats, elements)
    values = rng.normal(size=(elements, columns)) * 10.0 ** rng.uniform(-3, 3)
    want = np.zeros((boats, columns))
    np.add.at(want, owner, values)
    scale = np.abs(values).sum() + 1e-300
    np.testing.assert_allclose(sum_by_owner_f64(values, owner, boats), want, rtol=0,
                               atol=1e-12 * scale)
    # the public function takes any float layout (a transposed view here)
    np.testing.assert_allclose(sum_by_owner(np.asfortranarray(values), owner, boats), want,
                               rtol=0, atol=1e-12 * scale)


@settings(max_examples=100, deadline=None)
@given(**_CASES)
def test_weighted_means_per_boat_and_the_fallback_of_a_dry_boat(seed, boats, elements):
    rng, owner = _fleet(seed, boats, elements)
    values = rng.normal(size=(elements, 3))
    weights = rng.uniform(0.0, 2.0, size=elements)
    weights[rng.random(elements) < 0.2] = 0.0
    fallback = rng.normal(size=(boats, 3)) + 50.0
    got = weighted_mean_by_owner_f64(values, weights, owner, fallback)
    for b in range(boats):
        w = weights[owner == b]
        if w.sum() > 0.0:
            want = (values[owner == b] * w[:, None]).sum(axis=0) / w.sum()
            np.testing.assert_allclose(got[b], want, rtol=1e-12, atol=1e-12)
        else:
            np.testing.assert_array_equal(got[b], fallback[b])
