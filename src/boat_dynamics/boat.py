"""A boat: parameters, state, inputs, the force sum and the step.

``step(params, state, inputs, sea, dt) -> state`` is a pure function over frozen dataclasses
(Gymnasium functional-env / brax pipeline style). The dataclasses live in
:mod:`boat_dynamics.model`; the force models are one module each; the sum and the integration
are :mod:`boat_dynamics.fleet`, which steps one boat or many with the same code. Never imports
rclpy.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from boat_dynamics.fleet import (
    Fleet,
    FleetInputs,
    FleetState,
    fleet_forces,
    fleet_step,
    water_velocities,
)
from boat_dynamics.model import (
    BoatInputs,
    BoatParams,
    BoatState,
    Forces,
    initial_state,
    reference_pose,
)
from boat_dynamics.rigid_body import rotation_matrix
from ocean_sim.waves import WaveField

__all__ = [
    "BoatInputs",
    "BoatParams",
    "BoatState",
    "Forces",
    "evaluate_forces",
    "initial_state",
    "moving_with_the_water",
    "reference_pose",
    "step",
    "step_many",
]

_FLEETS: dict[tuple[int, ...], Fleet] = {}
_FLEET_CACHE_SIZE = 32


def _fleet(params: Sequence[BoatParams]) -> Fleet:
    """The Fleet of these parameter objects, built once (parameters are frozen)."""
    key = tuple(id(p) for p in params)
    fleet = _FLEETS.get(key)
    if fleet is None or any(a is not b for a, b in zip(fleet.params, params, strict=True)):
        if len(_FLEETS) >= _FLEET_CACHE_SIZE:
            _FLEETS.pop(next(iter(_FLEETS)))
        fleet = _FLEETS[key] = Fleet(params)
    return fleet


def moving_with_the_water(params: BoatParams, state: BoatState, sea: WaveField) -> BoatState:
    """``state`` with the velocity of the water at its hull reference point (body frame).

    A boat that has been afloat in the waves moves with the water around it. Released at rest
    over ground instead, it starts with the opposite of the water's orbital velocity (up to
    Q a omega per component) relative to the water, and with quadratic surge drag alone that
    offset decays only as 1/t. In one trochoidal wave (a 0.4 m, wavelength 40 m, Q 1) the
    default 4 m box released at rest at a crest still drifts 0.27 m/s against the waves
    10-40 s later; released with the water, 0.005 m/s (Gerstner particles move on closed
    orbits: no mean drift). Tested in tests/boat_dynamics/test_boat.py.

    With Q < 1 part of the offset stays: the hydrostatic pressure on the hull drives it on the
    orbit of linear theory (horizontal amplitude a), while the Gerstner water moves on Q a.

    Args:
        params: the boat.
        state: its state; the angular velocity is kept.
        sea: the wave field, sampled at ``state.t`` as the boat's damping samples it (its
            wave filter, precision and Stokes drift option).

    Returns:
        The state with ``velocity`` = R^T v_water; ``state`` itself in still water.
    """
    water = water_velocities(_fleet([params]), FleetState.stack([state]), sea)[0]
    if not np.any(water):
        return state
    rot = rotation_matrix(state.orientation)
    return replace(state, velocity=rot.T @ water)


def evaluate_forces(
    params: BoatParams, state: BoatState, inputs: BoatInputs, sea: WaveField
) -> Forces:
    """Evaluate every force model at ``state`` and sum them.

    Args:
        params: the boat.
        state: its state.
        inputs: validated actuator commands.
        sea: the wave field.

    Returns:
        Each source's wrench and the total, body frame, about the centre of mass.
    """
    forces, _ = fleet_forces(_fleet([params]), FleetState.stack([state]),
                             FleetInputs.stack([inputs]), sea)
    return forces.boat(0)


def step(
    params: BoatParams, state: BoatState, inputs: BoatInputs, sea: WaveField, dt: float
) -> BoatState:
    """Advance one boat by ``dt`` seconds (semi-implicit Euler).

    Args:
        params: the boat.
        state: its state at time t.
        inputs: validated actuator commands, held over the step.
        sea: the wave field.
        dt: s, > 0.

    Returns:
        The state at t + dt.
    """
    after, _ = fleet_step(_fleet([params]), FleetState.stack([state]),
                          FleetInputs.stack([inputs]), sea, dt)
    return after.boat(0)


def step_many(params: Sequence[BoatParams], states: Sequence[BoatState],
              inputs: Sequence[BoatInputs], sea: WaveField, dt: float
              ) -> list[tuple[BoatState, Forces]]:
    """Advance several boats by ``dt`` s together (see :mod:`boat_dynamics.fleet`).

    Boats at different times are stepped in one fleet per time.

    Returns:
        For each boat, its state at t + dt and the forces that acted during the step.
    """
    by_time: dict[float, list[int]] = {}
    for i, s in enumerate(states):
        by_time.setdefault(s.t, []).append(i)
    out: list = [None] * len(states)
    for members in by_time.values():
        after, forces = fleet_step(_fleet([params[i] for i in members]),
                                   FleetState.stack([states[i] for i in members]),
                                   FleetInputs.stack([inputs[i] for i in members]), sea, dt)
        for k, i in enumerate(members):
            out[i] = (after.boat(k), forces.boat(k))
    return out
