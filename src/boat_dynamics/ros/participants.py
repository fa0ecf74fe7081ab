"""The DDS participants of a ``boatsim run`` process: one per node, none matching its own.

Fast DDS 2.14 (ROS 2 Jazzy's default RMW) pairs each new endpoint of a participant with every
endpoint the participant already has (``EDP::pairing_writer_proxy_with_any_local_reader`` and
its twin copy each one's proxy data before comparing topics), so a participant's start-up grows
with writers x readers. Measured on the 2-core machine: 1000 boats' 12,000
publishers and 2,000 subscriptions in one participant took 27 s; with the participant property
``fastdds.ignore_local_endpoints`` (Fast DDS docs, "Ignore Local Endpoints") 9 s.

So a ``run`` process loads :data:`PROFILE` (that property in the default participant
profile) before its first participant, and gives every node a participant of its own
(:class:`Participants`, one rclpy Context each): nodes of one process still hear each other,
as any two participants do. A user's own Fast DDS profile, or another RMW, is left alone.
"""

from __future__ import annotations

import os
from collections.abc import MutableMapping
from pathlib import Path

import rclpy
from rclpy.context import Context
from rclpy.signals import SignalHandlerOptions

__all__ = ["PROFILE", "PROFILE_VARIABLES", "Participants", "use_profile"]

#: boatsim's Fast DDS XML profile: participants ignore their own endpoints.
PROFILE = Path(__file__).with_name("fastdds_profile.xml")
#: The variables Fast DDS reads its default profile file from (2.x, and 3.x's new name).
PROFILE_VARIABLES = ("FASTRTPS_DEFAULT_PROFILES_FILE", "FASTDDS_DEFAULT_PROFILES_FILE")
_FASTRTPS = "rmw_fastrtps_cpp"


def use_profile(environ: MutableMapping[str, str] | None = None) -> str | None:
    """Make this process's participants load :data:`PROFILE`, unless the user chose otherwise.

    Call before the process makes its first DDS participant (Fast DDS reads the profile file
    once per process). Child processes inherit it.

    Args:
        environ: the environment to set (default: ``os.environ``).

    Returns:
        None when the profile is in use, else why it is not (for a log line).
    """
    env = os.environ if environ is None else environ
    rmw = env.get("RMW_IMPLEMENTATION") or _FASTRTPS
    if rmw != _FASTRTPS:
        return f"RMW_IMPLEMENTATION is {rmw}, not {_FASTRTPS}"
    for variable in PROFILE_VARIABLES:
        value = env.get(variable)
        if value and Path(value) != PROFILE:
            return f"{variable} names your own Fast DDS profile ({value})"
    env[PROFILE_VARIABLES[0]] = str(PROFILE)
    return None


class Participants:
    """The rclpy contexts (one DDS participant each) made for a process's nodes.

    The first node of a process takes rclpy's default context; each further node takes
    :meth:`new`. :meth:`shutdown` ends them all but the default one.
    """

    def __init__(self) -> None:
        self._contexts: list[Context] = []

    def new(self) -> Context:
        """A new initialized context, its signals left to the process (as the default's)."""
        context = Context()
        rclpy.init(context=context, signal_handler_options=SignalHandlerOptions.NO)
        self._contexts.append(context)
        return context

    def shutdown(self) -> None:
        """Shut down every context made here (idempotent)."""
        for context in self._contexts:
            context.try_shutdown()
