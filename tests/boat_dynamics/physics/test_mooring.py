"""The soft mooring of the RAO runs: a critically damped spring on x, y and heading."""

import math
from dataclasses import replace

import numpy as np
import pytest

from boat_dynamics.physics import pipeline
from boat_dynamics.physics.model import BoatInputs, initial_state
from boat_dynamics.physics.mooring import mooring_wrench, soft_mooring
from boat_dynamics.physics.rigid_body import quat_to_euler, rotation_matrix
from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.physics.system import FleetInputs, FleetState, System
from ocean_sim.physics.waves import WaveField

NO_DAMPING = {"linear": [0.0] * 6, "quadratic": [0.0] * 6}


def _moored_box(period: float):
    params = parse_scenario({"boats": [{"damping": NO_DAMPING, "buoyancy": {
        "pressure": "hydrostatic"}, "hydrodynamics": {"coefficients": "none"}}]}).boats[0].params
    mass = np.array([params.mass, params.mass, params.inertia[2]])
    return replace(params, mooring=soft_mooring(np.zeros(3), mass, period))


@pytest.mark.parametrize(("offset", "yaw"), [((1.0, 0.0), 0.0), ((0.0, -0.5), 0.0),
                                             ((0.0, 0.0), 0.3)])
def test_a_displaced_hull_returns_as_a_critically_damped_oscillator(offset, yaw):
    # x(t) = x0 (1 + omega t) e^{-omega t} (no overshoot), in still water, no other damping:
    # within 1 % of the start offset at a quarter, half and one natural period.
    period = 20.0
    params = _moored_box(period)
    sea = WaveField()
    start = initial_state(params, np.array([*offset, 0.0]), yaw=yaw)
    system, state = pipeline.init(System.build([params]), FleetState.stack([start]), sea)
    omega, dt = 2 * math.pi / period, 0.01
    inputs = FleetInputs.stack([BoatInputs()])
    x0 = np.array([*offset, yaw])
    for t_end in (period / 4, period / 2, period):
        while state.t < t_end - dt / 2:
            state = pipeline.step(system, state, inputs, sea, dt).state
        now = np.array([*(state.position[0, :2] - params.center_of_mass[:2]),
                        quat_to_euler(state.orientation[0])[2]])
        expected = x0 * (1 + omega * state.t) * math.exp(-omega * state.t)
        assert np.abs(now - expected).max() <= 0.01 * np.abs(x0).max()


def test_the_mooring_pulls_horizontally_at_the_centre_of_mass():
    # Upright: no vertical force, no roll or pitch moment; the force opposes the offset and
    # the yaw moment the heading error (the shorter way round: 350 deg is -10 deg).
    rotation = rotation_matrix(np.array([0.0, 0.0, math.sin(math.radians(175)),
                                         math.cos(math.radians(175))]))[None]
    w = mooring_wrench(np.array([[100.0, 200.0, 50.0]]), np.zeros((1, 3)), np.zeros((1, 3)),
                       np.array([[1.0, -2.0, 0.3]]), rotation, np.zeros((1, 3)),
                       np.zeros((1, 3)))
    world_force = rotation[0] @ w.force[0]
    assert world_force == pytest.approx([-100.0, 400.0, 0.0])
    assert w.torque[0, :2] == pytest.approx([0.0, 0.0], abs=1e-12)
    assert w.torque[0, 2] == pytest.approx(50.0 * math.radians(10.0))


def test_a_free_boat_beside_a_moored_one_steps_as_if_alone():
    moored = _moored_box(30.0)
    free = parse_scenario({"boats": [{"damping": NO_DAMPING}]}).boats[0].params
    sea = WaveField()
    starts = [initial_state(moored, np.array([0.5, 0.0, 0.0])),
              initial_state(free, np.array([10.0, 0.0, 0.0]))]
    both, state = pipeline.init(System.build([moored, free]), FleetState.stack(starts), sea)
    alone, single = pipeline.init(System.build([free]), FleetState.stack(starts[1:]), sea)
    inputs2, inputs1 = (FleetInputs.stack([BoatInputs(0.5, 0.1)] * n) for n in (2, 1))
    for _ in range(200):
        step = pipeline.step(both, state, inputs2, sea, 0.01)
        state = step.state
        single = pipeline.step(alone, single, inputs1, sea, 0.01).state
    # as tests/boat_dynamics/physics/test_pipeline.py's fleet test: equal to summation order
    np.testing.assert_allclose(state.position[1], single.position[0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(state.orientation[1], single.orientation[0], rtol=0, atol=1e-12)
    assert np.abs(step.forces.mooring.force[0]).max() > 0.0
    assert not step.forces.mooring.force[1].any()
