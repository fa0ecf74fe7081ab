"""The pipeline: stepping boats together is stepping each alone (one implementation, batched);
the surface contact is a value a step takes and returns, never a cache."""

import math
from dataclasses import FrozenInstanceError, replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from ready_scenarios import SEED_MODEL, ready

from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.boat import BoatInputs, step
from boat_dynamics.physics.core.contact import contact
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from ocean_sim.physics.waves import WaveComponent, WaveField

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
    {"buoyancy": {"pressure": "froude_krylov", "max_triangles": 200}},
    {"buoyancy": {"pressure": "hydrostatic"}, "hydrodynamics": {"coefficients": "none"}},
]


def fleet_scenario(boats=BOATS):
    # float64 queries: float32 results depend on the batch (its phase-reduction centre) at the
    # 1e-7 m level, which would hide a real difference between the fleet and lone boats
    return ready({"simulation": {"wave_precision": "float64"},
                           "boats": [dict(b, name=f"b{i}", initial_pose={
        "position": [9.0 * i, 3.0 * (i % 3), 0.0], "yaw_deg": 20.0 * i})
        for i, b in enumerate(boats)]})


def commands(n):
    return [BoatInputs(1.0 - 0.15 * i, 0.3 * np.sin(i)) for i in range(n)]


def test_a_mixed_fleet_stepped_together_equals_each_boat_alone():
    sc = fleet_scenario()
    params = [b.params for b in sc.boats]
    inputs = commands(len(params))
    fleet = System.build(params).apart()  # no boat feels another's wake: each as if alone
    # boats 0, 1 and 7-11 share a code path (control modes apply after the step; 11 has fewer
    # triangles); 2-6 and 12 (the seed notes' hydrostatic pressure) do not
    assert sorted(g.index.tolist() for g in fleet.groups) == [[0, 1, 7, 8, 9, 10, 11], [2],
                                                               [3], [4], [5], [6], [12]]
    state = FleetState.stack([b.initial for b in sc.boats])
    alone = [b.initial for b in sc.boats]
    for _ in range(200):
        done = pipeline.step(fleet, state, FleetInputs.stack(inputs), SEA, DT)
        state, forces = done.state, done.forces
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
    fleet_ref, fleet_perm = System.build(params), System.build([params[i] for i in order])
    for _ in range(50):
        ref = pipeline.step(fleet_ref, ref, FleetInputs.stack(inputs), SEA, DT).state
        perm = pipeline.step(fleet_perm, perm, FleetInputs.stack([inputs[i] for i in order]),
                             SEA, DT).state
    np.testing.assert_allclose(perm.position, ref.position[list(order)], rtol=0, atol=1e-9)
    np.testing.assert_allclose(perm.velocity, ref.velocity[list(order)], rtol=0, atol=1e-9)


def test_contact_holds_the_depths_of_each_boats_points():
    from boat_dynamics.physics.body.rigid_body import rotation_matrix
    from boat_dynamics.physics.core.boat import reference_pose

    sc = fleet_scenario(BOATS[:5])
    fleet = System.build([b.params for b in sc.boats])
    state = FleetState.stack([b.initial for b in sc.boats])
    seen = 0
    for c in contact(fleet, state, WaveField()).groups:  # flat: depth = -z
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
    f32, f64 = System.build(p32), System.build(p64)
    for _ in range(500):  # 5 s on a steep sea
        a, b = pipeline.step(f32, s32, u, SEA, DT), pipeline.step(f64, s64, u, SEA, DT)
        s32, forces32, s64, forces64 = a.state, a.forces, b.state, b.forces
    assert np.abs(s32.position - s64.position).max() < 1e-4
    assert np.abs(s32.position - s64.position).max() > 0.0  # the two paths really differ
    weight = np.array([p.mass * p.gravity for p in p64])
    buoyancy_error = np.abs(forces32.buoyancy.force - forces64.buoyancy.force).max(axis=1)
    assert np.all(buoyancy_error < 1e-4 * weight)


def _two_boats():
    sc = fleet_scenario(BOATS[:4])
    system = System.build([b.params for b in sc.boats])
    return system, FleetState.stack([b.initial for b in sc.boats]), FleetInputs.stack(commands(4))


def test_a_step_hands_back_the_contact_its_forces_came_from():
    system, state, u = _two_boats()
    done = pipeline.step(system, state, u, SEA, DT)
    assert done.contact.t == state.t and done.contact.position is state.position
    again, _ = pipeline.forces(system, replace(state, throttle=done.state.throttle), u,
                               contact(system, state, SEA))
    assert np.array_equal(again.total.force, done.forces.total.force)


def test_a_given_contact_gives_the_same_step_bit_for_bit():
    system, state, u = _two_boats()
    after = pipeline.step(system, state, u, SEA, DT).state
    known = contact(system, after, SEA)  # as /diagnostics computes it for the new state
    reusing = pipeline.step(system, after, u, SEA, DT, known)
    fresh = pipeline.step(system, after, u, SEA, DT)
    assert reusing.contact is known
    for name in ("position", "orientation", "velocity", "angular_velocity"):
        assert np.array_equal(getattr(reusing.state, name), getattr(fresh.state, name)), name


