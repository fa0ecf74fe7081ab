"""A sensor's latency: readings held for a fixed time of simulation time, released in order.

A reading taken at t keeps its stamp t (the measurement's time, as drivers stamp them) and is
published at t + ``latency``: at the first step whose time is at or after it (within
:data:`TOLERANCE`, for the rounding of summed step times), so a latency that is not a whole
number of physics steps is rounded up to one.
"""

from __future__ import annotations

from collections import deque
from typing import Any

__all__ = ["TOLERANCE", "DelayLine"]

#: s: a release this close before the step's time is due (float sums of steps round by far
#: less; a step is at least 1e-4 s, simulation.rate_hz being at most 10 kHz).
TOLERANCE = 1e-6


class DelayLine:
    """Items held for ``latency`` s of simulation time, first in, first out.

    Args:
        latency: s, >= 0.
    """

    def __init__(self, latency: float) -> None:
        if not latency >= 0.0:
            raise ValueError(f"latency: {latency!r} s, must be >= 0")
        self.latency = float(latency)
        self._held: deque[tuple[float, Any]] = deque()

    def __len__(self) -> int:
        return len(self._held)

    def push(self, t: float, item: Any) -> None:
        """Hold ``item``, taken at ``t`` (s), until ``t + latency``."""
        self._held.append((t + self.latency, item))

    def pop_due(self, t: float) -> list[Any]:
        """The items due at ``t`` (s): released at or before it, in the order pushed."""
        out = []
        while self._held and self._held[0][0] <= t + TOLERANCE:
            out.append(self._held.popleft()[1])
        return out

    def clear(self) -> None:
        """Drop every item held (a restored snapshot's sensors start with none)."""
        self._held.clear()
