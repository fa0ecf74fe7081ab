"""Critical damping helper, damping regimes, energy, shooting out, substeps."""

import math
from dataclasses import replace

import numpy as np
import pytest
from ready_scenarios import SEED_MODEL, ready

from boat_dynamics.physics.core.boat import BoatInputs, initial_state, reference_pose, step
from boat_dynamics.physics.core.tuning import (
    critical_damping,
    equilibrium_height,
    hydrostatic_stiffness,
)
from ocean_sim.physics.waves import WaveField

FLAT = WaveField()


@pytest.mark.parametrize("model", ["mesh", "sample_points"])
def test_stiffness_and_equilibrium_of_a_box(boat_factory, model):
    params = boat_factory(density_ratio=0.4, com=(0, 0, -0.2), model=model, grid=(20, 20))
    assert equilibrium_height(params) == pytest.approx(0.5 - 0.4, abs=1e-9)
    k = hydrostatic_stiffness(params)
    assert k[0] == pytest.approx(1025 * 9.81 * 8.0, rel=1e-6)
    d = 0.4
    gm_t = d / 2 + 2.0**2 / (12 * d) - (0.5 - 0.2)
    gm_l = d / 2 + 4.0**2 / (12 * d) - (0.5 - 0.2)
    # mesh: exact; sample points: the 20 x 20 grid of columns is exact up to discretization
    tol = 1e-4 if model == "mesh" else 0.01
    assert k[1] == pytest.approx(params.mass * 9.81 * gm_t, rel=tol)
    assert k[2] == pytest.approx(params.mass * 9.81 * gm_l, rel=tol)


def heave_response(params, seconds=10.0, dt=0.002, z0=0.1):
    z_eq = equilibrium_height(params)
    state = initial_state(params, [0.0, 0.0, z_eq + z0])
    zs = []
    for _ in range(round(seconds / dt)):
        state = step(params, state, BoatInputs(), FLAT, dt)
        zs.append(reference_pose(params, state)[0][2] - z_eq)
    return np.array(zs)


def test_critical_damping_gives_no_overshoot(boat_factory):
    base = boat_factory(model="mesh")
    params = replace(base, damping_linear=critical_damping(base, [1.0, 0.0, 0.0]))
    zs = heave_response(params)
    assert zs.min() > -1e-4  # never crosses below equilibrium (0.1 m start)
    assert abs(zs[-1]) < 1e-4
    # and it is the fastest such return: 0.9 x critical does overshoot
    under = replace(base, damping_linear=critical_damping(base, [0.9, 0.0, 0.0]))
    assert heave_response(under).min() < -1e-4


def test_quadratic_damping_still_oscillates(boat_factory):
    params = boat_factory(model="mesh", quadratic=(0, 0, 50000.0, 0, 0, 0))
    zs = heave_response(params, seconds=20.0)
    crossings = np.flatnonzero(np.sign(zs[:-1]) != np.sign(zs[1:]))
    assert len(crossings) >= 6  # keeps crossing the equilibrium
    assert np.abs(zs[-1000:]).max() < 0.5 * np.abs(zs[:1000]).max()  # with decaying amplitude


def test_energy_without_damping_is_bounded_over_100_s(boat_factory):
    params = boat_factory(model="mesh")
    k = 1025 * 9.81 * 8.0
    z_eq = equilibrium_height(params)
    state = initial_state(params, [0.0, 0.0, z_eq + 0.1])
    dt = 0.01
    energies = []
    for _ in range(round(100.0 / dt)):
        state = step(params, state, BoatInputs(), FLAT, dt)
        z = reference_pose(params, state)[0][2] - z_eq
        energies.append(0.5 * params.mass * state.velocity @ state.velocity + 0.5 * k * z * z)
    e = np.array(energies)
    e0 = 0.5 * k * 0.1**2
    assert np.abs(e / e0 - 1.0).max() < 0.05  # symplectic Euler: O(omega dt), no drift
    assert e[-1000:].mean() == pytest.approx(e[:1000].mean(), rel=0.005)


@pytest.mark.parametrize("sea", [{}, {"components": [
    {"amplitude": 0.4, "wavelength": 20.0, "steepness": 0.8},
    {"amplitude": 0.2, "wavelength": 9.0, "direction_deg": 40, "steepness": 0.6}]}])
