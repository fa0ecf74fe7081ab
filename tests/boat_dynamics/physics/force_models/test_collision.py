"""Contact with obstacles: a free mass's bounce against closed forms, and a boat into a pier."""

import math

import numpy as np
import pytest
import yaml

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.contact import reference_points
from boat_dynamics.physics.core.model import BoatInputs
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from boat_dynamics.physics.force_models.collision import collision_wrench
from boat_dynamics.physics.scenario import default_scenario_path, parse_scenario
from boat_dynamics.physics.world.obstacles import (
    ContactParams,
    Cylinder,
    Prism,
    World,
    restitution_of,
)

WALL = Prism.make("wall", [[0.0, -50.0], [10.0, -50.0], [10.0, 50.0], [0.0, 50.0]], 5.0)


def _push(world, points, velocity, angular=(0.0, 0.0, 0.0), mass=1000.0, com=(0.0, 0.0, 0.0)):
    """One boat at the origin, level, body = world axes: its points' push."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    force, torque = collision_wrench(
        world, points, points, np.zeros(points.shape[0], dtype=np.intp), 1,
        np.eye(3)[None], np.array([com], dtype=float), np.array([velocity], dtype=float),
        np.array([angular], dtype=float), np.array([mass]))
    return force[0], torque[0]


def _bounce(restitution: float, speed: float, frequency: float = 10.0, dt: float = 0.01,
            start: float = -0.5) -> tuple[float, float]:
    """A free point mass (no water) into WALL: (rebound speed / speed, deepest penetration m)."""
    world = World((WALL,), ContactParams(frequency, restitution, 0.0))
    x, v, deepest, m = start, speed, 0.0, 1000.0
    for _ in range(int(3.0 / dt)):
        force, _ = _push(world, [[x, 0.0, 0.0]], [v, 0.0, 0.0], mass=m)
        # the force is of the point at the centre of mass: the mass's own
        v += force[0] / m * dt
        x += v * dt
        deepest = max(deepest, x)
    return -v / speed, deepest


@pytest.mark.parametrize("restitution", [0.2, 0.5, 0.9, 1.0])
def test_a_free_mass_bounces_back_with_its_restitution(restitution):
    # Schwager and Poeschel's restitution of a spring and damper that only pushes, inverted
    # for zeta: a soft contact (omega dt = 0.063) returns it within 0.01. The stiffest one
    # allowed (omega dt = 0.63, the default) at 10 m/s goes 0.1 m a step, as deep as the
    # contact: where in a step the mass arrives matters. Over ten arrivals a step apart the
    # mean is within 0.06 and each within 0.16 (measured: 0.053 .. 0.314, mean 0.177, for 0.2).
    soft, _ = _bounce(restitution, 10.0, frequency=1.0)
    assert soft == pytest.approx(restitution, abs=0.01)
    stiff = np.array([_bounce(restitution, 10.0, start=-0.5 + s)[0]
                      for s in np.linspace(0.0, 0.1, 10, endpoint=False)])
    assert stiff.mean() == pytest.approx(restitution, abs=0.06)
    np.testing.assert_allclose(stiff, restitution, atol=0.16)


def test_the_damping_ratio_returns_the_restitution_asked_for():
    for e in (0.2, 0.3, 0.5, 0.9, 1.0):
        assert restitution_of(ContactParams(1.0, e).damping_ratio) == pytest.approx(e, abs=1e-12)
    assert restitution_of(0.0) == 1.0
    assert restitution_of(1.0) == pytest.approx(math.exp(-2.0))
    with pytest.raises(ValueError, match="restitution"):
        ContactParams(1.0, 0.1)


def test_an_undamped_contact_stops_the_mass_within_speed_over_omega():
    # x_max = U / omega for a spring k = m omega^2: at 10 m/s and f = 10 Hz, 0.159 m.
    _, deepest = _bounce(1.0, 10.0)
    assert deepest == pytest.approx(10.0 / (2 * math.pi * 10.0), rel=0.1)


def test_the_push_is_the_boats_not_each_points():
    # N points at the same depth push as one: the force does not grow with the mesh.
    world = World((WALL,), ContactParams(10.0, 1.0, 0.0))
    one, _ = _push(world, [[0.1, 0.0, 0.0]], [0.0, 0.0, 0.0])
    many, _ = _push(world, [[0.1, y, 0.0] for y in np.linspace(-1, 1, 9)], [0.0, 0.0, 0.0])
    k = 1000.0 * (2 * math.pi * 10.0) ** 2
    np.testing.assert_allclose(one, [-k * 0.1, 0.0, 0.0])
    np.testing.assert_allclose(many, one, rtol=1e-12)


def test_friction_opposes_the_slide_and_the_torque_is_r_cross_f():
    world = World((WALL,), ContactParams(10.0, 1.0, 0.5))
    force, torque = _push(world, [[0.1, 2.0, -1.0]], [0.0, 3.0, 0.0])
    k = 1000.0 * (2 * math.pi * 10.0) ** 2
    np.testing.assert_allclose(force, [-k * 0.1, -0.5 * k * 0.1, 0.0])
    np.testing.assert_allclose(torque, np.cross([0.1, 2.0, -1.0], force))


def test_nothing_near_pushes_nothing():
    world = World((WALL, Cylinder("pile", np.array([-20.0, 0.0]), 1.0, 1.0)),
                  ContactParams(10.0))
    force, torque = _push(world, [[-5.0, 0.0, 0.0], [-19.5, 0.0, 2.0]], [9.0, 0.0, 0.0])
    assert not force.any() and not torque.any()


def _boat_into(world: World, speed: float, seconds: float = 3.0):
    """The default boat in calm water at ``speed`` m/s toward +x: its bow's x and its surge."""
    data = yaml.safe_load(default_scenario_path().read_text())
    data["ocean"] = {}
    data["boats"][0]["initial_pose"] = {"position": [0.0, 0.0, 0.0], "velocity": [speed, 0, 0]}
    scenario = pipeline.init_scenario(parse_scenario(data))
    system = System.build([b.params for b in scenario.boats])
    state = FleetState.stack([b.initial for b in scenario.boats])
    inputs = FleetInputs.stack([BoatInputs(0.0, 0.0)])
    body = system.groups[0].body
    bow, surge = [], []
    for _ in range(int(seconds * 100)):
        state = pipeline.step(system, state, inputs, scenario.sea, 0.01, world=world).state
        rot, ref = reference_points(system, state)
        bow.append((ref[0] + body @ rot[0].T)[:, 0].max())
        surge.append(state.velocity[0, 0])
    return np.array(bow), np.array(surge), state


