"""A boat: parameters, state, inputs, the force sum and the step.

``step(params, state, inputs, sea, dt) -> state`` is a pure function over frozen dataclasses
(Gymnasium functional-env / brax pipeline style). The dataclasses live in
:mod:`boat_dynamics.model`; the force models are one module each; the sum and the integration
are :mod:`boat_dynamics.fleet`, which steps one boat or many with the same code. Never imports
rclpy.
"""

from __future__ import annotations

from collections.abc import Sequence

from boat_dynamics.fleet import (
    Fleet,
    FleetInputs,
    FleetState,
    fleet_afloat,
    fleet_forces,
    fleet_step,
)
from boat_dynamics.model import (
    BoatInputs,
    BoatParams,
    BoatState,
    Forces,
    initial_state,
    reference_pose,
)
from ocean_sim.waves import WaveField

__all__ = [
    "BoatInputs",
    "BoatParams",
    "BoatState",
    "Forces",
    "afloat",
    "evaluate_forces",
    "initial_state",
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


def afloat(params: BoatParams, state: BoatState, sea: WaveField) -> BoatState:
    """``state`` with the velocity a boat has after floating a while in these waves.

    Released at rest over ground, a boat in waves lacks the orbital velocity its buoyancy
    would give it, and with quadratic surge drag alone (the derived damping) it keeps that
    offset as a drift for minutes, decaying as 1/t. So a boat starts with the velocity of
    :func:`boat_dynamics.fleet.fleet_afloat`: vertically the water's; horizontally the
    slope-driven orbital velocity of linear theory for the models pushed along the surface
    (``mesh``, sample points along the ``normal``), none for sample points pushed ``up``.
    Measured (tests/boat_dynamics/test_boat.py), the default 4 m box, derived damping, mean
    drift 10-40 s after the start:

    - one trochoidal wave (a 0.4 m, wavelength 40 m, Q 1: closed particle orbits, no drift):
      +0.005 and +0.002 m/s (released at a crest, in a trough); at rest -0.27 and +0.29;
    - a 0.3 m, wavelength 25 m, Q 0.5: 0.017 m/s; with the Gerstner water's velocity
      (Q a omega) 0.11; at rest 0.22.

    Args:
        params: the boat.
        state: its state; position, attitude and angular velocity are kept.
        sea: the wave field at ``state.t``, sampled as the boat's forces sample it (its wave
            filter and precision).

    Returns:
        The state with that velocity (body frame); zero in still water.
    """
    return fleet_afloat(_fleet([params]), FleetState.stack([state]), sea).boat(0)


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
