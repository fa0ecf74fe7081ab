"""The compiled pressure head and orbital velocity against their numpy oracles.

``waves.pressure_head`` and ``waves.orbital_velocity`` run the kernels of
:mod:`ocean_sim.physics.linear_kernel`; ``waves._pressure_head_numpy`` and
``waves._orbital_velocity_numpy`` are the numpy implementations they replaced, kept as the
oracle. They round differently (libm's exp against numpy's, a polynomial sin / cos, the sums'
order, the phase k D . x with or without a fused multiply-add), so they agree to 1e-12 of the
field's size plus what the phase's own rounding allows (a few ulp of k |x|: 1.5e-11 rad for
a 2 m wave 5 km out), not to the bit.
"""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from test_waves import admissible_seas

from ocean_sim.physics import waves
from ocean_sim.physics.waves import WaveComponent, WaveField, orbital_velocity, pressure_head


def _relative(sea: WaveField, xy: np.ndarray) -> float:
    """The relative tolerance: 1e-12, plus four ulp of the largest phase k D . x."""
    phase = np.abs(xy @ sea.arrays.kd).max()
    return 1e-12 + 4.0 * np.finfo(float).eps * float(phase)


def _points(sea: WaveField, seed: int, n: int, offset: float):
    """Points (N, 2) m, their surface heights (N,) m and heights (N,) m from above the crests
    to below the bed (both clipped by the stretching)."""
    rng = np.random.default_rng(seed)
    xy = rng.uniform(-300.0, 300.0, size=(n, 2)) + offset
    reach = sum(c.amplitude for c in sea.components)
    eta = rng.uniform(-reach, reach, n)
    bottom = min(sea.depth, 200.0)
    z = rng.uniform(-1.2 * bottom, reach + 0.5, n)
    return xy, eta, z


def _head_scale(sea: WaveField, z: np.ndarray) -> float:
    """m, the size of the pressure head: the waves' reach and the deepest point's depth."""
    return sum(c.amplitude for c in sea.components) + float(np.abs(z).max())


def _velocity_scale(sea: WaveField, z: np.ndarray) -> float:
    """m/s, the size of the orbital velocity: sum a omega, times coth(k h) at depth h."""
    ar = sea.arrays
    return float(np.sum(ar.a * ar.omega)) / math.tanh(float(ar.k.min()) * min(sea.depth, 1e6))


#: The compiled function, its numpy oracle, and the size of what they return.
PAIRS = {"pressure head": (pressure_head, waves._pressure_head_numpy, _head_scale),
         "orbital velocity": (orbital_velocity, waves._orbital_velocity_numpy, _velocity_scale)}


@settings(max_examples=300, deadline=None)
@given(sea=admissible_seas(max_ak=0.45), t=st.floats(0.0, 1e4), seed=st.integers(0, 2**16),
       offset=st.sampled_from([0.0, 5000.0]), which=st.sampled_from(sorted(PAIRS)))
def test_the_compiled_kernels_equal_their_numpy_oracles(sea, t, seed, offset, which):
    compiled, oracle, size = PAIRS[which]
    xy, eta, z = _points(sea, seed, 80, offset)
    got, want = compiled(sea, xy, eta, z, t), oracle(sea, xy, eta, z, t)
    assert got.shape == want.shape and got.shape[0] == 80
    assert np.abs(got - want).max() <= _relative(sea, xy) * max(size(sea, z), 1e-300)


def test_deep_water_at_the_surface_is_the_airy_closed_form():
    # one component along x: p/(rho g) = a cos(theta) - z at z = eta = 0; u = a w cos, w = a w sin
    sea = WaveField((WaveComponent(0.5, 20.0, 0.0, 0.0, 0.3),))
    k, omega = 2 * math.pi / 20.0, math.sqrt(9.81 * 2 * math.pi / 20.0)
    x = np.linspace(-30.0, 30.0, 13)
    xy, zero = np.column_stack([x, np.zeros(13)]), np.zeros(13)
    theta = k * x - omega * 2.0 + 0.3
    assert np.abs(pressure_head(sea, xy, zero, zero, 2.0) - 0.5 * np.cos(theta)).max() < 1e-14
    u = orbital_velocity(sea, xy, zero, zero - 3.0, 2.0)  # 3 m down: e^{-3 k}
    decay = math.exp(-3.0 * k)
    assert np.abs(u[:, 0] - 0.5 * omega * np.cos(theta) * decay).max() < 1e-14
    assert np.abs(u[:, 1]).max() == 0.0
    assert np.abs(u[:, 2] - 0.5 * omega * np.sin(theta) * decay).max() < 1e-14
