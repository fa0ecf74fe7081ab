"""Boats that feel each other's waves: the made waves' force on every boat of a fleet.

Each boat that makes waves (``made_waves``: its Kelvin wake at speed, :mod:`.kelvin_wake`;
the waves it radiates and scatters in the sea, from its file's Kochin functions,
:mod:`.scattered_waves`) is a source; each boat with potential-flow coefficients is a
receiver, and feels the waves of every other source as local plane waves through its own
Froude-Krylov and diffraction transfer functions (:mod:`.made_waves`, the wide-spacing
approximation). Linear
superposition: the made waves add to the sea's components and to each other; a receiver's
own waves are in its radiation and diffraction forces already. A receiver ignores made
waves shorter than its ``min_wavelength``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.body.wrench import Wrench
from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients
from boat_dynamics.physics.wave_making.kelvin_wake import (
    ThinShip,
    leaves_wake,
    pair_waves,
    wake_elevation,
)
from boat_dynamics.physics.wave_making.made_waves import local_wrenches
from boat_dynamics.physics.wave_making.scattered_waves import hull_radius, outgoing_waves
from ocean_sim.physics.waves import WaveComponent, WaveField

__all__ = ["MADE_WAVES_MODELS", "SCATTER_REACH", "WAKE_REACH", "MadeWaves", "MadeWavesModel",
           "feels_made_waves", "made_waves_build", "made_waves_elevation", "made_waves_wrench"]

#: What waves a boat makes that the others feel: ``wake``, its Kelvin wake at speed;
#: ``scattered``, the waves it radiates and scatters in the sea (its file's Kochin
#: functions); ``all``, both; ``none``.
MadeWavesModel = Literal["all", "wake", "scattered", "none"]
MADE_WAVES_MODELS: tuple[MadeWavesModel, ...] = get_args(MadeWavesModel)


#: How far behind its hull a wake is felt, in hull lengths (40: 160 m behind a 4 m boat,
#: where its transverse waves have a third of their height 16 m behind it). A bound on the
#: cost, which grows with the pairs of boats within reach of each other.
WAKE_REACH = 40.0


#: How far a boat's radiated and scattered waves are felt, in hull radii (the half-diagonal
#: of its waterplane, :func:`.scattered_waves.hull_radius`: 8 x 2.2 = 18 m for the default
#: box, where k r is 18 for a 2 s wave and their amplitude has fallen to a third of its value
#: at 2 radii). A bound on the cost: each scatterer in reach of another answers the sea and
#: then the waves it receives (a fleet 20 m apart pays nothing).
SCATTER_REACH = 8.0


@dataclass(frozen=True)
class MadeWaves:
    """The fleet's wave makers and the boats that feel them (:attr:`System.made_waves`).

    Attributes:
        ships: the wake makers' hulls, each with (S,) int, the fleet places of the boats
            that have it (boats sharing parameters share their thin ship).
        receivers: (R,) int, the boats with coefficients, which feel the waves.
        min_wavelength: (R,) m, their wave filters.
        gravity: g, m/s^2.
        hydro_groups: each coefficient set of the receivers with (K,) int, the sorted rows
            of ``receivers`` that have it (their wrenches are evaluated together).
        scatterers: (C,) int, the boats that radiate and scatter waves (coefficients with
            Kochin functions).
        viscous: (C, 6) their linear damping, added to the radiation damping of their RAOs.
        scatterer_wavelength: (C,) m, their wave filters (the components they answer).
        scatterer_hydro: their coefficients.
        scatter_reach: (C,) m, how far their waves are felt (:data:`SCATTER_REACH` hull
            radii).
    """

    ships: tuple[tuple[ThinShip, np.ndarray], ...]
    receivers: np.ndarray
    min_wavelength: np.ndarray
    gravity: float
    hydro_groups: tuple[tuple[HydroCoefficients, np.ndarray], ...] = ()
    scatterers: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.intp))
    viscous: np.ndarray = field(default_factory=lambda: np.zeros((0, 6)))
    scatterer_wavelength: np.ndarray = field(default_factory=lambda: np.zeros(0))
    scatterer_hydro: tuple[HydroCoefficients, ...] = ()
    scatter_reach: np.ndarray = field(default_factory=lambda: np.zeros(0))


def made_waves_build(params: Sequence) -> MadeWaves | None:
    """The fleet's :class:`MadeWaves`, or None when no boat would feel another's waves.

    Args:
        params: the boats' :class:`~boat_dynamics.physics.core.model.BoatParams`.
    """
    makers: dict[int, tuple[ThinShip, list[int]]] = {}
    for i, p in enumerate(params):
        if p.made_waves in ("all", "wake") and p.thin_ship is not None:
            makers.setdefault(id(p.thin_ship), (p.thin_ship, []))[1].append(i)
    scatterers = [i for i, p in enumerate(params) if p.made_waves in ("all", "scattered")
                  and p.hydro is not None and p.hydro.has_kochin]
    sources = [i for _, members in makers.values() for i in members] + scatterers
    receivers = [i for i, p in enumerate(params) if p.hydro is not None]
    if not any(r != s for r in receivers for s in sources):
        return None
    hydro = tuple(params[i].hydro for i in receivers)
    groups: dict[int, list[int]] = {}
    for row, h in enumerate(hydro):
        groups.setdefault(id(h), []).append(row)
    return MadeWaves(tuple((ship, np.array(m, dtype=np.intp)) for ship, m in makers.values()),
                     np.array(receivers, dtype=np.intp),
                     np.array([params[i].min_wavelength for i in receivers], dtype=float),
                     float(params[0].gravity),
                     tuple((hydro[rows[0]], np.array(rows, dtype=np.intp))
                           for rows in groups.values()),
                     np.array(scatterers, dtype=np.intp),
                     np.array([params[i].damping_linear for i in scatterers],
                              dtype=float).reshape(-1, 6),
                     np.array([params[i].min_wavelength for i in scatterers], dtype=float),
                     tuple(params[i].hydro for i in scatterers),
                     np.array([SCATTER_REACH * hull_radius(params[i].hydro) for i in scatterers],
                              dtype=float))


def feels_made_waves(params) -> bool:
    """Whether a boat feels the waves others make: it has coefficients, or will have them.

    ``coefficients: auto`` without a file: ``pipeline.init`` estimates them.

    Args:
        params: its :class:`~boat_dynamics.physics.core.model.BoatParams`, derived or not.
    """
    return params.hydro is not None or (params.derive is not None
                                        and params.derive.estimate is not None)


def _courses(velocity_world: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(B,) m/s speeds and (B,) rad courses of horizontal velocities (B, 2) through water."""
    return (np.hypot(velocity_world[:, 0], velocity_world[:, 1]),
            np.arctan2(velocity_world[:, 1], velocity_world[:, 0]))


