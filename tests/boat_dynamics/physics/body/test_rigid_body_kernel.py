"""The compiled 6 x 6 step against its numpy oracle and a closed form."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.rigid_body import (
    _integrate_coupled_numpy,
    integrate_coupled,
    mass_matrix,
    quat_from_euler,
    rotation_matrix,
)


def _fleet(rng, boats):
    q = rng.normal(size=(boats, 4))
    mass = rng.uniform(1.0, 1e5, size=boats)
    inertia = np.empty((boats, 3, 3))
    inverse = np.empty((boats, 6, 6))
    for b in range(boats):
        moments = mass[b] * rng.uniform(0.1, 10.0, size=3)
        rigid = mass_matrix(mass[b], moments, 0.05 * moments * rng.uniform(-1, 1, size=3))
        added = rng.normal(size=(6, 6)) * 0.1 * mass[b]
        inertia[b] = rigid[3:, 3:]
        inverse[b] = np.linalg.inv(rigid + np.diag(np.abs(np.diag(rigid))) * 0.5
                                   + 0.5 * (added + added.T) * 0.1)
    return (rng.normal(size=(boats, 3)) * 100.0, q / np.linalg.norm(q, axis=1, keepdims=True),
            rng.normal(size=(boats, 3)) * 5.0, rng.normal(size=(boats, 3)),
            rng.normal(size=(boats, 3)) * mass[:, None],
            rng.normal(size=(boats, 3)) * mass[:, None],
            mass, inertia, inverse)


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), boats=st.integers(1, 20),
       dt=st.floats(1e-4, 0.1), still=st.booleans())
def test_the_compiled_step_equals_numpys(seed, boats, dt, still):
    args = _fleet(np.random.default_rng(seed), boats)
    if still:  # no rotation: the quaternion exponential's 0/0 limit
        args[3][:] = 0.0
    got = integrate_coupled(*args, dt)
    want = _integrate_coupled_numpy(*args, dt)
    for name, a, b in zip(("position", "orientation", "velocity", "angular velocity"),
                          got, want, strict=True):
        scale = np.abs(b).max() + 1.0
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * scale, err_msg=name)
    np.testing.assert_allclose(np.linalg.norm(got[1], axis=1), 1.0, atol=1e-15)


def test_a_free_spin_and_glide_follow_the_closed_form():
    """No force: w x v and w x I w alone. A spin about z (a principal axis) with no sway:
    the spin stays, the boat surges on, and the pose turns by w dt about z."""
    mass, moments = 1000.0, np.array([500.0, 2000.0, 2500.0])
    rigid = mass_matrix(mass, moments, np.zeros(3))
    q0 = quat_from_euler(0.0, 0.0, 0.3)[None]
    w0, dt = 0.2, 0.05
    p, q, v, w = integrate_coupled(np.zeros((1, 3)), q0, np.zeros((1, 3)),
                                   np.array([[0.0, 0.0, w0]]), np.zeros((1, 3)),
                                   np.zeros((1, 3)), np.array([mass]), rigid[None, 3:, 3:],
                                   np.linalg.inv(rigid)[None], dt)
    np.testing.assert_allclose(w, [[0.0, 0.0, w0]], atol=1e-15)
    np.testing.assert_allclose(v, 0.0, atol=1e-15)
    np.testing.assert_allclose(q[0], quat_from_euler(0.0, 0.0, 0.3 + w0 * dt), atol=1e-15)
    # and a surge of 2 m/s with the spin: v' = -w x v, so sway 2 w dt after one step
    p, q, v, w = integrate_coupled(np.zeros((1, 3)), q0, np.array([[2.0, 0.0, 0.0]]),
                                   np.array([[0.0, 0.0, w0]]), np.zeros((1, 3)),
                                   np.zeros((1, 3)), np.array([mass]), rigid[None, 3:, 3:],
                                   np.linalg.inv(rigid)[None], dt)
    np.testing.assert_allclose(v, [[2.0, -w0 * 2.0 * dt, 0.0]], atol=1e-15)
    np.testing.assert_allclose(p[0], dt * rotation_matrix(q[0]) @ v[0], atol=1e-15)
