"""Boats that feel each other's waves: the made waves' force on every boat of a fleet.

Each boat that makes waves (``made_waves``: its Kelvin wake, :mod:`.kelvin_wake`) is a
source; each boat with potential-flow coefficients is a receiver, and feels the waves of
every other source as local plane waves through its own Froude-Krylov and diffraction
transfer functions (:mod:`.made_waves`, the wide-spacing approximation). Linear
superposition: the made waves add to the sea's components and to each other; a receiver's
own waves are in its radiation and diffraction forces already. A receiver ignores made
waves shorter than its ``min_wavelength``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.body.wrench import Wrench
from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients
from boat_dynamics.physics.potential_flow.kelvin_wake import (
    SHORTEST_WAVE,
    ThinShip,
    _waves,
    wake_elevation,
)
from boat_dynamics.physics.potential_flow.made_waves import LocalWaves, local_wrench, stacked

__all__ = ["MADE_WAVES_MODELS", "MadeWaves", "MadeWavesModel", "Source", "made_waves_build",
           "made_waves_elevation", "made_waves_wrench"]

#: What waves a boat makes that the others feel: ``wake``, its Kelvin wake at speed;
#: ``none``. (``all``: every kind this version models.)
MadeWavesModel = Literal["all", "wake", "none"]
MADE_WAVES_MODELS: tuple[MadeWavesModel, ...] = get_args(MadeWavesModel)


@dataclass(frozen=True)
class Source:
    """A boat that makes waves.

    Attributes:
        index: its place in the fleet.
        ship: its thin-ship hull (:func:`.kelvin_wake.thin_ship`), for its wake.
        gravity: g, m/s^2.
    """

    index: int
    ship: ThinShip
    gravity: float


@dataclass(frozen=True)
class MadeWaves:
    """The fleet's wave makers and the boats that feel them (:attr:`System.made_waves`).

    Attributes:
        sources: the boats that make waves.
        receivers: (R,) int, the boats with coefficients, which feel them.
        hydro: their coefficients, one per receiver.
        min_wavelength: (R,) m, their wave filters.
    """

    sources: tuple[Source, ...]
    receivers: np.ndarray
    hydro: tuple[HydroCoefficients, ...]
    min_wavelength: np.ndarray


def made_waves_build(params: Sequence) -> MadeWaves | None:
    """The fleet's :class:`MadeWaves`, or None when no boat would feel another's waves.

    Args:
        params: the boats' :class:`~boat_dynamics.physics.core.model.BoatParams`.
    """
    sources = tuple(Source(i, p.thin_ship, p.gravity) for i, p in enumerate(params)
                    if p.made_waves in ("all", "wake") and p.thin_ship is not None)
    receivers = [i for i, p in enumerate(params) if p.hydro is not None]
    if not sources or not any(r != s.index for r in receivers for s in sources):
        return None
    return MadeWaves(sources, np.array(receivers, dtype=np.intp),
                     tuple(params[i].hydro for i in receivers),
                     np.array([params[i].min_wavelength for i in receivers], dtype=float))


def _courses(velocity_world: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(B,) m/s speeds and (B,) rad courses of horizontal velocities (B, 2) through water."""
    return (np.hypot(velocity_world[:, 0], velocity_world[:, 1]),
            np.arctan2(velocity_world[:, 1], velocity_world[:, 0]))


def _wakes_at(made: MadeWaves, reference_xy: np.ndarray, through_water: np.ndarray, t: float
              ) -> list[list[LocalWaves]]:
    """Per receiver, the local waves of every other source's wake at its reference point."""
    speed, course = _courses(through_water)
    at = reference_xy[made.receivers]
    out: list[list[LocalWaves]] = [[] for _ in made.receivers]
    for s in made.sources:
        u = float(speed[s.index])
        if 2.0 * math.pi * u * u / s.gravity < SHORTEST_WAVE:
            continue  # too slow to leave a wake
        theta, k, a = _waves(s.ship, u, reference_xy[s.index], float(course[s.index]), at,
                             s.gravity)
        for j, r in enumerate(made.receivers):
            live = (a[:, j] != 0.0) & (2.0 * math.pi / k[:, j] >= made.min_wavelength[j])
            if r == s.index or not live.any():
                continue
            out[j].append(LocalWaves(at[j], t, np.abs(a[live, j]),
                                     k[live, j] * u * np.cos(theta[live, j]), k[live, j],
                                     course[s.index] + theta[live, j], np.angle(a[live, j])))
    return out


def made_waves_wrench(made: MadeWaves, reference_xy: np.ndarray, heading: np.ndarray,
                      velocity_world: np.ndarray, through_water: np.ndarray, t: float,
                      count: int) -> Wrench:
    """(B, 3) force and (B, 3) torque of the waves other boats make, body frames.

    Args:
        made: the fleet's wave makers and receivers.
        reference_xy: (B, 2) m, world x, y of the hull reference points.
        heading: (B,) rad, yaws.
        velocity_world: (B, 2) m/s, horizontal velocities over ground, world frame.
        through_water: (B, 2) m/s, the same through the water (the current taken off).
        t: s.
        count: B.
    """
    force, torque = np.zeros((count, 3)), np.zeros((count, 3))
    for j, waves in enumerate(_wakes_at(made, reference_xy, through_water, t)):
        if not waves:
            continue
        r = made.receivers[j]
        local = waves[0] if len(waves) == 1 else stacked(waves)
        scattered, incident = local_wrench(made.hydro[j], local, float(heading[r]),
                                           velocity_world[r])
        total = scattered + incident
        force[r], torque[r] = total[:3], total[3:]
    return Wrench(force, torque)


def made_waves_elevation(ships: Sequence[ThinShip | None], reference_xy: np.ndarray,
                         through_water: np.ndarray, xy: np.ndarray,
                         gravity: float) -> np.ndarray:
    """(P,) m, the elevation of every boat's wake at world points ``xy`` (P, 2) (the view).

    Args:
        ships: each boat's thin-ship hull, or None for a boat that makes no wake.
        reference_xy: (B, 2) m, world x, y of the hull reference points.
        through_water: (B, 2) m/s, horizontal velocities through the water, world frame.
        xy: (P, 2) m, world points.
        gravity: g, m/s^2.
    """
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    speed, course = _courses(np.asarray(through_water, dtype=float).reshape(-1, 2))
    out = np.zeros(xy.shape[0])
    for i, ship in enumerate(ships):
        if ship is not None:
            out += wake_elevation(ship, float(speed[i]), reference_xy[i], float(course[i]), xy,
                                  gravity)
    return out