def test_a_contact_of_another_state_sea_or_system_is_refused():
    system, state, u = _two_boats()
    after = pipeline.step(system, state, u, SEA, DT).state
    stale = contact(system, state, SEA)
    with pytest.raises(ValueError, match="another system, state or sea"):
        pipeline.step(system, after, u, SEA, DT, stale)
    with pytest.raises(ValueError, match="another system, state or sea"):
        pipeline.step(system, state, u, WaveField(), DT, stale)
    other = System.build(system.params)
    with pytest.raises(ValueError, match="another system, state or sea"):
        pipeline.step(other, state, u, SEA, DT, stale)


def test_stepping_changes_nothing_it_is_given():
    system, state, u = _two_boats()
    copies = {k: getattr(state, k).copy() for k in ("position", "orientation", "velocity")}
    first = pipeline.step(system, state, u, SEA, DT)
    second = pipeline.step(system, state, u, SEA, DT)
    for k, v in copies.items():
        assert np.array_equal(getattr(state, k), v), k
    assert np.array_equal(first.state.position, second.state.position)
    with pytest.raises(FrozenInstanceError):
        system.mass = None


def test_afloat_is_exactly_zero_velocity_in_still_water_and_moves_with_waves():
    system, state, _ = _two_boats()
    still = pipeline.afloat(system, state, WaveField())
    assert np.array_equal(still.velocity, np.zeros_like(state.velocity))
    assert not np.signbit(still.velocity).any()
    moving = pipeline.afloat(system, state, SEA)
    assert np.abs(moving.velocity).max() > 0.05
    assert moving.position is state.position  # only the velocity is set


def test_a_boat_started_under_way_keeps_its_speed_from_the_first_step():
    # initial_pose.velocity: the waves' motion plus the given body-frame velocity; in calm
    # water at full thrust, a boat started at its own top speed holds it, one started at rest
    # has a run-up; the angular velocity is the one asked for, in rad/s
    from boat_dynamics.physics.scenario import parse_scenario

    at_rest = parse_scenario({"boats": [{"name": "a", **SEED_MODEL}]})
    moving = parse_scenario({"boats": [{"name": "a", **SEED_MODEL, "initial_pose": {
        "velocity": [1.5, -0.2, 0.0], "angular_velocity_deg": [0.0, 0.0, 5.0]}}]})
    assert np.array_equal(moving.boats[0].initial.angular_velocity,
                          [0.0, 0.0, math.radians(5.0)])
    _, rest = pipeline.start(at_rest.boats, SEA)
    _, under_way = pipeline.start(moving.boats, SEA)
    assert np.allclose(under_way.velocity - rest.velocity, [[1.5, -0.2, 0.0]], atol=1e-12)
    _, calm = pipeline.start(moving.boats, WaveField())
    assert np.array_equal(calm.velocity, [[1.5, -0.2, 0.0]])
    # started again (a scenario already initialized, as the trials do): not added twice
    again = pipeline.init_scenario(replace(moving, sea=WaveField()))
    assert np.array_equal(pipeline.start(again.boats, WaveField())[1].velocity, calm.velocity)
    top = parse_scenario({"boats": [{"name": "a", **SEED_MODEL,
                                     "initial_pose": {"velocity": [2.0, 0, 0]}},
                                    {"name": "b", **SEED_MODEL}]})
    system, state = pipeline.start(top.boats, WaveField())
    inputs = FleetInputs.stack([BoatInputs(throttle=1.0), BoatInputs(throttle=1.0)])
    for _ in range(100):
        state = pipeline.step(system, state, inputs, WaveField(), DT).state
    u = state.velocity[:, 0]
    assert u[0] > 1.5 and u[1] < 0.8 * u[0], u  # 1 s in: at speed against a run-up


def test_init_derives_each_boat_once_and_sets_it_afloat():
    from boat_dynamics.physics.core.tuning import critical_damping, default_drag, equilibrium_height
    from boat_dynamics.physics.scenario import parse_scenario

    sc = parse_scenario({"boats": [{"name": "a", **SEED_MODEL},
                                   {"name": "b", "damping": {"linear": [0] * 6}, "mass": 2000.0}]})
    raw = [b.params for b in sc.boats]
    assert all(p.derive is not None for p in raw)  # the reader leaves it to init
    assert all(np.array_equal(b.initial.velocity, np.zeros(3)) for b in sc.boats)
    system, state = pipeline.init(System.build(raw),
                                  FleetState.stack([b.initial for b in sc.boats]), SEA)
    a, b = system.params
    assert a.derive is None and b.derive is None
    z_a = equilibrium_height(raw[0])
    assert a.control.height_offset == z_a
    assert np.array_equal(a.damping_linear, critical_damping(raw[0], [0.2, 0.1, 0.2], z_a))
    assert np.array_equal(a.damping_quadratic, default_drag(raw[0], z_a))
    assert np.array_equal(b.damping_linear, np.zeros(6))  # linear given: no ratio added
    assert b.damping_quadratic[2] > 0.0  # quadratic not given: derived
    # b takes the default: its coefficient file (auto), A_inf and the fitted memory; the
    # radiation damps heave and pitch
    assert b.added_mass_matrix is not None and b.radiation_memory is not None
    assert a.added_mass_matrix is None and a.radiation_memory is None
    assert np.array_equal(state.velocity,
                          pipeline.afloat(system, FleetState.stack([x.initial for x in sc.boats]),
                                          SEA).velocity)
    # nothing left to derive: init is then only the afloat start
    again, _ = pipeline.init(system, state, SEA)
    assert again is system