PIER = Prism.make("pier", [[6.0, -20.0], [6.5, -20.0], [6.5, 20.0], [6.0, 20.0]], 2.0)


def test_a_boat_at_10_m_s_stops_at_a_half_metre_pier_without_going_through():
    # The default boat (4 m, 4,100 kg; bow at x = 2), launched at 10 m/s toward a pier at
    # x = 6 .. 6.5 (it arrives at 6.4 m/s): its hull goes at most 0.1 m in (one step's travel)
    # and, within four steps, comes back out, slower than it came (measured: 0.0097 m in,
    # 1.10 m/s back). The water it set moving (the radiation memory) may carry it back to
    # rest against the pier, the contact holding it.
    bow, surge, state = _boat_into(World((PIER,), ContactParams(10.0, 0.2, 0.3)), 10.0)
    hit = int(np.argmax(bow > 6.0))  # the first step in contact
    arrival = surge[hit - 1]
    assert 6.0 < bow.max() < 6.1
    assert 5.0 < arrival < 8.0
    assert np.all(surge[hit + 4:hit + 14] < 0.0) and -surge.min() < 0.5 * arrival
    assert bow[hit + 10:hit + 20].max() < 6.0 and bow[-1] < 6.01
    assert np.all(np.isfinite(state.position)) and abs(state.position[0, 1]) < 0.05


def test_an_elastic_contact_returns_about_the_speed_it_took():
    # Restitution 1: the boat leaves at about its arrival speed. Not exactly: the push is
    # shared by the points in contact, which arrive and leave at different steps, so it is
    # not a potential's (measured: 6.37 m/s in, 6.31 m/s out; within 10 %).
    bow, surge, _ = _boat_into(World((PIER,), ContactParams(10.0, 1.0, 0.0)), 10.0)
    hit = int(np.argmax(bow > 6.0))
    assert bow.max() < 6.2
    assert -surge.min() == pytest.approx(surge[hit - 1], rel=0.1)


def test_no_obstacles_change_nothing():
    far = World((Cylinder("far", np.array([500.0, 0.0]), 1.0, 1.0),), ContactParams(10.0))
    a, _, sa = _boat_into(World(), 2.0, 0.5)
    b, _, sb = _boat_into(far, 2.0, 0.5)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(sa.position, sb.position)


