"""Actuator commands: range checks and scripted command sequences (pure Python).

The ROS node feeds every incoming ``cmd_thrust`` / ``cmd_rudder`` value through
:func:`check_command`; a scenario's ``commands:`` list becomes a :class:`CommandScript`.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

__all__ = ["CommandCheck", "CommandScript", "check_command"]


@dataclass(frozen=True)
class CommandCheck:
    """Outcome of checking one command value.

    Attributes:
        value: the value to use, or None when the command must be ignored (non-finite).
        problem: why the raw value was not used as is, or None when it was fine.
    """

    value: float | None
    problem: str | None


def check_command(raw: float, low: float, high: float, unit: str = "") -> CommandCheck:
    """Refuse a non-finite command, clamp an out-of-range one into [low, high].

    Args:
        raw: the received value.
        low: smallest allowed value.
        high: largest allowed value.
        unit: unit shown in the message, e.g. "rad".

    Returns:
        The value to apply (None to keep the previous one) and the problem, if any.
    """
    suffix = f" {unit}" if unit else ""
    if not math.isfinite(raw):
        return CommandCheck(None, f"ignored {raw!r}: must be a finite number in "
                                  f"[{low:g}, {high:g}]{suffix}")
    if raw < low or raw > high:
        clamped = min(max(raw, low), high)
        return CommandCheck(clamped, f"clamped {raw:g} to {clamped:g}: allowed range is "
                                     f"[{low:g}, {high:g}]{suffix}")
    return CommandCheck(float(raw), None)


@dataclass(frozen=True)
class CommandScript:
    """Piecewise-constant commands in simulation time (a scenario's ``commands:`` list).

    Attributes:
        times: s, strictly increasing start times.
        throttles: -1..1 per entry.
        rudders: rad per entry.
    """

    times: tuple[float, ...]
    throttles: tuple[float, ...]
    rudders: tuple[float, ...]

    def at(self, t: float) -> tuple[float, float]:
        """(throttle, rudder) in force at time t (zero before the first entry)."""
        i = bisect.bisect_right(self.times, t) - 1
        if i < 0:
            return 0.0, 0.0
        return self.throttles[i], self.rudders[i]