def test_init_refuses_a_hull_that_sinks_naming_the_boat():
    from boat_dynamics.physics.scenario import parse_scenario

    sc = parse_scenario({"boats": [{"name": "a"}, {"name": "lead", "density": 2000.0}]})
    with pytest.raises(pipeline.InitError, match="the hull sinks") as err:
        pipeline.start(sc.boats, SEA)
    assert err.value.boat == 1 and err.value.key == "mass"
    assert err.value.value == pytest.approx(2000.0 * 8.0)


def test_init_panels_froude_krylov_hulls_for_the_shortest_wave_acting_on_them():
    from boat_dynamics.physics.body.hull import longest_edge
    from boat_dynamics.physics.scenario import parse_scenario

    sc = parse_scenario({"boats": [
        {"name": "fk", "buoyancy": {"pressure": "froude_krylov"}},
        {"name": "coarse", "buoyancy": {"pressure": "froude_krylov", "panels_per_wavelength": 2}},
        {"name": "capped", "buoyancy": {"pressure": "froude_krylov", "max_triangles": 100}},
        {"name": "filtered", "buoyancy": {"pressure": "froude_krylov"}, "min_wavelength": 5.0},
        {"name": "hydrostatic", "buoyancy": {"pressure": "hydrostatic"}}]})
    system, _ = pipeline.init(System.build([b.params for b in sc.boats]),
                              FleetState.stack([b.initial for b in sc.boats]), SEA)
    meshes = [p.buoyancy.mesh for p in system.params]
    shortest = min(c.wavelength for c in SEA.components)  # 3 m
    assert longest_edge(meshes[0]) <= shortest / 10 < 2 * longest_edge(meshes[0])
    assert longest_edge(meshes[1]) <= shortest / 2 < 2 * longest_edge(meshes[1])
    assert meshes[2].faces.shape[0] == 48  # 12 -> 48; 192 would pass 100
    assert longest_edge(meshes[3]) <= 7.0 / 10  # the 3 m component does not act on it
    assert meshes[4] is sc.boats[4].params.buoyancy.mesh  # hydrostatic: untouched
    still, _ = pipeline.init(System.build([sc.boats[0].params]),
                             FleetState.stack([sc.boats[0].initial]), WaveField())
    assert still.params[0].buoyancy.mesh is sc.boats[0].params.buoyancy.mesh


def test_a_diverged_boat_is_found_and_held_where_it_was_at_rest():
    # the node's watchdog: NaN, or faster than any boat (1000 m/s, 1000 rad/s); the 1 g boat
    # of tests/ros/test_hostile_inputs.py passes 1000 m/s at its first step
    from boat_dynamics.physics.core.system import FleetInputs
    from boat_dynamics.physics.scenario import parse_scenario

    sc = parse_scenario({"boats": [{"name": "feather", "mass": 0.001},
                                   {"name": "alpha", "initial_pose": {"position": [20, 0, 0]}}]})
    system, before = pipeline.start(sc.boats, sc.sea)
    inputs = FleetInputs.stack([BoatInputs(throttle=1.0), BoatInputs(throttle=1.0)])
    after = pipeline.step(system, before, inputs, sc.sea, 0.01).state
    assert after.diverged().tolist() == [True, False]
    held = after.held(before, after.diverged())
    np.testing.assert_array_equal(held.position[0], before.position[0])
    np.testing.assert_array_equal(held.orientation[0], before.orientation[0])
    assert not held.velocity[0].any() and not held.angular_velocity[0].any()
    assert not held.throttle[0].any()
    for name in ("position", "velocity", "throttle"):  # the other boat untouched
        np.testing.assert_array_equal(getattr(held, name)[1], getattr(after, name)[1])
    nan = replace(after, position=np.where([[False], [True]], np.nan, after.position))
    assert nan.diverged().tolist() == [True, True]
    spin = replace(before, angular_velocity=np.array([[0.0, 0.0, 1001.0], [0.0, 0.0, 999.0]]))
    assert spin.diverged().tolist() == [True, False]