def _two_boats(restitution: float, speed: float = 3.0, offset: float = 0.0, steps: int = 200):
    """Two default boats head-on in calm water, 2 m between bows, each at ``speed``.

    ``offset``: m, the second boat's sideways offset (a glancing contact). Returns per step
    the contact's world force on each boat, the boats' centres of mass, the contact's
    world torque on each, and their surge speeds; and the deepest overlap seen.
    """
    data = yaml.safe_load(default_scenario_path().read_text())
    data["ocean"] = {}
    data["boats"] = [
        {**data["boats"][0], "name": "a", "initial_pose": {"position": [0, 0, 0],
                                                           "velocity": [speed, 0, 0]}},
        {**data["boats"][0], "name": "b", "initial_pose": {"position": [6, offset, 0],
                                                           "yaw_deg": 180,
                                                           "velocity": [speed, 0, 0]}}]
    scenario = pipeline.init_scenario(parse_scenario(data))
    system = System.build([b.params for b in scenario.boats])
    state = FleetState.stack([b.initial for b in scenario.boats])
    inputs = FleetInputs.stack([BoatInputs(0.0, 0.0)] * 2)
    world = World((), ContactParams(10.0, restitution, 0.0))
    out = {"force": [], "com": [], "torque": [], "surge": []}
    for _ in range(steps):
        done = pipeline.step(system, state, inputs, scenario.sea, 0.01, world=world)
        rot = rotation_matrix(state.orientation)
        out["force"].append(np.einsum("bij,bj->bi", rot, done.forces.collision.force))
        out["torque"].append(np.einsum("bij,bj->bi", rot, done.forces.collision.torque))
        out["com"].append(state.position.copy())
        state = done.state
        out["surge"].append(state.velocity[:, 0].copy())
    return {k: np.array(v) for k, v in out.items()}, system


def test_two_boats_push_each_other_equally_and_oppositely():
    # Newton's third law at the same points: the pair's momentum and angular momentum are
    # the contact's to keep, step by step, head-on and glancing.
    for offset in (0.0, 1.2):
        run, _ = _two_boats(1.0, offset=offset)
        force = run["force"]
        assert np.abs(force).max() > 1e4, "no contact"
        scale = np.abs(force).max()
        np.testing.assert_allclose(force.sum(axis=1), 0.0, atol=1e-9 * scale)
        moment = np.cross(run["com"], force) + run["torque"]  # about the world origin
        np.testing.assert_allclose(moment.sum(axis=1), 0.0, atol=1e-9 * scale * 10.0)


@pytest.mark.parametrize("restitution", [1.0, 0.5, 0.2])
def test_two_boats_part_with_the_restitution_asked_for(restitution):
    # Head-on at 3 m/s each (they meet at 2.4 m/s each): the pair is one reduced mass on one
    # spring, whichever hull's points are in the other, so they part at e times the speed
    # they met at, within 0.1 (measured: 0.998, 0.47, 0.13), each going back.
    run, _ = _two_boats(restitution)
    surge = run["surge"]
    hit = int(np.argmax(np.abs(run["force"][:, 0, 0]) > 0.0))
    closing = surge[hit - 1].sum()
    parting = -surge[hit:].sum(axis=1).min()
    assert parting / closing == pytest.approx(restitution, abs=0.1)
    assert np.all(surge[hit + 10] < 0.0)


def test_a_boat_coasting_onto_a_shelving_shore_runs_aground_short_of_its_edge():
    # A shore from x = 8 whose floor rises 1 in 10 (0.6 m deep 6 m out): the default boat
    # (draft 0.5 m, bow at x = 2) launched at 3 m/s, no thrust, touches bottom about 3 m
    # out, rides up, and stops there aground: bow up, lifted, the floor carrying part of its
    # weight, its bow short of the edge (where the water is 0 m deep). The floor's softer
    # contact (FLOOR_SOFTNESS) keeps the push under the bow from throwing it up: with the
    # walls' stiffness it was thrown 3.9 m into the air.
    shore = Prism.make("shore", [[8.0, -50.0], [60.0, -50.0], [60.0, 50.0], [8.0, 50.0]],
                       2.0, 0.1)
    world = World((shore,), ContactParams(10.0, 0.2, 0.3))
    bow, surge, state = _boat_into(world, 3.0, 8.0)
    assert bow.max() < 8.0, f"the bow reached x = {bow.max():.2f}, past the edge"
    assert 5.0 < bow[-1]
    assert abs(surge[-100:]).max() < 0.05  # at rest for the last second
    _, _, afloat = _boat_into(World(), 0.0, 0.01)
    rise = state.position[0, 2] - afloat.position[0, 2]
    assert 0.05 < rise < 0.5, f"the centre of mass {rise:.3f} m above where it floats"
    x, y, zq, w = state.orientation[0]
    pitch = math.asin(2 * (w * y - zq * x))
    assert math.radians(-15.0) < pitch < math.radians(-0.5)  # bow up
