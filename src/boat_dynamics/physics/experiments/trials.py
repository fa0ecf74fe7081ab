"""Sea trials: a boat driven through a sea on fixed orders, as a naval architect tries one.

:func:`sea_trials` steps copies of one boat side by side (one fleet: a boat's physics does not
depend on the others), each on its own order (throttle, rudder or differential thrust, and the
heading it starts on relative to the waves), and records what a trials report reads: the
track, the attitude, the speed through the water, the heave of the hull reference point
against the sea's own elevation there, and whether the hull was ever fully submerged or out of
the water. The driving suite (tests/boat_dynamics/physics/experiments/test_driving.py) holds every
shipped boat to the bounds a naval architect accepts.

Headings are relative to the sea's main direction of travel (:func:`main_direction`): a boat
on heading pi meets the waves head on, pi / 2 has them on its starboard beam (they travel
toward its port side), 0 runs before them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from boat_dynamics.physics.body.rigid_body import quat_from_euler, quat_to_euler, rotation_matrix
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.diagnostics import fleet_reports
from boat_dynamics.physics.core.model import BoatInputs, BoatParams
from boat_dynamics.physics.core.system import FleetInputs
from boat_dynamics.physics.scenario.specs import BoatSpec
from ocean_sim.physics.waves import WaveField, sample_surface

__all__ = ["Order", "Track", "main_direction", "orders_for", "sea_trials"]


@dataclass(frozen=True)
class Order:
    """What one copy of the boat is told for the whole trial.

    Attributes:
        name: a label (``ahead``, ``turn``).
        heading: rad, the initial heading relative to the sea's main direction (pi = head
            seas).
        throttle: -1..1 for every thruster, or one per thruster (differential thrust).
        rudder: rad, + turns the bow to port (rudder and steerable thrusters).
    """

    name: str
    heading: float
    throttle: float | tuple[float, ...]
    rudder: float


@dataclass(frozen=True)
class Track:
    """What a trial recorded, sampled every ``t[1] - t[0]`` s; R orders, S samples.

    Attributes:
        orders: the R orders.
        t: (S,) s.
        position: (R, S, 3) m, world, the hull reference point.
        attitude: (R, S, 3) rad, roll, pitch and yaw (yaw unwrapped).
        velocity: (R, S, 3) m/s, body frame, over ground.
        angular_velocity: (R, S, 3) rad/s, body frame.
        elevation: (R, S) m, the sea's elevation under the hull reference point.
        equilibrium: m, the reference point's height afloat in still water.
        submerged: (R, S) bool, the hull fully under water (/diagnostics WARN).
        airborne: (R, S) bool, the hull out of the water.
    """

    orders: tuple[Order, ...]
    t: np.ndarray
    position: np.ndarray
    attitude: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray
    elevation: np.ndarray
    equilibrium: float
    submerged: np.ndarray
    airborne: np.ndarray

    def index(self, name: str, heading: float) -> int:
        """The row of the order ``name`` that started on ``heading`` (rad)."""
        for i, o in enumerate(self.orders):
            if o.name == name and math.isclose(o.heading, heading, abs_tol=1e-9):
                return i
        raise KeyError(f"no order {name!r} on heading {heading!r}")


def main_direction(sea: WaveField) -> float:
    """rad, the energy-weighted mean direction the waves travel toward (0 for a flat sea)."""
    if sea.is_flat:
        return 0.0
    a = np.array([c.amplitude for c in sea.components]) ** 2
    d = np.array([c.direction for c in sea.components])
    return float(math.atan2(np.sum(a * np.sin(d)), np.sum(a * np.cos(d))))


def orders_for(params: BoatParams, name: str, heading: float, throttle: float,
               turn: float) -> Order:
    """The order ``throttle`` ahead, turning by ``turn`` (rad of rudder) to port.

    A boat with a rudder or a steerable thruster turns by its angle; one with neither and two
    or more fixed thrusters (a twin-screw catamaran) by differential thrust: the thrusters on
    its port side (y > 0) at throttle (1 - turn / max_angle), the others at throttle.
    """
    steerable = any(t.steerable for t in params.thrusters)
    if params.rudder.model != "none" or steerable or len(params.thrusters) < 2:
        return Order(name, heading, throttle, turn)
    share = float(turn) / float(params.rudder.max_angle)
    throttles = tuple(throttle * (1.0 - share) if t.position[1] > 0.0 else throttle
                      for t in params.thrusters)
    return Order(name, heading, throttles, 0.0)


def sea_trials(boat: BoatSpec | Sequence[BoatSpec], sea: WaveField, orders: Sequence[Order],
               duration: float, dt: float, sample_every: int = 10) -> Track:
    """Drive copies of ``boat``, one per order, through ``sea`` for ``duration`` s.

    The copies start at the boat's initial position and attitude, afloat
    (:func:`.pipeline.start`: its angular velocity kept), turned to their headings, and are
    stepped together at ``dt`` with their orders held throughout
    (through the pipeline, as the dynamics node steps a fleet).

    Args:
        boat: the boat as a scenario gives it, or one such boat per order (the same hull
            started otherwise, e.g. heeled), stepped together as one fleet.
        sea: the sea.
        orders: what each copy does.
        duration: s of simulated time.
        dt: s, the step.
        sample_every: steps between samples.

    Returns:
        The track.
    """
    direction = main_direction(sea)
    boats = [boat] * len(orders) if isinstance(boat, BoatSpec) else list(boat)
    if len(boats) != len(orders):
        raise ValueError(f"{len(boats)} boats for {len(orders)} orders: one, or one per order")
    copies = [replace(b, initial=_placed(b, *quat_to_euler(b.initial.orientation)[:2],
                                         direction + o.heading))
              for b, o in zip(boats, orders, strict=True)]
    system, state = pipeline.start(copies, sea, 0.0)
    system = system.apart()  # separate trials: no copy feels another's wake
    inputs = FleetInputs.stack([BoatInputs(throttle=o.throttle, rudder=o.rudder)
                                for o in orders])
    samples: list[tuple] = []
    for k in range(round(duration / dt) + 1):
        done = pipeline.step(system, state, inputs, sea, dt)
        if k % sample_every == 0:
            samples.append(_sample(system, state, done.contact))
        state = done.state
    return _track(tuple(orders), samples, system.params[0].control.height_offset, sea)


def _placed(boat: BoatSpec, roll: float, pitch: float, yaw: float):
    """The boat's initial state turned to ``yaw`` (rad) about its hull reference point."""
    params, start = boat.params, boat.initial
    reference = start.position - rotation_matrix(start.orientation) @ params.center_of_mass
    q = quat_from_euler(roll, pitch, yaw)
    return replace(start, orientation=q,
                   position=reference + rotation_matrix(q) @ params.center_of_mass)


