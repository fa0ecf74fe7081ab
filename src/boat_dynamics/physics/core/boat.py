"""One boat (or a few) at a time: conveniences over the batched pipeline, for tests and tools.

Each call builds a one-boat :class:`~boat_dynamics.physics.core.system.System` and runs
:mod:`boat_dynamics.physics.core.pipeline`, the one implementation of the physics; the dynamics
node steps its whole fleet through the pipeline directly. Nothing is cached between calls.
"""

from __future__ import annotations

from collections.abc import Sequence

from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.contact import contact
from boat_dynamics.physics.core.model import (
    BoatInputs,
    BoatParams,
    BoatState,
    Forces,
    initial_state,
    reference_pose,
)
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from ocean_sim.physics.environment import Environment
from ocean_sim.physics.waves import WaveField

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


def afloat(params: BoatParams, state: BoatState, sea: WaveField) -> BoatState:
    """``state`` with the velocity a boat has after floating a while (:func:`pipeline.afloat`).

    Measured (tests/boat_dynamics/physics/core/test_boat.py), the default 4 m box, derived damping,
    mean drift 10-40 s after the start:

    - one trochoidal wave (a 0.4 m, wavelength 40 m, Q 1: closed particle orbits, no drift):
      +0.005 and +0.002 m/s (released at a crest, in a trough); at rest -0.27 and +0.29;
    - a 0.3 m, wavelength 25 m, Q 0.5: 0.017 m/s; with the Gerstner water's velocity
      (Q a omega) 0.11; at rest 0.22.

    Args:
        params: the boat.
        state: its state; position, attitude and angular velocity are kept.
        sea: the wave field at ``state.t``.

    Returns:
        The state with that velocity (body frame); zero in still water.
    """
    return pipeline.afloat(System.build([params]), FleetState.stack([state]), sea).boat(0)


def evaluate_forces(
    params: BoatParams, state: BoatState, inputs: BoatInputs, sea: WaveField,
    environment: Environment | None = None,
) -> Forces:
    """Evaluate every force model at ``state`` and sum them.

    Args:
        params: the boat.
        state: its state.
        inputs: validated actuator commands.
        sea: the wave field.
        environment: the current and the wind, or None.

    Returns:
        Each source's wrench and the total, body frame, about the centre of mass.
    """
    system, fleet_state = System.build([params]), FleetState.stack([state])
    forces, _ = pipeline.forces(system, fleet_state, FleetInputs.stack([inputs]),
                                contact(system, fleet_state, sea), environment)
    return forces.boat(0)


def step(
    params: BoatParams, state: BoatState, inputs: BoatInputs, sea: WaveField, dt: float,
    environment: Environment | None = None,
) -> BoatState:
    """Advance one boat by ``dt`` seconds (semi-implicit Euler).

    Args:
        params: the boat.
        state: its state at time t.
        inputs: validated actuator commands, held over the step.
        sea: the wave field.
        dt: s, > 0.
        environment: the current and the wind, or None.

    Returns:
        The state at t + dt.
    """
    return pipeline.step(System.build([params]), FleetState.stack([state]),
                         FleetInputs.stack([inputs]), sea, dt,
                         environment=environment).state.boat(0)


def step_many(params: Sequence[BoatParams], states: Sequence[BoatState],
              inputs: Sequence[BoatInputs], sea: WaveField, dt: float
              ) -> list[tuple[BoatState, Forces]]:
    """Advance several boats by ``dt`` s together, one pipeline step per distinct time.

    Each is alone on the sea (:meth:`.System.apart`): none feels another's waves.

    Returns:
        For each boat, its state at t + dt and the forces that acted during the step.
    """
    by_time: dict[float, list[int]] = {}
    for i, s in enumerate(states):
        by_time.setdefault(s.t, []).append(i)
    out: list = [None] * len(states)
    for members in by_time.values():
        done = pipeline.step(System.build([params[i] for i in members]).apart(),
                             FleetState.stack([states[i] for i in members]),
                             FleetInputs.stack([inputs[i] for i in members]), sea, dt)
        for k, i in enumerate(members):
            out[i] = (done.state.boat(k), done.forces.boat(k))
    return out

