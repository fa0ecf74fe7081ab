"""The added mass at forward speed (the Munk moment), and the encounter frequency."""

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.potential_flow.added_mass import added_mass_coriolis
from boat_dynamics.physics.potential_flow.diffraction import excitation_wrench
from boat_dynamics.physics.potential_flow.hydro import load_coefficients
from ocean_sim.physics.waves import WaveComponent, WaveField, angular_frequency

BOX = Path(__file__).resolve().parents[3] / "data" / "hydro" / "box_4x2x1_d0.5.npz"
RHO = 1025.0


def _spheroid(length: float, diameter: float) -> tuple[np.ndarray, float]:
    """(6, 6) added mass of a prolate spheroid about its centre, and its volume (Lamb 1932,
    sec. 373: k1 = alpha0 / (2 - alpha0), k2 = beta0 / (2 - beta0), k' for rotation)."""
    a, b = length / 2, diameter / 2
    e = math.sqrt(1 - (b / a) ** 2)
    log = math.log((1 + e) / (1 - e))
    alpha0 = 2 * (1 - e * e) / e**3 * (0.5 * log - e)
    beta0 = 1 / e**2 - (1 - e * e) / (2 * e**3) * log
    volume = 4 / 3 * math.pi * a * b * b
    k1, k2 = alpha0 / (2 - alpha0), beta0 / (2 - beta0)
    k_rot = (e**4 * (beta0 - alpha0)
             / ((2 - e * e) * (2 * e * e - (2 - e * e) * (beta0 - alpha0))))
    inertia = volume * (a * a + b * b) / 5
    return np.diag([k1 * RHO * volume, k2 * RHO * volume, k2 * RHO * volume, 0.0,
                    k_rot * RHO * inertia, k_rot * RHO * inertia]), volume


def test_a_slender_body_at_a_drift_angle_feels_the_munk_moment():
    """Newman (1977), sec. 4.13: M = -U^2 sin(beta) cos(beta) (m22 - m11), turning it broadside."""
    added, _ = _spheroid(8.0, 1.0)
    speed, drift = 3.0, math.radians(5.0)
    velocity = np.array([[speed * math.cos(drift), speed * math.sin(drift), 0.0]])
    w = added_mass_coriolis(added[None], velocity, np.zeros((1, 3)))
    munk = -speed**2 * math.sin(drift) * math.cos(drift) * (added[1, 1] - added[0, 0])
    assert w.torque[0, 2] == pytest.approx(munk, rel=1e-12)
    assert w.torque[0, 2] < 0.0  # drifting to port, the bow turns to starboard: broadside
    assert np.abs(w.force).max() == 0.0 and w.torque[0, :2].tolist() == [0.0, 0.0]
    # the slender limit: m22 -> rho pi r^2 L / ... = rho V, m11 -> 0 (k2 -> 1, k1 -> 0)
    slender, volume = _spheroid(100.0, 1.0)
    assert slender[1, 1] / (RHO * volume) == pytest.approx(1.0, abs=0.01)


def test_a_steady_turn_feels_the_added_masss_centripetal_force():
    added = np.diag([300.0, 900.0, 5000.0, 800.0, 5000.0, 1000.0])[None]
    u, r = 2.0, 0.1
    w = added_mass_coriolis(added, np.array([[u, 0.0, 0.0]]), np.array([[0.0, 0.0, r]]))
    assert w.force[0].tolist() == pytest.approx([0.0, -300.0 * u * r, 0.0])  # Y = -A11 u r
    assert not w.torque.any()
    # heave, roll and pitch motions are left to the radiation memory (module docstring)
    w = added_mass_coriolis(added, np.array([[u, 0.0, 0.7]]), np.array([[0.3, 0.4, 0.0]]))
    assert not np.abs(np.concatenate([w.force, w.torque], axis=1)).any()


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(-5, 5), min_size=6, max_size=6),
       st.lists(st.floats(-1000, 1000), min_size=21, max_size=21))
def test_the_added_masss_coriolis_force_does_no_work(nu, entries):
    upper = np.zeros((6, 6))
    upper[np.triu_indices(6)] = entries
    added = (upper + upper.T)[None]
    v = np.array([[nu[0], nu[1], 0.0]])
    w = np.array([[0.0, 0.0, nu[5]]])
    wrench = added_mass_coriolis(added, v, w)
    power = float(wrench.force[0] @ v[0] + wrench.torque[0] @ w[0])
    scale = max(1.0, float(np.abs(added).max()) * 25.0)
    assert abs(power) <= 1e-9 * scale


def test_a_boat_crossing_a_regular_wave_meets_it_at_the_encounter_frequency():
    """omega_e = omega - k U cos(beta): into a head wave faster, running before it slower."""
    hydro = load_coefficients(BOX)
    wave = WaveComponent(0.1, 12.0, 0.0, 0.0, 0.0)
    sea = WaveField((wave,))
    omega = float(angular_frequency(wave.wavenumber, sea.gravity, sea.depth))
    for heading, speed in ((math.pi, 2.0), (0.0, 1.5), (0.0, 6.0)):  # 6 m/s overtakes it
        velocity = speed * np.array([math.cos(heading), math.sin(heading)])
        encounter = omega - wave.wavenumber * velocity[0]
        times = np.linspace(0.0, 12 * 2 * math.pi / abs(encounter), 2401)
        heave = np.array([excitation_wrench(hydro, sea, velocity * t, heading, t,
                                            "diffraction", velocity)[0][2] for t in times])
        crossings = np.flatnonzero(np.diff(np.sign(heave)) != 0)
        period = 2 * (times[crossings[-1]] - times[crossings[0]]) / (crossings.size - 1)
        assert 2 * math.pi / period == pytest.approx(abs(encounter), rel=0.01)
        # its size is the transfer function's at the encounter frequency
        seen = -heading + (math.pi if encounter < 0 else 0.0)  # relative to the bow
        expected = abs(hydro.diffraction_at(np.array([abs(encounter)]),
                                            np.array([seen]))[0, 2]) * wave.amplitude
        assert np.abs(heave).max() == pytest.approx(expected, rel=0.01)
        at_rest = abs(hydro.diffraction_at(np.array([omega]), np.array([seen]))[0, 2])
        assert abs(expected - at_rest * wave.amplitude) > 0.05 * expected  # it matters
