"""The Cummins radiation memory: its kernel, its fit to Capytaine's coefficients, its stepping."""

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.potential_flow.hydro import load_coefficients
from boat_dynamics.physics.potential_flow.radiation import (
    MAX_ORDER,
    advance,
    fit_memory,
    memory_wrench,
    retardation_kernel,
)

BOX = Path(__file__).resolve().parents[3] / "data" / "hydro" / "box_4x2x1_d0.5.npz"


@pytest.fixture(scope="module")
def hydro():
    return load_coefficients(BOX)


@pytest.fixture(scope="module")
def memory(hydro):
    return fit_memory(hydro)


@pytest.mark.parametrize("t", [0.0, 0.37, 1.5, 6.0])
def test_the_kernel_is_the_cosine_transform_of_the_damping(hydro, t):
    # Closed form against a fine trapezoid rule on the same piecewise-linear B (0 at 0, the
    # file's grid, tapered to 0 at 2 omega_W).
    grid = np.concatenate([[0.0], hydro.omega, [2 * hydro.omega[-1]]])
    omega = np.linspace(0.0, grid[-1], 400_001)
    expected = np.empty((6, 6))
    for i in range(6):
        for j in range(6):
            b = np.interp(omega, grid,
                          np.concatenate([[0.0], hydro.radiation_damping[:, i, j], [0.0]]))
            expected[i, j] = 2 / np.pi * np.trapezoid(b * np.cos(omega * t), omega)
    got = retardation_kernel(hydro, np.array([t]))[0]
    assert np.abs(got - expected).max() <= 1e-6 * np.abs(expected).max()


def test_the_fitted_memory_is_stable_and_reproduces_the_damping(hydro, memory):
    # B(omega) = Re K^(omega) of the fit against the file, per entry relative to
    # sqrt(max B_ii max B_jj) (the fit's own tolerance, 3 %); every mode decays.
    assert memory.poles.shape[0] <= MAX_ORDER
    assert np.all(memory.poles.real < 0.0)
    response = memory.response(hydro.omega)
    scale = np.abs(np.diagonal(hydro.radiation_damping, axis1=1, axis2=2)).max(axis=0)
    error = np.abs(response.real - hydro.radiation_damping).max(axis=0)
    assert (error / np.sqrt(np.outer(scale, scale))).max() <= 0.03
    assert memory.error <= 0.03


def test_the_fitted_memory_gives_capytaines_added_mass(hydro, memory):
    # Kramers-Kronig: the memory is fitted to B alone, so its A(omega) = A_inf + Im K^ / omega
    # is an independent check against the file's added mass (3 % of the diagonal scale;
    # heave 1.1 % and roll 0.5 % measured).
    response = memory.response(hydro.omega)
    added = hydro.added_mass_inf + response.imag / hydro.omega[:, None, None]
    scale = np.abs(np.diagonal(hydro.added_mass, axis1=1, axis2=2)).max(axis=0)
    error = np.abs(added - hydro.added_mass).max(axis=0)
    assert (error / np.sqrt(np.outer(scale, scale))).max() <= 0.03


def test_a_steady_velocity_leaves_no_memory_force(hydro, memory):
    # K^(0) = B(0) = 0 in deep water: a hull at constant speed makes no lasting radiation
    # force. After 60 s of steady 1 m/s surge and 0.2 rad/s yaw: under 3 % of the force of
    # the kernel's peak B over one second.
    z = np.zeros((1, memory.poles.shape[0]), complex)
    nu = np.array([[1.0, 0.0, 0.0, 0.0, 0.0, 0.2]])
    for _ in range(600):
        z = advance(memory.poles[None], memory.input[None], z, nu, nu, 0.1)
    force, torque = memory_wrench(memory.output[None], z)
    peak = retardation_kernel(hydro, np.array([0.0]))[0]
    assert abs(force[0, 0]) <= 0.03 * peak[0, 0]
    assert abs(torque[0, 2]) <= 0.03 * peak[5, 5] * 0.2


def test_the_memory_step_is_the_convolution(hydro, memory):
    # z advanced with a velocity ramp equals the convolution integral of the kernel with that
    # ramp (the memory force of a ramp, trapezoid on a fine grid).
    dt, steps = 0.05, 80
    t_end = dt * steps
    z = np.zeros((1, memory.poles.shape[0]), complex)
    unit = np.zeros(6)
    unit[2] = 1.0
    for k in range(steps):
        z = advance(memory.poles[None], memory.input[None], z, (k * dt * unit)[None],
                    ((k + 1) * dt * unit)[None], dt)
    force = memory_wrench(memory.output[None], z)[0][0, 2]
    tau = np.linspace(0.0, t_end, 20_001)
    kernel = np.einsum("in,tn,n->t", memory.output[2:3],
                       np.exp(np.outer(t_end - tau, memory.poles)), memory.input[:, 2]).real
    expected = -np.trapezoid(kernel * tau, tau)
    assert force == pytest.approx(expected, rel=1e-6)


@settings(max_examples=30, deadline=None)
@given(dt=st.floats(0.001, 0.2), start=st.lists(st.floats(-2, 2), min_size=6, max_size=6),
       slope=st.lists(st.floats(-5, 5), min_size=6, max_size=6))
def test_two_half_steps_equal_one_step_for_a_linear_velocity(memory, dt, start, slope):
    # The first-order hold is exact for a velocity linear in time: splitting the step changes
    # nothing but rounding.
    p, b = memory.poles[None], memory.input[None]
    u0, du = np.array([start]), np.array([slope])
    z0 = np.exp(1j * np.arange(memory.poles.shape[0]))[None] * 10.0
    one = advance(p, b, z0, u0, u0 + du * dt, dt)
    half = advance(p, b, z0, u0, u0 + du * dt / 2, dt / 2)
    two = advance(p, b, half, u0 + du * dt / 2, u0 + du * dt, dt / 2)
    assert np.allclose(one, two, rtol=1e-9, atol=1e-9 * (1 + np.abs(one).max()))
