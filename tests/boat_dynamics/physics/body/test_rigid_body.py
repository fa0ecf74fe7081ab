"""Quaternion kinematics and the integrator: invariants (hypothesis) and closed forms."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.rigid_body import (
    integrate,
    quat_from_euler,
    quat_multiply,
    quat_to_euler,
    rotation_matrix,
)

angles = st.floats(-math.pi + 1e-3, math.pi - 1e-3)


@settings(max_examples=200)
@given(roll=angles, pitch=st.floats(-1.5, 1.5), yaw=angles)
def test_euler_round_trip_and_orthonormal_rotation(roll, pitch, yaw):
    q = quat_from_euler(roll, pitch, yaw)
    assert np.linalg.norm(q) == pytest.approx(1.0, abs=1e-12)
    assert np.allclose(quat_to_euler(q), (roll, pitch, yaw), atol=1e-9)
    r = rotation_matrix(q)
    assert np.allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(r) == pytest.approx(1.0, abs=1e-12)


@settings(max_examples=100)
@given(a=st.tuples(angles, st.floats(-1.5, 1.5), angles),
       b=st.tuples(angles, st.floats(-1.5, 1.5), angles))
def test_quaternion_product_composes_rotations(a, b):
    qa, qb = quat_from_euler(*a), quat_from_euler(*b)
    assert np.allclose(rotation_matrix(quat_multiply(qa, qb)),
                       rotation_matrix(qa) @ rotation_matrix(qb), atol=1e-12)


def test_rep103_yaw_turns_x_towards_y():
    r = rotation_matrix(quat_from_euler(0.0, 0.0, math.pi / 2))
    assert np.allclose(r @ [1, 0, 0], [0, 1, 0], atol=1e-15)


def test_constant_spin_rotates_by_omega_t():
    p, q, v, w = np.zeros(3), np.array([0.0, 0, 0, 1]), np.zeros(3), np.array([0, 0, 0.5])
    for _ in range(1000):
        p, q, v, w = integrate(p, q, v, w, np.zeros(3), np.zeros(3), np.full(3, 2.0),
                               np.array([1.0, 2.0, 3.0]), 0.01)
    assert quat_to_euler(q)[2] == pytest.approx(math.remainder(0.5 * 10.0, 2 * math.pi),
                                                 abs=1e-9)


def test_constant_force_gives_uniform_acceleration():
    p, q, v, w = np.zeros(3), np.array([0.0, 0, 0, 1]), np.zeros(3), np.zeros(3)
    dt, n = 1e-3, 2000
    for _ in range(n):
        p, q, v, w = integrate(p, q, v, w, np.array([4.0, 0, 0]), np.zeros(3), np.full(3, 2.0),
                               np.ones(3), dt)
    t = n * dt
    assert v[0] == pytest.approx(2.0 * t, rel=1e-12)
    assert p[0] == pytest.approx(0.5 * 2.0 * t * t, rel=2e-3)  # semi-implicit: O(dt) error


def test_torque_free_rotation_keeps_energy_and_momentum_bounded():
    inertia = np.array([1.0, 2.0, 3.0])
    p, q, v, w = np.zeros(3), np.array([0.0, 0, 0, 1]), np.zeros(3), np.array([0.1, 1.0, 0.1])
    e0 = 0.5 * np.sum(inertia * w * w)
    l0 = np.linalg.norm(rotation_matrix(q) @ (inertia * w))
    for _ in range(20000):
        p, q, v, w = integrate(p, q, v, w, np.zeros(3), np.zeros(3), np.ones(3), inertia, 1e-3)
    assert 0.5 * np.sum(inertia * w * w) == pytest.approx(e0, rel=0.05)
    assert np.linalg.norm(rotation_matrix(q) @ (inertia * w)) == pytest.approx(l0, rel=0.05)
    assert np.linalg.norm(q) == pytest.approx(1.0, abs=1e-12)


def test_a_full_inertia_tensor_is_the_principal_body_seen_in_rotated_axes():
    # I = R0 D R0^T: the same body as the principal one D, with its body axes turned by R0.
    from boat_dynamics.physics.body.rigid_body import inertia_tensor

    moments = np.array([1.0, 2.0, 3.0])
    r0q = quat_from_euler(0.3, -0.4, 0.7)
    r0 = rotation_matrix(r0q)
    tensor = r0 @ np.diag(moments) @ r0.T
    diag, products = np.diag(tensor).copy(), -np.array([tensor[0, 1], tensor[0, 2], tensor[1, 2]])
    np.testing.assert_allclose(inertia_tensor(diag, products), tensor, atol=1e-15)
    w_principal = np.array([0.05, 0.1, 1.0])  # near the major axis: a stable spin
    zero, one = np.zeros(3), np.ones(3)
    q_full, w_full = np.array([0.0, 0, 0, 1]), r0 @ w_principal
    q_p, w_p = r0q, w_principal
    l0 = rotation_matrix(q_full) @ tensor @ w_full
    for _ in range(2000):
        _, q_full, _, w_full = integrate(zero, q_full, zero, w_full, zero, zero, one, diag, 1e-3,
                                         inertia_products=products)
        _, q_p, _, w_p = integrate(zero, q_p, zero, w_p, zero, zero, one, moments, 1e-3)
    np.testing.assert_allclose(rotation_matrix(q_full) @ r0, rotation_matrix(q_p), atol=1e-9)
    np.testing.assert_allclose(r0.T @ w_full, w_p, atol=1e-9)
    l1 = rotation_matrix(q_full) @ tensor @ w_full
    assert np.linalg.norm(l1 - l0) < 0.01 * np.linalg.norm(l0)  # angular momentum conserved


def test_zero_products_of_inertia_are_the_principal_axes_path():
    args = (np.zeros(3), quat_from_euler(0.1, 0.2, 0.3), np.array([1.0, 0.2, 0.0]),
            np.array([0.3, -0.2, 0.5]), np.array([10.0, 0, 0]), np.array([1.0, 2.0, 3.0]),
            np.array([100.0, 100.0, 100.0]), np.array([10.0, 20.0, 30.0]), 0.01)
    for a, b in zip(integrate(*args), integrate(*args, inertia_products=np.zeros(3)),
                    strict=True):
        np.testing.assert_allclose(a, b, rtol=1e-14, atol=1e-15)
