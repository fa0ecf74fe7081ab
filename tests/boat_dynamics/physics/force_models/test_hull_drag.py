"""ITTC 1957 friction and pressure drag on the wetted triangles of a box."""

import math
from dataclasses import replace

import numpy as np
import pytest
from ready_scenarios import ready

from boat_dynamics.physics.core.boat import BoatInputs, evaluate_forces, initial_state
from boat_dynamics.physics.force_models.hull_drag import HullDrag, friction_coefficient
from boat_dynamics.physics.scenario import ScenarioError
from ocean_sim.physics.waves import WaveField

L, B, D, U = 4.0, 2.0, 0.5, 2.0


def moving_box(drag):
    sc = ready({"boats": [{"damping": {"linear": [0] * 6, "quadratic": [0] * 6}}]})
    params = sc.boats[0].params
    params = replace(params, buoyancy=replace(params.buoyancy, drag=drag))
    state = replace(initial_state(params, [0.0, 0.0, 0.0]), velocity=np.array([U, 0.0, 0.0]))
    return evaluate_forces(params, state, BoatInputs(), WaveField()).drag


def test_friction_coefficient_is_the_ittc_line():
    assert friction_coefficient(1.0, 10.0, 1e-6) == pytest.approx(0.075 / 25.0)
    assert friction_coefficient(0.0, 10.0, 1e-6) == 0.0


def test_viscous_resistance_acts_on_the_wetted_surface_along_the_flow():
    drag = moving_box(HullDrag(viscous=True, form_factor=0.2))
    cf = friction_coefficient(U, L, 1.19e-6)
    wetted = L * B + 2 * L * D  # bottom and sides; bow and stern see no tangential flow
    expected = -0.5 * 1025.0 * cf * 1.2 * wetted * U * U
    assert drag.force[0] == pytest.approx(expected, rel=1e-9)
    assert abs(drag.force[1]) < 1e-9 and abs(drag.force[2]) < 1e-9


def test_pressure_drag_pushes_the_bow_and_pulls_the_stern():
    drag = moving_box(HullDrag(pressure=True, pressure_linear=20.0, pressure_quadratic=5.0,
                               suction_linear=4.0, suction_quadratic=1.0))
    bow = (20.0 * U + 5.0 * U * U) * B * D
    stern = (4.0 * U + 1.0 * U * U) * B * D
    assert drag.force[0] == pytest.approx(-(bow + stern), rel=1e-9)


def test_no_drag_by_default_and_scenario_keys():
    assert not moving_box(HullDrag()).force.any()
    sc = ready({"boats": [{"buoyancy": {"model": "mesh",
                                                 "drag": {"viscous": True, "pressure": True,
                                                          "form_factor": 0.1}}}]})
    assert sc.boats[0].params.buoyancy.drag.viscous
    with pytest.raises(ScenarioError,
                       match=r"buoyancy.drag: \{\} is not allowed: only for model mesh"):
        ready({"boats": [{"buoyancy": {"model": "sample_points", "drag": {}}}]})
    assert math.isclose(ready({"boats": [{"inertia": [1, 2, 3],
                                                   "inertia_scale": [2, 2, 2]}]})
                        .boats[0].params.inertia[2], 6.0)
