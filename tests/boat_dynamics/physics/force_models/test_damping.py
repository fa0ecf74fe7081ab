"""Damping: the force models dissipate, per DOF, and the notes' decay only shrinks velocities."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from boat_dynamics.physics.force_models.damping import damping, velocity_decay

coefficients = arrays(np.float64, 6, elements=st.floats(0.0, 1e5))
velocities = arrays(np.float64, 3, elements=st.floats(-50.0, 50.0))


@settings(max_examples=300, deadline=None)
@given(linear=coefficients, quadratic=coefficients, v=velocities, w=velocities)
def test_damping_never_adds_energy_in_any_dof(linear, quadratic, v, w):
    d = damping(linear, quadratic, v, w)
    # per DOF: the force opposes the relative velocity (power <= 0), never reverses it
    assert np.all(d.force * v <= 0.0) and np.all(d.torque * w <= 0.0)
    # and it is exactly Fossen's diagonal linear + quadratic law (eqs. 6.54, 6.59)
    np.testing.assert_allclose(d.force, -linear[:3] * v - quadratic[:3] * np.abs(v) * v,
                               rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(d.torque, -linear[3:] * w - quadratic[3:] * np.abs(w) * w,
                               rtol=1e-12, atol=1e-9)


def test_damping_over_a_fleet_is_each_boat_alone():
    rng = np.random.default_rng(3)
    lin, quad = rng.uniform(0, 1e4, (5, 6)), rng.uniform(0, 1e3, (5, 6))
    v, w = rng.normal(size=(5, 3)), rng.normal(size=(5, 3))
    together = damping(lin, quad, v, w)
    for b in range(5):
        alone = damping(lin[b], quad[b], v[b], w[b])
        assert np.array_equal(alone.force, together.force[b])
        assert np.array_equal(alone.torque, together.torque[b])


@settings(max_examples=200, deadline=None)
@given(v=velocities, w=velocities,
       rates=arrays(np.float64, 6, elements=st.floats(0.0, 100.0)),
       dt=st.floats(1e-4, 0.1))
def test_velocity_decay_shrinks_each_component_without_reversing_it(v, w, rates, dt):
    v2, w2 = velocity_decay(v, w, rates, dt)
    for before, after in ((v, v2), (w, w2)):
        assert np.all(np.abs(after) <= np.abs(before))
        assert np.all(after * before >= 0.0)
    # zero rate: untouched
    v3, w3 = velocity_decay(v, w, np.zeros(6), dt)
    assert np.array_equal(v3, v) and np.array_equal(w3, w)
