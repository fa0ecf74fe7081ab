"""An AIS receiver: the other boats' position reports, at the rates AIS class A sends them.

Each other boat within ``range`` of the receiver reports its position (WGS-84, of its hull
reference point, with white noise of ``position_sigma`` m per horizontal axis, as its own
GNSS would), its course and speed over ground and its heading, every reporting interval of
its speed (ITU-R M.1371-5, Annex 1, Table 1, class A underway: 10 s below 14 knots, 6 s
from 14 to 23, 2 s above; here a boat at :data:`AT_ANCHOR` m/s or slower counts as at
anchor: 180 s). The receiver looks for due reports at its ``rate_hz``; a report is due
once its interval has passed since the boat's last one, and every boat's first at the
receiver's first look.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.physics.sensors.noise import standard_normal

__all__ = ["AT_ANCHOR", "KNOT", "AisReport", "AisSpec", "AisState", "ais_reports",
           "report_interval"]

#: m/s in a knot.
KNOT = 1852.0 / 3600.0
#: m/s: a boat this slow or slower reports as at anchor (every 3 minutes).
AT_ANCHOR = 0.2


@dataclass(frozen=True)
class AisSpec:
    """An AIS receiver on a boat.

    Attributes:
        name: its name (topic ``<ns>/<name>/reports``).
        rate_hz: how often it looks for due reports.
        position: (3,) m, body frame (its antenna; unused but for /tf_static).
        range: m, the farthest boat it hears (VHF: about 20 nautical miles).
        position_sigma: m, each report's position noise per horizontal axis.
        dropout: the probability that a report is lost.
        latency: s from a report to its publication.
    """

    name: str = "ais"
    rate_hz: float = 1.0
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    range: float = 37_000.0
    position_sigma: float = 5.0
    dropout: float = 0.0
    latency: float = 0.0


@dataclass(frozen=True)
class AisState:
    """The receiver's looks taken (its noise draws) and each boat's last report time.

    Attributes:
        sample: looks taken.
        last: (B,) s, each boat's last report (-inf: none yet).
    """

    sample: int = 0
    last: np.ndarray | None = None


@dataclass(frozen=True)
class AisReport:
    """One boat's report.

    Attributes:
        boat: its index in the fleet.
        position: (3,) m, world frame, its reported position (noisy).
        course: rad, its course over ground, counter-clockwise from east (ENU).
        speed: m/s, its speed over ground.
        heading: rad, its heading, counter-clockwise from east.
    """

    boat: int
    position: np.ndarray
    course: float
    speed: float
    heading: float


def report_interval(speed: float) -> float:
    """Seconds between a class A transponder's reports at ``speed`` m/s over ground."""
    if speed <= AT_ANCHOR:
        return 180.0
    knots = speed / KNOT
    return 10.0 if knots < 14.0 else 6.0 if knots <= 23.0 else 2.0


def ais_reports(spec: AisSpec, key: np.ndarray, state: AisState, t: float, own: int,
                positions: np.ndarray, velocities: np.ndarray, headings: np.ndarray,
                transponders: np.ndarray | None = None) -> tuple[list[AisReport], AisState]:
    """The reports due at ``t`` (s), and the receiver's state after them.

    Args:
        spec: the receiver.
        key: its noise stream.
        state: its state before.
        t: s, simulation time.
        own: its boat's index (not reported to itself).
        positions: (B, 3) m, every boat's hull reference point, world frame.
        velocities: (B, 3) m/s, their velocities over ground, world frame.
        headings: (B,) rad, counter-clockwise from east.
        transponders: (B,) bool, the bodies that transmit (boats, not buoys); None: all.
    """
    count = positions.shape[0]
    last = np.full(count, -math.inf) if state.last is None else state.last.copy()
    speed = np.hypot(velocities[:, 0], velocities[:, 1])
    due = np.array([t - last[b] >= report_interval(speed[b]) - 1e-9 for b in range(count)])
    heard = np.hypot(*(positions[:, :2] - positions[own, :2]).T) <= spec.range
    due &= heard & (np.arange(count) != own)
    if transponders is not None:
        due &= transponders
    noise = spec.position_sigma * standard_normal(key, state.sample, 2 * count).reshape(-1, 2)
    out = []
    for b in np.flatnonzero(due):
        where = positions[b].copy()
        where[:2] += noise[b]
        out.append(AisReport(int(b), where, math.atan2(velocities[b, 1], velocities[b, 0]),
                             float(speed[b]), float(headings[b])))
        last[b] = t
    return out, AisState(state.sample + 1, last)