def _sample(system, state, touching) -> tuple:
    """One sample of every copy: t, reference pose, velocities, the diagnostics' verdict."""
    rot = rotation_matrix(state.orientation)
    ref = state.position - np.einsum("bij,bj->bi", rot, system.center_of_mass)
    reports = fleet_reports(system, state, touching)
    levels = [(r.level == 1 and r.message == "fully submerged",
               r.level == 1 and r.message == "out of the water") for r in reports]
    return (state.t, ref, rot, state.velocity.copy(), state.angular_velocity.copy(), levels)


def _track(orders: tuple[Order, ...], samples: list[tuple], equilibrium: float,
           sea: WaveField) -> Track:
    """The samples as arrays, with the sea's elevation under each reference point."""
    t = np.array([s[0] for s in samples])
    position = np.stack([s[1] for s in samples], axis=1)
    rot = np.stack([s[2] for s in samples], axis=1)
    roll = np.arctan2(rot[..., 2, 1], rot[..., 2, 2])
    pitch = np.arcsin(np.clip(-rot[..., 2, 0], -1.0, 1.0))
    yaw = np.unwrap(np.arctan2(rot[..., 1, 0], rot[..., 0, 0]), axis=1)
    elevation = np.stack([sample_surface(sea, position[:, j, :2], tj).heights
                          for j, tj in enumerate(t)], axis=1)
    levels = np.array([s[5] for s in samples]).transpose(1, 0, 2)
    return Track(orders, t, position, np.stack([roll, pitch, yaw], axis=-1),
                 np.stack([s[3] for s in samples], axis=1),
                 np.stack([s[4] for s in samples], axis=1), elevation, equilibrium,
                 levels[..., 0], levels[..., 1])