def _wakes_at(made: MadeWaves, reference_xy: np.ndarray, through_water: np.ndarray
              ) -> tuple[np.ndarray, ...] | None:
    """Every wake wave at every receiver, one pass per hull shape over the pairs in reach.

    Returns:
        (N,) each: the receiver's row in ``made.receivers``, amplitude m, omega rad/s, k
        rad/m, direction rad (world), phase rad at the receiver; None: no wave anywhere.
    """
    speed, course = _courses(through_water)
    at = reference_xy[made.receivers]
    found = []
    for ship, members in made.ships:
        fast = members[leaves_wake(speed[members], made.gravity)]
        if fast.shape[0] == 0:
            continue
        d = at[None, :, :] - reference_xy[fast][:, None, :]  # (S, R, 2)
        c, s = np.cos(course[fast])[:, None], np.sin(course[fast])[:, None]
        x, y = d[..., 0] * c + d[..., 1] * s, d[..., 1] * c - d[..., 0] * s
        near = ((x < -0.5 * ship.length) & (8.0 * y * y <= x * x)
                & (x > -WAKE_REACH * ship.length)
                & (fast[:, None] != made.receivers[None, :]))
        si, rj = np.nonzero(near)
        if si.shape[0] == 0:
            continue
        u = speed[fast][si]
        theta, k, a = pair_waves(ship, x[si, rj], y[si, rj], u, made.gravity)
        live = (a != 0.0) & (2.0 * math.pi / k >= made.min_wavelength[rj][None, :])
        b, p = np.nonzero(live)
        found.append((rj[p], np.abs(a[b, p]), k[b, p] * u[p] * np.cos(theta[b, p]), k[b, p],
                      course[fast][si[p]] + theta[b, p], np.angle(a[b, p])))
    return _joined(found)


def _scattered_at(made: MadeWaves, reference_xy: np.ndarray, heading: np.ndarray,
                  sea: WaveField, t: float) -> tuple[np.ndarray, ...] | None:
    """Every radiated and scattered wave at every other receiver (:func:`_wakes_at`'s rows).

    Each scatterer's answer to the sea's components acting on it
    (:func:`.scattered_waves.outgoing_waves`), at the receivers other than itself; then, once,
    its answer to those of the others' waves that reach it (:func:`_passed_on`): multiple
    scattering to second order, which brings a boat's own waves back to it off its
    neighbours.
    """
    if made.scatterers.shape[0] == 0 or not sea.components:
        return None
    first = _joined([_outgoing(made, c, sea.filtered(float(made.scatterer_wavelength[c])),
                               reference_xy, heading, t)
                     for c in range(made.scatterers.shape[0])])
    if first is None:
        return None
    second = _joined([_passed_on(made, c, first, reference_xy, heading, t, sea.gravity,
                                 sea.depth) for c in range(made.scatterers.shape[0])])
    return _joined([first, second])


