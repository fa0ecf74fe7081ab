"""Actuator commands: range checks, scripted sequences and a fleet's command intake.

A scenario's ``commands:`` list becomes a :class:`CommandScript`. A :class:`CommandIntake`
takes every command a fleet receives (the dynamics node hands it each ``cmd_thrust``,
``cmd_rudder`` and per-thruster value, with the simulation time it arrived at), checks it
(:func:`check_command`), keeps the last valid one and its time, applies the command
time-out, and gives the inputs of the next step. It knows no ROS: the node turns its
verdicts into log lines and /diagnostics.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from boat_dynamics.physics.core.model import BoatParams
from boat_dynamics.physics.core.system import FleetInputs
from boat_dynamics.physics.force_models.propulsion import MAX_THRUSTERS

__all__ = ["BoatCommands", "CommandCheck", "CommandIntake", "CommandScript", "Commanded",
           "TimedOut", "check_command"]


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


@dataclass(frozen=True)
class Commanded:
    """What a boat's commands are checked against.

    Attributes:
        params: the boat's parameters (its rudder's and thrusters' angle limits).
        script: its scripted commands, or None: it takes commands as they come.
        thrusters: how many named thrusters take commands of their own (0: one unnamed
            propulsion driven by ``cmd_thrust``; a scripted boat takes none).
    """

    params: BoatParams
    script: CommandScript | None = None
    thrusters: int = 0


@dataclass
class BoatCommands:
    """One boat's intake: the last valid commands, when they came, and the counts.

    Attributes:
        throttle: -1..1, the last valid ``cmd_thrust``.
        rudder: rad, the last valid ``cmd_rudder``.
        last_thrust_t: s of simulation time of the last valid ``cmd_thrust``.
        timed_out: no ``cmd_thrust`` within the time-out (the throttle is 0).
        thrusts: -1..1 per named thruster.
        angles: rad per named thruster (steering).
        thrust_t: s, the time of each named thruster's last throttle command.
        thrust_out: each named thruster timed out.
        received: commands received.
        ignored: of those, not finite (ignored).
        clamped: of those, out of range (clamped).
    """

    throttle: float = 0.0
    rudder: float = 0.0
    last_thrust_t: float = -math.inf
    timed_out: bool = True
    thrusts: list[float] = field(default_factory=list)
    angles: list[float] = field(default_factory=list)
    thrust_t: list[float] = field(default_factory=list)
    thrust_out: list[bool] = field(default_factory=list)
    received: int = 0
    ignored: int = 0
    clamped: int = 0


@dataclass(frozen=True)
class TimedOut:
    """A throttle set to 0 by the time-out: boat ``boat``, named thruster ``thruster`` (or None)."""

    boat: int
    thruster: int | None


#: A boat's intake in a snapshot: numbers ...
_SCALARS = ("throttle", "rudder", "last_thrust_t", "timed_out", "received", "ignored",
            "clamped")
#: ... and per named thruster (padded to MAX_THRUSTERS columns).
_PER_THRUSTER = ("thrusts", "angles", "thrust_t", "thrust_out")


class CommandIntake:
    """The commands of a fleet, as they arrive, and the inputs of each step.

    Args:
        boats: what each boat's commands are checked against.
    """

    def __init__(self, boats: Sequence[Commanded]) -> None:
        self.targets = tuple(boats)
        self.boats = [BoatCommands(thrusts=[0.0] * n, angles=[0.0] * n,
                                   thrust_t=[-math.inf] * n, thrust_out=[True] * n)
                      for n in (0 if b.script is not None else b.thrusters
                                for b in self.targets)]
        # the boats whose named thrusters take commands of their own (constant)
        self._named = [i for i, b in enumerate(self.targets) if b.thrusters and b.script is None]

    def _check(self, i: int, raw: float, limit: float, unit: str = "") -> CommandCheck:
        """Count and check a command of boat ``i`` against [-limit, limit]."""
        boat = self.boats[i]
        boat.received += 1
        checked = check_command(raw, -limit, limit, unit)
        if checked.problem:
            if checked.value is None:
                boat.ignored += 1
            else:
                boat.clamped += 1
        return checked

    def thrust(self, i: int, raw: float, t: float) -> CommandCheck:
        """``cmd_thrust`` of boat ``i`` at ``t`` s: it drives every named thruster too."""
        checked, boat = self._check(i, raw, 1.0), self.boats[i]
        if checked.value is not None:
            boat.throttle, boat.last_thrust_t, boat.timed_out = checked.value, t, False
            for j in range(len(boat.thrusts)):
                boat.thrusts[j], boat.thrust_t[j], boat.thrust_out[j] = checked.value, t, False
        return checked

    def thruster_thrust(self, i: int, j: int, raw: float, t: float) -> CommandCheck:
        """Named thruster ``j``'s throttle command of boat ``i`` at ``t`` s."""
        checked, boat = self._check(i, raw, 1.0), self.boats[i]
        if checked.value is not None:
            boat.thrusts[j], boat.thrust_t[j], boat.thrust_out[j] = checked.value, t, False
        return checked

    def thruster_angle(self, i: int, j: int, raw: float) -> CommandCheck:
        """Named thruster ``j``'s steering angle command of boat ``i``, rad."""
        limit = float(self.targets[i].params.thrusters[j].max_angle)
        checked = self._check(i, raw, limit, "rad")
        if checked.value is not None:
            self.boats[i].angles[j] = checked.value
        return checked

    def rudder(self, i: int, raw: float) -> CommandCheck:
        """``cmd_rudder`` of boat ``i``, rad: it steers the steerable named thrusters too."""
        params, boat = self.targets[i].params, self.boats[i]
        checked = self._check(i, raw, params.rudder.max_angle, "rad")
        if checked.value is None:
            return checked
        boat.rudder = checked.value
        for j, model in enumerate(params.thrusters[:len(boat.angles)]):
            if model.steerable:
                limit = float(model.max_angle)
                boat.angles[j] = min(max(checked.value, -limit), limit)
        return checked

    def inputs(self, t: float, timeout: float) -> tuple[FleetInputs, list[TimedOut]]:
        """The inputs of the step at ``t`` s, after the time-outs.

        A scripted boat follows its script; the others keep their last valid commands, but
        a throttle not renewed within ``timeout`` s falls to 0.

        Returns:
            The fleet's inputs, and the throttles that fell to 0 from a value other than 0
            (for a warning).
        """
        fell: list[TimedOut] = []
        commands = np.array([self._boat_inputs(i, t, timeout, fell)
                             for i in range(len(self.boats))], dtype=float).reshape(-1, 2)
        if not self._named:
            return FleetInputs(commands[:, 0], commands[:, 1]), fell
        throttle = np.repeat(commands[:, :1], MAX_THRUSTERS, axis=1)
        angle = np.repeat(commands[:, 1:2], MAX_THRUSTERS, axis=1)
        for i in self._named:
            boat = self.boats[i]
            for j in range(len(boat.thrusts)):
                if not boat.thrust_out[j] and t - boat.thrust_t[j] > timeout:
                    boat.thrust_out[j] = True
                    if boat.thrusts[j] != 0.0:
                        fell.append(TimedOut(i, j))
                    boat.thrusts[j] = 0.0
            throttle[i, :len(boat.thrusts)] = boat.thrusts
            angle[i, :len(boat.angles)] = boat.angles
        return FleetInputs(throttle, commands[:, 1], angle), fell

    def _boat_inputs(self, i: int, t: float, timeout: float, fell: list[TimedOut]
                     ) -> tuple[float, float]:
        """(throttle, rudder rad) of boat ``i`` at ``t``: scripted, or the last valid ones."""
        script, boat = self.targets[i].script, self.boats[i]
        if script is not None:
            return script.at(t)
        if not boat.timed_out and t - boat.last_thrust_t > timeout:
            boat.timed_out = True
            if boat.throttle != 0.0:
                fell.append(TimedOut(i, None))
            boat.throttle = 0.0
        return boat.throttle, boat.rudder

    def snapshot(self) -> dict[str, np.ndarray]:
        """The intake as arrays (``boats.<field>``: one row per boat)."""
        out = {f"boats.{name}": np.array([getattr(b, name) for b in self.boats])
               for name in _SCALARS}
        for name in _PER_THRUSTER:
            out[f"boats.{name}"] = np.array(
                [[*getattr(b, name), *[0] * (MAX_THRUSTERS - len(getattr(b, name)))]
                 for b in self.boats], dtype=float).reshape(-1, MAX_THRUSTERS)
        return out

    def restore(self, arrays: dict[str, np.ndarray]) -> None:
        """Continue from a :meth:`snapshot` of the same boats."""
        for i, b in enumerate(self.boats):
            for name in _SCALARS:
                setattr(b, name, type(getattr(b, name))(arrays[f"boats.{name}"][i]))
            for name in _PER_THRUSTER:
                kind = bool if name == "thrust_out" else float
                n = len(getattr(b, name))
                setattr(b, name, [kind(v) for v in arrays[f"boats.{name}"][i, :n]])
