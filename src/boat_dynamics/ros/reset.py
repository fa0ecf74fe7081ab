"""The reset service's requests (``/boatsim/reset``, boat_msgs/srv/Reset): checked, then applied.

A request is checked whole before anything changes (:func:`check_request`): a refusal names
the field, the value and what is allowed, and the simulation goes on as it was. A checked
request (:class:`ResetPlan`) gives the boats' new state (:func:`placed_state`): the scenario's
initial state at t = 0, with the boats it names at the poses and twists it gives. Poses and
twists are odometry's (the hull reference point's pose in the world, its velocity in the
body frame); the state holds the centre of mass's.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.body.wrench import cross
from boat_dynamics.physics.core.system import DIVERGED_RATE, DIVERGED_SPEED, FleetState, System

__all__ = ["SCENARIO_SEED", "ResetError", "ResetPlan", "check_request", "placed_state"]

#: The request's ``seed`` for the scenario's own ``simulation.seed``.
SCENARIO_SEED = -1
#: How far a given orientation's norm may be from 1 (it is then normalized).
QUATERNION_TOLERANCE = 1e-6


class ResetError(ValueError):
    """A reset request refused: its message names the field, the value and what is allowed."""


@dataclass(frozen=True)
class ResetPlan:
    """A checked reset request.

    Attributes:
        seed: the sensors' noise seed, or None: the scenario's ``simulation.seed``.
        placed: boat index -> (13,) its reference point's position (m, world), unit
            orientation (x, y, z, w), velocity (m/s, body) and angular velocity (rad/s, body).
    """

    seed: int | None
    placed: dict[int, np.ndarray]


def check_request(seed: int, names: Sequence[str], poses: Sequence[Sequence[float]],
                  twists: Sequence[Sequence[float]], boats: Sequence[str]) -> ResetPlan:
    """The plan of a request, or :class:`ResetError`.

    Args:
        seed: the request's seed: >= 0, or :data:`SCENARIO_SEED`.
        names: the boats to place.
        poses: (7,) each: x, y, z (m), qx, qy, qz, qw, one per name.
        twists: (6,) each: vx, vy, vz (m/s), wx, wy, wz (rad/s), one per name; or none.
        boats: the run's boats, in fleet order.

    Raises:
        ResetError: naming the first field refused, its value and what is allowed.
    """
    if seed < SCENARIO_SEED:
        raise ResetError(f"seed: {seed} is not allowed: >= 0, or {SCENARIO_SEED} for the "
                         "scenario's simulation.seed")
    if len(poses) != len(names):
        raise ResetError(f"poses: {len(poses)} given for {len(names)} names: one per name")
    if twists and len(twists) != len(names):
        raise ResetError(f"twists: {len(twists)} given for {len(names)} names: one per name, "
                         "or none (at rest)")
    placed: dict[int, np.ndarray] = {}
    for k, name in enumerate(names):
        if name not in boats:
            raise ResetError(f"names[{k}]: {name!r} is not allowed: a boat of this run, one "
                             f"of {_listed(boats)}")
        if boats.index(name) in placed:
            raise ResetError(f"names[{k}]: {name!r} is not allowed: named twice")
        pose = np.asarray(poses[k], dtype=float)
        twist = np.asarray(twists[k] if twists else np.zeros(6), dtype=float)
        _check_finite(f"poses[{k}]", pose, ("position.x", "position.y", "position.z",
                                            "orientation.x", "orientation.y", "orientation.z",
                                            "orientation.w"))
        _check_finite(f"twists[{k}]", twist, ("linear.x", "linear.y", "linear.z",
                                              "angular.x", "angular.y", "angular.z"))
        for part, limit, unit in ((twist[:3], DIVERGED_SPEED, "m/s"),
                                  (twist[3:], DIVERGED_RATE, "rad/s")):
            if np.linalg.norm(part) >= limit:
                field = "linear" if unit == "m/s" else "angular"
                raise ResetError(f"twists[{k}].{field}: {part.tolist()} is not allowed: "
                                 f"below {limit:g} {unit} (faster is a diverged state)")
        placed[boats.index(name)] = np.concatenate([pose[:3], _unit(pose[3:], k), twist])
    return ResetPlan(None if seed == SCENARIO_SEED else int(seed), placed)


def _listed(boats: Sequence[str]) -> str:
    shown = [repr(b) for b in boats[:10]]
    return ", ".join(shown) + (f" ... ({len(boats)} boats)" if len(boats) > 10 else "")


def _check_finite(key: str, values: np.ndarray, fields: tuple[str, ...]) -> None:
    for value, name in zip(values.tolist(), fields, strict=True):
        if not math.isfinite(value):
            raise ResetError(f"{key}.{name}: {value} is not allowed: a finite number")


def _unit(q: np.ndarray, k: int) -> np.ndarray:
    """The orientation normalized, or ResetError when it is not a unit quaternion."""
    norm = float(np.linalg.norm(q))
    if abs(norm - 1.0) > QUATERNION_TOLERANCE:
        raise ResetError(f"poses[{k}].orientation: {q.tolist()} is not allowed: a unit "
                         f"quaternion (x, y, z, w; its norm {norm:.9g} is not within "
                         f"{QUATERNION_TOLERANCE:g} of 1)")
    return q / norm


def placed_state(system: System, initial: FleetState, plan: ResetPlan) -> FleetState:
    """The boats' state at t = 0 of a new episode: ``initial`` with the placed boats moved.

    A placed boat keeps the rest of its initial state (throttle, control weight, radiation
    memory); its centre of mass is put where its reference point's pose puts it, and its
    velocity is the reference point's plus w x (r_com - r_ref).

    Args:
        system: the boats (their centres of mass, m, body frame from the reference point).
        initial: their state at the start of the run.
        plan: the checked request.
    """
    position, orientation = initial.position.copy(), initial.orientation.copy()
    velocity, rate = initial.velocity.copy(), initial.angular_velocity.copy()
    for i, v in plan.placed.items():
        c = system.center_of_mass[i]
        position[i] = v[:3] + rotation_matrix(v[3:7]) @ c
        orientation[i], rate[i] = v[3:7], v[10:13]
        velocity[i] = v[7:10] + cross(v[10:13], c)
    return replace(initial, t=0.0, position=position, orientation=orientation,
                   velocity=velocity, angular_velocity=rate)