def _joined(parts: list[tuple[np.ndarray, ...] | None]) -> tuple[np.ndarray, ...] | None:
    """The made waves of several parts (each as :func:`_wakes_at` gives them) as one.

    None when every part is None.
    """
    found = [p for p in parts if p is not None]
    if not found:
        return None
    return found[0] if len(found) == 1 else tuple(
        np.concatenate(columns) for columns in zip(*found, strict=True))


def _outgoing(made: MadeWaves, c: int, acting: WaveField, reference_xy: np.ndarray,
              heading: np.ndarray, t: float) -> tuple[np.ndarray, ...] | None:
    """Scatterer c's waves in ``acting`` at the other receivers, as :func:`_wakes_at`'s rows."""
    s = made.scatterers[c]
    d = reference_xy[made.receivers] - reference_xy[s]
    rows = np.flatnonzero((made.receivers != s)
                          & (np.hypot(d[:, 0], d[:, 1]) <= made.scatter_reach[c]))
    if rows.shape[0] == 0 or not acting.components:
        return None
    waves = outgoing_waves(made.scatterer_hydro[c], acting, reference_xy[s], float(heading[s]),
                           reference_xy[made.receivers[rows]], t, viscous=made.viscous[c])
    found = []
    for j, w in zip(rows, waves, strict=True):
        keep = 2.0 * math.pi / np.maximum(w.wavenumber, 1e-300) >= made.min_wavelength[j]
        if w.count and keep.any():
            found.append((np.full(int(keep.sum()), j), w.amplitude[keep], w.omega[keep],
                          w.wavenumber[keep], w.direction[keep], w.phase[keep]))
    return _joined(found)


def _passed_on(made: MadeWaves, c: int, waves: tuple[np.ndarray, ...],
               reference_xy: np.ndarray, heading: np.ndarray, t: float, gravity: float,
               depth: float) -> tuple[np.ndarray, ...] | None:
    """Scatterer c's answer to the made waves that reach it, as :func:`_outgoing` gives it.

    The plane waves at its reference point (``waves``' rows of it) become the components of
    a sea of their own: a cos(k D . r - omega t + phi) with phi such that each has its phase
    at the scatterer at ``t``.
    """
    s = made.scatterers[c]
    row = np.flatnonzero(made.receivers == s)
    rows, amplitude, omega, k, direction, phase = waves
    mine = rows == row[0] if row.shape[0] else np.zeros(rows.shape, dtype=bool)
    mine &= 2.0 * math.pi / np.maximum(k, 1e-300) >= made.scatterer_wavelength[c]
    if not mine.any():
        return None
    d = np.stack([np.cos(direction[mine]), np.sin(direction[mine])], axis=1)
    phi = phase[mine] - k[mine] * (d @ reference_xy[s]) + omega[mine] * t
    received = WaveField(tuple(WaveComponent(float(a), 2.0 * math.pi / float(q), float(b), 0.0,
                                             float(f))
                               for a, q, b, f in zip(amplitude[mine], k[mine],
                                                     direction[mine], phi, strict=True)),
                         gravity=gravity, depth=depth)
    return _outgoing(made, c, received, reference_xy, heading, t)


def made_waves_wrench(made: MadeWaves, reference_xy: np.ndarray, heading: np.ndarray,
                      velocity_world: np.ndarray, through_water: np.ndarray, t: float,
                      count: int, sea: WaveField | None = None) -> Wrench:
    """(B, 3) force and (B, 3) torque of the waves other boats make, body frames.

    Args:
        made: the fleet's wave makers and receivers.
        reference_xy: (B, 2) m, world x, y of the hull reference points.
        heading: (B,) rad, yaws.
        velocity_world: (B, 2) m/s, horizontal velocities over ground, world frame.
        through_water: (B, 2) m/s, the same through the water (the current taken off).
        t: s.
        count: B.
        sea: the sea the boats are in (the scatterers answer it), or None: calm.
    """
    force, torque = np.zeros((count, 3)), np.zeros((count, 3))
    waves = _joined([_wakes_at(made, reference_xy, through_water),
                     None if sea is None else _scattered_at(made, reference_xy, heading, sea,
                                                            t)])
    if waves is None:
        return Wrench(force, torque)
    rows, amplitude, omega, k, direction, phase = waves
    for hydro, members in made.hydro_groups:
        mine = np.isin(rows, members)
        if not mine.any():
            continue
        place = np.searchsorted(members, rows[mine])  # owner: the receiver's place in members
        boats = made.receivers[members]
        scattered, incident = local_wrenches(
            hydro, place, heading[boats], velocity_world[boats], amplitude[mine], omega[mine],
            k[mine], direction[mine], phase[mine])
        total = scattered + incident
        force[boats], torque[boats] = total[:, :3], total[:, 3:]
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
