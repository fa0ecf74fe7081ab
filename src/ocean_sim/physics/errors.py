"""The one error of a value that is not allowed, shared by both physics layers.

A refused value names the key it came from, the value and what is allowed (as rosbags'
errors do): :class:`InvalidValueError`. The sea's, the scenario's and the start-up's errors
(:class:`ocean_sim.physics.waves.InvalidSeaStateError`,
:class:`boat_dynamics.physics.scenario.ScenarioError`,
:class:`boat_dynamics.physics.core.pipeline.InitError`) are kinds of it, so a caller that turns
bad input into a clear message and an exit status catches one class.
"""

from __future__ import annotations

__all__ = ["InvalidValueError"]


class InvalidValueError(ValueError):
    """A value that is not allowed.

    Attributes:
        key: where the value came from, e.g. ``boats[0].mass`` or ``components[2].wavelength``.
        value: the value found.
        allowed: what would have been accepted.
    """

    def __init__(self, key: str, value: object, allowed: str, message: str | None = None
                 ) -> None:
        """``message``: the text, when not ``KEY: VALUE is not allowed: ALLOWED``."""
        self.key, self.value, self.allowed = key, value, allowed
        super().__init__(message if message is not None
                         else f"{key}: {value!r} is not allowed: {allowed}")
