"""The compiled Cummins memory and added mass at speed against their numpy oracles."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.potential_flow.added_mass import (
    _added_mass_coriolis_numpy,
    added_mass_coriolis,
)
from boat_dynamics.physics.potential_flow.radiation import (
    _advance_numpy,
    _memory_wrench_numpy,
    advance,
    memory_wrench,
)

_SIZES = dict(seed=st.integers(0, 2**32 - 1), boats=st.integers(1, 12), order=st.integers(1, 40))


def _complex(rng, *shape):
    return rng.normal(size=shape) + 1j * rng.normal(size=shape)


def _close(got, want, name=""):
    scale = np.abs(want).max(initial=0.0) + 1e-300
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * scale, err_msg=name)


@settings(max_examples=100, deadline=None)
@given(dt=st.floats(1e-4, 0.5), **_SIZES)
def test_the_memory_advances_as_numpys(seed, boats, order, dt):
    rng = np.random.default_rng(seed)
    # stable poles, decaying from 0.01 to 100 per s, oscillating up to 20 rad/s
    poles = -10.0 ** rng.uniform(-2, 2, size=(boats, order)) + 1j * rng.uniform(
        -20, 20, size=(boats, order))
    args = (poles, _complex(rng, boats, order, 6) * 1e4, _complex(rng, boats, order),
            rng.normal(size=(boats, 6)), rng.normal(size=(boats, 6)), dt)
    _close(advance(*args), _advance_numpy(*args))


@settings(max_examples=100, deadline=None)
@given(**_SIZES)
def test_the_memory_wrench_is_numpys_times_the_share_carried(seed, boats, order):
    rng = np.random.default_rng(seed)
    output, z = _complex(rng, boats, 6, order) * 1e3, _complex(rng, boats, order)
    carried = rng.uniform(0.0, 1.0, size=boats)
    want_force, want_torque = _memory_wrench_numpy(output, z)
    force, torque = memory_wrench(output, z, carried)
    _close(force, want_force * carried[:, None], "force")
    _close(torque, want_torque * carried[:, None], "torque")
    force, torque = memory_wrench(output, z)  # all carried
    _close(force, want_force, "force")
    _close(torque, want_torque, "torque")


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), boats=st.integers(1, 12))
def test_the_added_mass_at_speed_is_numpys(seed, boats):
    rng = np.random.default_rng(seed)
    added = rng.normal(size=(boats, 6, 6)) * 1e3
    added = added + added.transpose(0, 2, 1)
    v, w = rng.normal(size=(boats, 3)) * 5.0, rng.normal(size=(boats, 3))
    carried = rng.uniform(0.0, 1.0, size=boats)
    want = _added_mass_coriolis_numpy(added * carried[:, None, None], v, w)
    got = added_mass_coriolis(added, v, w, carried)
    _close(got.force, want.force, "force")
    _close(got.torque, want.torque, "torque")
    # no work on the horizontal plane: Q . nu = 0
    power = (got.force[:, 0] * v[:, 0] + got.force[:, 1] * v[:, 1] + got.torque[:, 2] * w[:, 2])
    np.testing.assert_allclose(power, 0.0, atol=1e-9 * (np.abs(added).max() * 25.0))
