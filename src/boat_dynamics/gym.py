"""Gymnasium environments over the physics core: steer a boat to a waypoint, without ROS.

An adapter over :mod:`boat_dynamics.physics.core.pipeline` (no rclpy, no rosbags; the
``gym`` extra, requirements/gym.txt): :class:`BoatEnv` is one boat (a ``gymnasium.Env``),
:class:`BoatVectorEnv` is ``num_envs`` copies of it stepped together in one
:class:`~boat_dynamics.physics.core.system.System` (a ``gymnasium.vector.VectorEnv``: one
pipeline step for the whole batch). Boats do not interact, so the copies start at the same
pose, each with its own waypoint.

The task (:class:`Task`): a waypoint is drawn from the reset's seed, at a distance in
``waypoint_range`` (m) and any bearing from the boat's start; each control period (``control
_period`` s of simulation time: the scenario's physics steps held at one command) the reward
is the progress towards it (the decrease in horizontal distance, m). An episode terminates
when the boat arrives within ``arrival_radius`` (+ ``arrival_reward``), or capsizes (roll or
pitch beyond 90 degrees) or its state diverges (- ``arrival_reward``); it is truncated after
``episode_time`` s. Observation and action: :data:`OBSERVATION_FIELDS`,
:data:`ACTION_FIELDS` (SI units, radians). Commands pass through the dynamics node's own
:class:`~boat_dynamics.physics.core.commands.CommandIntake`: an out-of-range action is
clamped into the boat's range as ``cmd_thrust`` and ``cmd_rudder`` are (counted in the info's
``clamped``), a NaN or infinite one is refused with :class:`InvalidValueError`.

Same seed, same episode: ``reset(seed=s)`` and the same actions give bit-identical
observations (the physics is deterministic; the waypoint is the only draw).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.commands import Commanded, CommandIntake
from boat_dynamics.physics.core.system import FleetState
from boat_dynamics.physics.scenario import Scenario, load_scenario
from ocean_sim.physics.errors import InvalidValueError

__all__ = ["ACTION_FIELDS", "OBSERVATION_FIELDS", "BoatEnv", "BoatVectorEnv",
           "InvalidValueError", "Task"]

#: The observation's entries, in order (float64): the waypoint ahead of the boat and to port
#: of it, along its heading (m: the horizontal offset from the centre of mass, in the frame
#: turned by the heading alone); the centre of mass's height (m, world z, up); roll, pitch,
#: heading (rad, ZYX; heading from east, counter-clockwise); the body-frame velocity u, v, w
#: (m/s, x forward, y to port, z up) and angular velocity p, q, r (rad/s); the actual thrust
#: fraction of the first thruster (-1..1; it lags the command by the thruster's time constant).
OBSERVATION_FIELDS = ("waypoint_ahead", "waypoint_port", "z", "roll", "pitch", "heading",
                      "u", "v", "w", "p", "q", "r", "throttle")
#: The action's entries: throttle (-1..1, a fraction of every thruster's maximum, negative
#: astern: ``cmd_thrust``) and rudder (rad, + turns the bow to port, within the boat's
#: ``rudder.max_angle_deg``; it steers steerable thrusters too: ``cmd_rudder``).
ACTION_FIELDS = ("throttle", "rudder")


@dataclass(frozen=True)
class Task:
    """The waypoint task.

    Attributes:
        control_period: s of simulation time an action is held (a whole number of the
            scenario's physics steps, 1 / (``rate_hz`` x ``substeps``)).
        episode_time: s, after which an episode is truncated.
        waypoint_range: (nearest, farthest) m from the start at which waypoints are drawn.
        arrival_radius: m, the horizontal distance that counts as arrived.
        arrival_reward: the reward for arriving (and minus it for capsizing or diverging).
    """

    control_period: float = 0.1
    episode_time: float = 60.0
    waypoint_range: tuple[float, float] = (20.0, 60.0)
    arrival_radius: float = 5.0
    arrival_reward: float = 10.0

    def __post_init__(self) -> None:
        for key in ("control_period", "episode_time", "arrival_radius"):
            value = getattr(self, key)
            if not (math.isfinite(value) and value > 0.0):
                raise InvalidValueError(f"task.{key}", value, "must be a finite number > 0 s"
                                        if key != "arrival_radius" else "must be in (0, inf) m")
        near, far = self.waypoint_range
        if not (math.isfinite(far) and 0.0 <= near <= far):
            raise InvalidValueError("task.waypoint_range", self.waypoint_range,
                                    "must be (nearest, farthest) m with 0 <= nearest <= "
                                    "farthest < inf")
        if not math.isfinite(self.arrival_reward):
            raise InvalidValueError("task.arrival_reward", self.arrival_reward,
                                    "must be a finite number")


class _Fleet:
    """``count`` copies of one boat of a scenario in one System, and their waypoints.

    Args:
        scenario: the scenario, or a path to its file.
        boat: the boat's name or place in the scenario.
        count: how many copies.
        task: the task.
    """

    def __init__(self, scenario: Scenario | str, boat: str | int, count: int, task: Task
                 ) -> None:
        scenario = load_scenario(scenario) if not isinstance(scenario, Scenario) else scenario
        spec = _pick(scenario, boat)
        if not (isinstance(count, int) and count >= 1):
            raise InvalidValueError("num_envs", count, "must be an integer >= 1")
        self.task, self.count, self.spec = task, count, spec
        self.sea, self.environment = scenario.sea, scenario.environment
        sim = scenario.simulation
        self.dt = 1.0 / (sim.rate_hz * sim.substeps)
        self.steps = round(task.control_period / self.dt)
        if self.steps < 1 or abs(self.steps * self.dt - task.control_period) > 1e-9:
            raise InvalidValueError("task.control_period", task.control_period,
                                    f"must be a whole number of the scenario's physics steps "
                                    f"of {self.dt:g} s")
        system, self.initial = pipeline.start((spec,) * count, scenario.sea)
        self.system = system.apart()  # separate environments: none feels another's waves
        self.state = self.initial
        self.own_velocity = np.asarray(spec.velocity, dtype=float)
        self.rudder_limit = float(self.system.params[0].rudder.max_angle)
        self.waypoints = np.zeros((count, 2))
        self.start_t = np.zeros(count)
        self.distance = np.zeros(count)
        self.intake = self._intake()

    def _intake(self) -> CommandIntake:
        return CommandIntake([Commanded(p, None, len(self.spec.thrusters))
                              for p in self.system.params])

    def restart(self, rng: np.random.Generator, waypoints: np.ndarray | None) -> None:
        """Every copy back at the scenario's initial state at t = 0, with new waypoints."""
        self.state, self.intake = self.initial, self._intake()
        self.start_t[:] = 0.0
        self._aim(np.ones(self.count, bool), rng, waypoints)

    def restart_rows(self, rows: np.ndarray, rng: np.random.Generator) -> None:
        """The copies ``rows`` ((N,) bool) back at their initial pose, at the current time.

        Afloat in the sea as it is now (:func:`pipeline.afloat`), with the boat's own
        starting velocity; their thrust, radiation memory and slamming history restart.
        """
        fresh = _rows(self.state, self.initial, rows)
        floating = pipeline.afloat(self.system, fresh, self.sea).velocity + self.own_velocity
        self.state = replace(fresh, velocity=np.where(rows[:, None], floating, fresh.velocity))
        for i in np.flatnonzero(rows):
            self.intake.boats[i] = self._intake().boats[i]
        self.start_t[rows] = self.state.t
        self._aim(rows, rng, None)

    def _aim(self, rows: np.ndarray, rng: np.random.Generator, given: np.ndarray | None
             ) -> None:
        """Waypoints for ``rows``: ``given`` ((N, 2) m, world x, y) or drawn from ``rng``."""
        n = int(rows.sum())
        if given is None:
            near, far = self.task.waypoint_range
            bearing = rng.uniform(-math.pi, math.pi, n)
            reach = rng.uniform(near, far, n)
            given = (self.state.position[rows, :2]
                     + reach[:, None] * np.stack([np.cos(bearing), np.sin(bearing)], axis=1))
        self.waypoints[rows] = given
        self.distance[rows] = self._distance()[rows]

    def _distance(self) -> np.ndarray:
        return np.hypot(*(self.waypoints - self.state.position[:, :2]).T)

    def command(self, actions: np.ndarray) -> np.ndarray:
        """Take (N, 2) actions as the node takes commands; (N,) bool: which were clamped.

        Raises:
            InvalidValueError: an action that is not a finite number (NaN, infinity).
        """
        actions = _shaped(actions, (self.count, len(ACTION_FIELDS)) if self.count > 1
                          else (len(ACTION_FIELDS),)).reshape(self.count, len(ACTION_FIELDS))
        bad = ~np.isfinite(actions)
        if bad.any():
            row, col = np.argwhere(bad)[0]
            key = f"action[{row}][{col}]" if self.count > 1 else f"action[{col}]"
            raise InvalidValueError(
                f"{key} ({ACTION_FIELDS[col]})", float(actions[row, col]),
                f"must be a finite number (throttle -1..1, rudder within "
                f"+-{self.rudder_limit:g} rad; out-of-range values are clamped)")
        clamped = np.zeros(self.count, bool)
        for i, (throttle, rudder) in enumerate(actions):
            a = self.intake.thrust(i, float(throttle), self.state.t)
            b = self.intake.rudder(i, float(rudder))
            clamped[i] = a.problem is not None or b.problem is not None
        return clamped

    def advance(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """One control period; (N,) reward, terminated and truncated."""
        inputs, _ = self.intake.inputs(self.state.t, math.inf)
        stopped = np.zeros(self.count, bool)
        for _ in range(self.steps):
            before = self.state
            self.state = pipeline.step(self.system, before, inputs, self.sea, self.dt,
                                       environment=self.environment).state
            diverged = self.state.diverged()
            if diverged.any():
                self.state = self.state.held(before, diverged)
                stopped |= diverged
        return self.score(stopped)

    def score(self, stopped: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(N,) reward, terminated and truncated of the state reached by a control period.

        Args:
            stopped: (N,) bool, the copies whose state diverged during it.
        """
        roll, pitch, _ = _euler(self.state.orientation)
        lost = stopped | (np.abs(roll) > math.pi / 2) | (np.abs(pitch) > math.pi / 2)
        distance = self._distance()
        reward = self.distance - distance
        self.distance = distance
        arrived = ~lost & (distance <= self.task.arrival_radius)
        reward += self.task.arrival_reward * (arrived.astype(float) - lost.astype(float))
        truncated = self.state.t - self.start_t >= self.task.episode_time - 1e-9
        return reward, arrived | lost, truncated & ~(arrived | lost)

    def observe(self) -> np.ndarray:
        """(N, 13) observations (:data:`OBSERVATION_FIELDS`)."""
        s = self.state
        roll, pitch, heading = _euler(s.orientation)
        offset = self.waypoints - s.position[:, :2]
        c, si = np.cos(heading), np.sin(heading)
        ahead = c * offset[:, 0] + si * offset[:, 1]
        port = -si * offset[:, 0] + c * offset[:, 1]
        return np.column_stack([ahead, port, s.position[:, 2], roll, pitch, heading,
                                s.velocity, s.angular_velocity, s.throttle[:, 0]])

    def info_of(self) -> dict[str, np.ndarray]:
        """Per copy: distance to the waypoint (m), the waypoint, the episode's time (s)."""
        return {"distance": self.distance.copy(), "waypoint": self.waypoints.copy(),
                "episode_time": self.state.t - self.start_t}


def _pick(scenario: Scenario, boat: str | int):
    """The scenario's boat by name or place (InvalidValueError naming the boats there are)."""
    names = [b.name for b in scenario.boats]
    if isinstance(boat, int) and not isinstance(boat, bool) and 0 <= boat < len(names):
        return scenario.boats[boat]
    if isinstance(boat, str) and boat in names:
        return scenario.boats[names.index(boat)]
    raise InvalidValueError("boat", boat, f"must be one of {names} or a place 0.."
                                          f"{len(names) - 1} in {scenario.source}")


def _euler(q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(B,) roll, pitch, yaw (rad) of (B, 4) unit quaternions (x, y, z, w), ZYX."""
    x, y, z, w = q.T
    roll = np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = np.arcsin(np.clip(2 * (w * y - z * x), -1.0, 1.0))
    yaw = np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


def _rows(now: FleetState, initial: FleetState, rows: np.ndarray) -> FleetState:
    """``now`` with the boats ``rows`` as in ``initial`` (time kept; histories restarted)."""
    def pick(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.where(rows.reshape((-1,) + (1,) * (a.ndim - 1)), b, a)

    def restart(a: np.ndarray | None, b: np.ndarray | None, fill: np.ndarray | float):
        if a is None:
            return None
        return pick(a, b if b is not None else np.broadcast_to(fill, a.shape))

    return replace(now, position=pick(now.position, initial.position),
                   orientation=pick(now.orientation, initial.orientation),
                   velocity=pick(now.velocity, initial.velocity),
                   angular_velocity=pick(now.angular_velocity, initial.angular_velocity),
                   throttle=pick(now.throttle, initial.throttle),
                   control_weight=pick(now.control_weight, initial.control_weight),
                   memory=restart(now.memory, initial.memory, 0.0),
                   slamming=restart(now.slamming, None, np.array([0.0, now.t])),
                   swept=restart(now.swept, None, 0.0))


def _spaces(fleet: _Fleet) -> tuple[spaces.Box, spaces.Box]:
    """One copy's observation and action spaces."""
    high = np.full(len(OBSERVATION_FIELDS), np.inf)
    high[3:6] = math.pi, math.pi / 2, math.pi  # roll, pitch, heading
    high[12] = 1.0  # throttle
    observation = spaces.Box(-high, high, dtype=np.float64)
    limit = fleet.rudder_limit
    action = spaces.Box(np.array([-1.0, -limit]), np.array([1.0, limit]), dtype=np.float64)
    return observation, action


class BoatEnv(gymnasium.Env):
    """One boat of a scenario steered to a waypoint (the module's docstring: the task).

    Args:
        scenario: a :class:`~boat_dynamics.physics.scenario.Scenario`, or a scenario file.
        boat: the boat's name or place in the scenario (default the first).
        task: the task (:class:`Task`).

    Raises:
        InvalidValueError: an unknown boat, or a task the scenario's step does not divide
            (``ScenarioError``, a kind of it, for an invalid scenario file).
    """

    metadata: dict[str, Any] = {"render_modes": []}  # noqa: RUF012 (gymnasium's attribute)

    def __init__(self, scenario: Scenario | str, boat: str | int = 0, task: Task | None = None
                 ) -> None:
        self._fleet = _Fleet(scenario, boat, 1, task or Task())
        self.observation_space, self.action_space = _spaces(self._fleet)
        self.task = self._fleet.task

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[np.ndarray, dict[str, Any]]:
        """The boat at the scenario's initial state at t = 0, and a new waypoint.

        Args:
            seed: seeds the waypoints' draws (Gymnasium's ``np_random``).
            options: ``{"waypoint": (x, y)}`` m, world frame: this waypoint, not a drawn one.
        """
        super().reset(seed=seed)
        given = (options or {}).get("waypoint")
        if given is not None:
            given = _waypoints(given, 1, "options.waypoint")
        self._fleet.restart(self.np_random, given)
        return self._fleet.observe()[0], _first(self._fleet.info_of())

    def step(self, action: np.ndarray
             ) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Hold ``action`` (throttle, rudder rad) for one control period.

        Raises:
            InvalidValueError: a NaN or infinite action.
        """
        clamped = self._fleet.command(action)
        reward, terminated, truncated = self._fleet.advance()
        info = _first(self._fleet.info_of())
        info["clamped"] = bool(clamped[0])
        return (self._fleet.observe()[0], float(reward[0]), bool(terminated[0]),
                bool(truncated[0]), info)


class BoatVectorEnv(VectorEnv):
    """``num_envs`` copies of one boat stepped together (one System), each to its waypoint.

    Next-step autoreset (Gymnasium's default): the step after a copy's episode ended resets
    it and returns its first observation, reward 0, not terminated or truncated, its action
    ignored. A copy reset on its own restarts at the batch's current simulation time: the
    same pose, a later phase of the waves (in still water the same episode as from t = 0).
    ``reset`` restarts every copy at t = 0.

    Args:
        scenario: a scenario, or a scenario file.
        num_envs: how many copies.
        boat: the boat's name or place in the scenario (default the first).
        task: the task (:class:`Task`).
    """

    metadata: dict[str, Any] = {"autoreset_mode": AutoresetMode.NEXT_STEP,  # noqa: RUF012
                                "render_modes": []}

    def __init__(self, scenario: Scenario | str, num_envs: int, boat: str | int = 0,
                 task: Task | None = None) -> None:
        self._fleet = _Fleet(scenario, boat, num_envs, task or Task())
        self.num_envs = num_envs
        self.single_observation_space, self.single_action_space = _spaces(self._fleet)
        self.observation_space = gymnasium.vector.utils.batch_space(
            self.single_observation_space, num_envs)
        self.action_space = gymnasium.vector.utils.batch_space(self.single_action_space,
                                                               num_envs)
        self.task = self._fleet.task
        self._ended = np.zeros(num_envs, bool)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[np.ndarray, dict[str, Any]]:
        """Every copy at the scenario's initial state at t = 0, and new waypoints.

        Args:
            seed: seeds the waypoints' draws.
            options: ``{"waypoints": (num_envs, 2)}`` m, world x, y: these, not drawn ones.
        """
        super().reset(seed=seed)
        given = (options or {}).get("waypoints")
        if given is not None:
            given = _waypoints(given, self.num_envs, "options.waypoints")
        self._fleet.restart(self.np_random, given)
        self._ended[:] = False
        return self._fleet.observe(), self._fleet.info_of()

    def step(self, actions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                 np.ndarray, dict[str, Any]]:
        """Hold ``actions`` ((num_envs, 2): throttle, rudder rad) for one control period.

        Raises:
            InvalidValueError: a NaN or infinite action (its row and column named).
        """
        actions = _shaped(actions, (self.num_envs, len(ACTION_FIELDS))).reshape(
            self.num_envs, len(ACTION_FIELDS)).copy()
        actions[self._ended] = 0.0  # being reset: its action is not used
        clamped = self._fleet.command(actions)
        reward, terminated, truncated = self._fleet.advance()
        if self._ended.any():
            self._fleet.restart_rows(self._ended, self.np_random)
            reward[self._ended] = 0.0
            terminated[self._ended] = truncated[self._ended] = False
        self._ended = terminated | truncated
        info = self._fleet.info_of()
        info["clamped"] = clamped
        return self._fleet.observe(), reward, terminated, truncated, info


def _shaped(actions: Any, shape: tuple[int, ...]) -> np.ndarray:
    """``actions`` as a float array of ``shape``, or InvalidValueError saying what it was."""
    try:
        out = np.asarray(actions, dtype=float)
    except (TypeError, ValueError):
        out = None
    if out is None or out.size != math.prod(shape):
        raise InvalidValueError("action", actions, f"must be {shape} numbers: "
                                                   f"{', '.join(ACTION_FIELDS)}"
                                                   f"{' per copy' if len(shape) > 1 else ''}")
    return out


def _waypoints(value: Any, count: int, key: str) -> np.ndarray:
    """(count, 2) finite waypoints from an option, or InvalidValueError naming ``key``."""
    try:
        out = np.asarray(value, dtype=float).reshape(count, 2)
    except (TypeError, ValueError):
        out = None
    if out is None or not np.isfinite(out).all():
        raise InvalidValueError(key, value, f"must be {count} finite (x, y) pair"
                                            f"{'s' if count > 1 else ''} in m, world frame")
    return out


def _first(info: dict[str, np.ndarray]) -> dict[str, Any]:
    """One copy's info from a batch's."""
    return {k: (v[0] if v[0].ndim else float(v[0])) for k, v in info.items()}
