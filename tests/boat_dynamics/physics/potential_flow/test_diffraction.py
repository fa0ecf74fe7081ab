"""The diffraction force from a BEM solution, and the total wave excitation against Capytaine."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from boat_dynamics.physics.core.boat import BoatInputs, evaluate_forces, initial_state
from boat_dynamics.physics.core.pipeline import init_scenario
from boat_dynamics.physics.potential_flow.diffraction import diffraction_wrench
from boat_dynamics.physics.potential_flow.hydro import load_coefficients
from boat_dynamics.physics.scenario import parse_scenario
from ocean_sim.physics.waves import WaveComponent, WaveField

BOX = Path(__file__).resolve().parents[3] / "data" / "hydro" / "box_4x2x1_d0.5.npz"


def _excitation(params, sea, omega, position=(0.0, 0.0), yaw=0.0, a=0.005):
    """(6,) complex first harmonic per metre of amplitude of buoyancy + diffraction on the
    boat held at its mean pose: x(t) = Re[X e^{-i omega t}]."""
    times = np.arange(24) * (2 * math.pi / omega) / 24
    rows = []
    for t in times:
        f = evaluate_forces(params, initial_state(params, [*position, 0.0], yaw=yaw, t=t),
                            BoatInputs(), sea)
        rows.append(np.concatenate([f.buoyancy.force + f.diffraction.force,
                                    f.buoyancy.torque + f.diffraction.torque]))
    return 2 * (np.exp(1j * omega * times) @ np.array(rows)) / len(times) / a


def _boat(sea):
    sc = parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                    "buoyancy": {"pressure": "froude_krylov"},
                                    "hydrodynamics": {"coefficients": str(BOX)}}]})
    return init_scenario(replace(sc, sea=sea)).boats[0].params


@pytest.mark.parametrize("direction_deg", [0, 45, 90, 135, 180])
@pytest.mark.parametrize("index", [3, 8, 13, 18])
def test_wave_excitation_on_a_fixed_hull_is_froude_krylov_plus_diffraction(direction_deg,
                                                                           index):
    # The bound: within 10 % of Capytaine's Froude-Krylov + diffraction force (all six
    # dofs, amplitude and phase; wavelengths 8.0, 1.9, 0.82 and 0.46 boat lengths).
    ref = load_coefficients(BOX)
    omega = float(ref.omega[index])
    d = int(np.argmin(np.abs(ref.directions - math.radians(direction_deg))))
    sea = WaveField((WaveComponent(0.005, 2 * math.pi * 9.81 / omega**2,
                                   math.radians(direction_deg), 0.0, 0.0),))
    measured = _excitation(_boat(sea), sea, omega)
    expected = ref.froude_krylov[index, d] + ref.diffraction[index, d]
    assert np.abs(measured - expected).max() <= 0.10 * np.abs(expected).max()


def test_diffraction_follows_the_boats_heading_and_position():
    # A boat yawed by psi in a wave travelling at beta + psi feels in its body frame what an
    # unyawed boat feels at beta; moved by dx along the wave, the force is the same, later by
    # the phase k dx.
    ref = load_coefficients(BOX)
    omega = 3.0
    k = omega**2 / 9.81
    psi, beta = math.radians(30.0), math.radians(60.0)
    straight = WaveField((WaveComponent(1.0, 2 * math.pi / k, beta, 0.0, 0.3),))
    turned = WaveField((WaveComponent(1.0, 2 * math.pi / k, beta + psi, 0.0, 0.3),))
    for t in (0.0, 0.4, 1.1):
        a = diffraction_wrench(ref, straight, np.zeros(2), 0.0, t)
        b = diffraction_wrench(ref, turned, np.zeros(2), psi, t)
        np.testing.assert_allclose(np.concatenate(b), np.concatenate(a), atol=1e-9)
    dx = 1.7 * np.array([math.cos(beta), math.sin(beta)])
    shifted = diffraction_wrench(ref, straight, dx, 0.0, 0.9 + k * 1.7 / omega)
    np.testing.assert_allclose(np.concatenate(shifted),
                               np.concatenate(diffraction_wrench(ref, straight, np.zeros(2),
                                                                 0.0, 0.9)), atol=1e-9)
    # and it is there: Capytaine's transfer function at this frequency and direction
    x = ref.diffraction_at(np.array([omega]), np.array([beta]))[0]
    f, m = diffraction_wrench(ref, straight, np.zeros(2), 0.0, 0.0)
    np.testing.assert_allclose(np.concatenate([f, m]), (x * np.exp(0.3j)).real, atol=1e-9)


def test_mirrored_directions_mirror_sway_roll_and_yaw():
    ref = load_coefficients(BOX)
    w = np.array([2.5, 2.5])
    up, down = ref.diffraction_at(w, np.array([math.radians(40.0), math.radians(-40.0)]))
    np.testing.assert_allclose(down, up * np.array([1, -1, 1, -1, 1, -1]), atol=1e-9)


def test_a_boat_without_coefficients_feels_no_diffraction():
    sc = init_scenario(parse_scenario({"boats": [{"hydrodynamics": {"coefficients": "none"}}]}))
    sea = WaveField((WaveComponent(0.3, 10.0, 0.0, 0.5, 0.0),))
    f = evaluate_forces(sc.boats[0].params, sc.boats[0].initial, BoatInputs(), sea)
    assert not f.diffraction.force.any() and not f.diffraction.torque.any()


def test_boats_sharing_coefficients_are_evaluated_together_as_alone():
    # The pipeline evaluates boats with one coefficient set in one call: each boat's wrench
    # equals its own evaluation (positions, headings differ; two components, two directions).
    ref = load_coefficients(BOX)
    sea = WaveField((WaveComponent(0.4, 15.0, 0.3, 0.0, 0.2),
                     WaveComponent(0.2, 6.0, 2.0, 0.0, 1.0)))
    xy = np.array([[0.0, 0.0], [5.0, -3.0], [-12.0, 7.5]])
    psi = np.array([0.0, 1.2, -2.9])
    force, torque = diffraction_wrench(ref, sea, xy, psi, 4.2)
    for g in range(3):
        f, m = diffraction_wrench(ref, sea, xy[g], float(psi[g]), 4.2)
        np.testing.assert_allclose(force[g], f, rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(torque[g], m, rtol=1e-12, atol=1e-9)
    assert np.abs(force).max() > 100.0  # N: a real force
