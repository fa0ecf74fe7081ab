"""Stepping boats together as a fleet is stepping each alone (one implementation, batched)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.boat import BoatInputs, step
from boat_dynamics.fleet import Fleet, FleetInputs, FleetState, contacts, fleet_step
from boat_dynamics.scenario import parse_scenario
from ocean_sim.waves import WaveComponent, WaveField

SEA = WaveField((WaveComponent(0.4, 20.0, 0.5, 0.8, 0.1), WaveComponent(0.2, 7.0, -1.0, 0.6, 2.0),
                 WaveComponent(0.05, 3.0, 2.0, 0.5, 1.0)))
DT = 0.01

#: Boats that take different code paths, and some that share one with different numbers.
BOATS = [
    {},
    {"mass": 2500.0, "hull": {"type": "box", "length": 5.0, "beam": 2.2, "height": 1.1}},
    {"hull": {"type": "box", "subdivisions": 2}, "buoyancy": {"drag": {"viscous": True,
                                                                       "pressure": True}}},
    {"buoyancy": {"model": "sample_points", "layout": "boat", "point_damping": 0.5,
                  "direction": "normal"}},
    {"buoyancy": {"model": "sample_points", "layout": "grid", "curve": "exponential",
                  "force_clamp": 0.8, "depth_scale": True},
     "propulsion": {"at_center_of_mass": True, "time_constant": 0.5},
     "rudder": {"model": "torque", "max_torque": 500}},
    {"propulsion": {"steerable": True}, "rudder": {"model": "none"}, "min_wavelength": 5.0},
    {"stokes_drift": True, "keel": {"model": "reflection", "rate": 0.5},
     "rudder": {"model": "hybrid", "max_torque": 1000, "base_torque": 200, "max_speed": 5}},
    {"control_mode": "kinematic", "control": {"attitude": "pd"}},
    {"control_mode": "constrained"},
    {"control_mode": "blend"},
    {"inertia": [3000, 9000, 10000], "inertia_products": [0, 800, 0]},
]


def fleet_scenario(boats=BOATS):
    # float64 queries: float32 results depend on the batch (its phase-reduction centre) at the
    # 1e-7 m level, which would hide a real difference between the fleet and lone boats
    return parse_scenario({"simulation": {"wave_precision": "float64"},
                           "boats": [dict(b, name=f"b{i}", initial_pose={
        "position": [9.0 * i, 3.0 * (i % 3), 0.0], "yaw_deg": 20.0 * i})
        for i, b in enumerate(boats)]})


def commands(n):
    return [BoatInputs(1.0 - 0.15 * i, 0.3 * np.sin(i)) for i in range(n)]


def test_a_mixed_fleet_stepped_together_equals_each_boat_alone():
    sc = fleet_scenario()
    params = [b.params for b in sc.boats]
    inputs = commands(len(params))
    fleet = Fleet(params)
    # boats 0, 1 and 7-10 share a code path (control modes apply after the step); 2-6 do not
    assert sorted(g.index.tolist() for g in fleet.groups) == [[0, 1, 7, 8, 9, 10], [2], [3],
                                                               [4], [5], [6]]
    state = FleetState.stack([b.initial for b in sc.boats])
    alone = [b.initial for b in sc.boats]
    for _ in range(200):
        state, forces = fleet_step(fleet, state, FleetInputs.stack(inputs), SEA, DT)
        alone = [step(p, s, u, SEA, DT) for p, s, u in zip(params, alone, inputs, strict=True)]
    for i, a in enumerate(alone):
        b = state.boat(i)
        assert b.t == pytest.approx(a.t, abs=1e-12)
        np.testing.assert_allclose(b.position, a.position, rtol=0, atol=1e-9, err_msg=f"b{i}")
        np.testing.assert_allclose(b.velocity, a.velocity, rtol=0, atol=1e-9, err_msg=f"b{i}")
        np.testing.assert_allclose(b.orientation, a.orientation, rtol=0, atol=1e-12)
        assert b.throttle == pytest.approx(a.throttle, abs=1e-15)
    assert np.all(np.isfinite(forces.total.force))
    # the boats really moved differently: the comparison is not between copies
    assert np.ptp(state.velocity[:, 0]) > 0.5


@settings(max_examples=8, deadline=None)
@given(st.permutations(range(6)))
def test_the_order_of_the_boats_does_not_matter(order):
    sc = fleet_scenario(BOATS[:6])
    params = [b.params for b in sc.boats]
    inputs = commands(6)
    ref = FleetState.stack([b.initial for b in sc.boats])
    perm = FleetState.stack([sc.boats[i].initial for i in order])
    fleet_ref, fleet_perm = Fleet(params), Fleet([params[i] for i in order])
    for _ in range(50):
        ref, _ = fleet_step(fleet_ref, ref, FleetInputs.stack(inputs), SEA, DT)
        perm, _ = fleet_step(fleet_perm, perm, FleetInputs.stack([inputs[i] for i in order]),
                             SEA, DT)
    np.testing.assert_allclose(perm.position, ref.position[list(order)], rtol=0, atol=1e-9)
    np.testing.assert_allclose(perm.velocity, ref.velocity[list(order)], rtol=0, atol=1e-9)


def test_contacts_are_the_depths_of_each_boats_points():
    from boat_dynamics.boat import reference_pose
    from boat_dynamics.rigid_body import rotation_matrix

    sc = fleet_scenario(BOATS[:5])
    fleet = Fleet([b.params for b in sc.boats])
    state = FleetState.stack([b.initial for b in sc.boats])
    seen = 0
    for c in contacts(fleet, state, WaveField()):  # flat: depth = -z
        g, world, depths = c.group, c.world, c.depths
        for k, i in enumerate(g.index):
            boat = sc.boats[i]
            model = boat.params.buoyancy
            body = model.mesh.vertices if hasattr(model, "mesh") else model.points
            ref, q = reference_pose(boat.params, boat.initial)
            expected = ref + body @ rotation_matrix(q).T
            np.testing.assert_allclose(world[g.owner == k], expected, atol=1e-12)
            np.testing.assert_allclose(depths[g.owner == k], -expected[:, 2], atol=1e-12)
            seen += 1
    assert seen == 5


def test_a_fleet_steps_boats_at_one_time():
    sc = fleet_scenario(BOATS[:2])
    a, b = sc.boats[0].initial, sc.boats[1].initial
    from dataclasses import replace

    with pytest.raises(ValueError, match="one time"):
        FleetState.stack([a, replace(b, t=1.0)])


def test_float32_surface_queries_stay_within_a_tenth_of_a_millimetre_of_float64():
    from dataclasses import replace

    sc = fleet_scenario(BOATS[:4])
    p32 = [replace(b.params, wave_precision="float32") for b in sc.boats]
    p64 = [replace(b.params, wave_precision="float64") for b in sc.boats]
    s32 = s64 = FleetState.stack([b.initial for b in sc.boats])
    u = FleetInputs.stack(commands(4))
    f32, f64 = Fleet(p32), Fleet(p64)
    for _ in range(500):  # 5 s on a steep sea
        s32, forces32 = fleet_step(f32, s32, u, SEA, DT)
        s64, forces64 = fleet_step(f64, s64, u, SEA, DT)
    assert np.abs(s32.position - s64.position).max() < 1e-4
    assert np.abs(s32.position - s64.position).max() > 0.0  # the two paths really differ
    weight = np.array([p.mass * p.gravity for p in p64])
    buoyancy_error = np.abs(forces32.buoyancy.force - forces64.buoyancy.force).max(axis=1)
    assert np.all(buoyancy_error < 1e-4 * weight)