def test_no_shooting_out_with_defaults(sea):
    """A hull released 5 m deep breaks the surface without flying clear of it.

    The default model (Froude-Krylov pressure, the hull's coefficients): a half-density box
    rising at about 3 m/s against its heave drag may break out a little, as a real one does;
    the numerical shooting out of the seed notes (and a constant added mass carried out of the
    water: its bottom 0.38 and 0.92 m above the surface) throws it clear. The
    clearance is the lowest vertex's height above the surface there (zero while any part is
    wet). Bounds: in calm water a tenth of its height; in any sea no higher than its fastest
    rise would carry it, v^2 / 2 g (flying higher, the water would have given it energy it
    does not have: the shooting out). Measured: never clear in calm water; in the
    steep sea 0.26 m for an instant (0.074 m with 10 % of critical heave damping, the default
    with coefficients until then).
    """
    from boat_dynamics.physics.body.rigid_body import rotation_matrix
    from boat_dynamics.physics.core.contact import contact
    from boat_dynamics.physics.core.system import FleetState, System

    sc = ready({"ocean": sea, "boats": [{}]})
    boat = sc.boats[0]
    params = boat.params
    state = initial_state(params, [0.0, 0.0, -5.0])
    dt = 1.0 / sc.simulation.rate_hz
    from ocean_sim.physics.waves import surface_height
    top_above, clearance, rise = -math.inf, 0.0, 0.0
    system = System.build([params])
    for _ in range(round(15.0 / dt)):
        state = step(params, state, BoatInputs(), sc.sea, dt)
        rise = max(rise, float((rotation_matrix(state.orientation) @ state.velocity)[2]))
        depths = contact(system, FleetState.stack([state]), sc.sea).groups[0].depths
        clearance = max(clearance, -float(depths.max()))
        ref = reference_pose(params, state)[0]
        h = surface_height(sc.sea, ref[None, :2], state.t)[0]
        top_above = max(top_above, ref[2] + 0.5 - h)
    assert top_above > 0.2  # it broke the surface
    assert clearance < rise**2 / (2 * 9.81), (clearance, rise)
    if not sea:
        assert clearance < 0.1, clearance


def test_substeps_divide_the_step():
    sc = ready({"simulation": {"rate_hz": 50, "substeps": 4}})
    assert sc.simulation.substeps == 4
    from boat_dynamics.physics.scenario import ScenarioError
    with pytest.raises(ScenarioError, match=r"simulation.substeps: 0"):
        ready({"simulation": {"substeps": 0}})


def test_default_damping_is_derived_and_explicit_values_are_kept():
    default = ready({}).boats[0].params
    # with its coefficients (auto): none in heave and pitch (their radiation damps them),
    # 10 % of critical in roll with the added mass A_44 (inf)
    assert default.damping_linear[2] == 0.0 and default.damping_linear[4] == 0.0
    roll_inertia = default.inertia[0] + default.added_mass_matrix[3, 3]
    roll_stiffness = hydrostatic_stiffness(default)[1]
    assert default.damping_linear[3] == pytest.approx(
        0.1 * 2 * math.sqrt(roll_stiffness * roll_inertia), rel=1e-6)
    seed_model = ready({"boats": [SEED_MODEL]}).boats[0].params
    b_crit = 2 * math.sqrt(1025 * 9.81 * 8.0 * seed_model.mass)
    assert seed_model.damping_linear[2] == pytest.approx(0.2 * b_crit, rel=1e-6)
    assert default.damping_quadratic[2] == pytest.approx(0.5 * 1025 * 1.0 * 8.0)
    assert default.damping_quadratic[1] == pytest.approx(0.5 * 1025 * 1.0 * 4.0 * 0.5, rel=1e-6)
    explicit = ready({"boats": [{"damping": {"linear": [1, 2, 3, 4, 5, 6],
                                                       "quadratic": [0] * 6}}]})
    assert explicit.boats[0].params.damping_linear.tolist() == [1, 2, 3, 4, 5, 6]
    assert explicit.boats[0].params.damping_quadratic.tolist() == [0] * 6
