"""A Gymnasium environment over a running boatsim, through ROS lockstep.

The waypoint task of :mod:`boat_dynamics.gym`, stepped by a simulation in another process.

:class:`RosBoatEnv` has :class:`~boat_dynamics.gym.BoatEnv`'s spaces, task and rewards, so a
policy trained on one runs on the other; the boat is stepped by ``boatsim run SCENARIO
--fast --lockstep`` (one process, the same scenario file), not in this process. Its node
follows docs/DESIGN.md, "Lockstep: the client's recipe" (any node name; default
``boatsim_gym``):

- ``reset(seed=s)`` calls ``/boatsim/reset`` (boat_msgs/srv/Reset) with seed ``s`` (the
  sensors' noise; -1, the scenario's, without one) and waits for the boat's ``odom`` stamped
  at the new episode's time 0; the waypoint is drawn from ``s`` as BoatEnv draws it;
- ``step(action)`` publishes ``cmd_thrust`` and ``cmd_rudder`` (the action, clamped as the
  node clamps it), grants one control period on ``/boatsim/lockstep`` (repeated every 0.1 s)
  and waits for ``odom`` stamped at its end.

The observation is BoatEnv's, from odometry: the centre of mass's position and velocity from
the reference point's (odom's pose and twist, and the boat's centre of mass from the
scenario), so it equals BoatEnv's to rounding (about 1e-15 m). The thrust fraction is not in
odometry: the environment follows it from its own commands through the core's thruster lag
(:func:`~boat_dynamics.physics.force_models.propulsion.lagged_throttle`, the step's own
arithmetic), exact while it is the boat's only commander. A boat whose state diverges is
stopped by the node (its log says so); here it is then an episode that goes on at rest.
One client at a time: a reset or grant by another client moves the run away from this
environment's episode (its next step then times out); call :meth:`RosBoatEnv.reset`.

This module needs rclpy and boatsim's messages (``make setup``); :mod:`boat_dynamics.gym`
does not.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Any

import gymnasium
import numpy as np
import rclpy
from boat_msgs.srv import Reset
from nav_msgs.msg import Odometry
from rclpy.executors import SingleThreadedExecutor
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64, Float64MultiArray, String

from boat_dynamics.gym import (
    ACTION_FIELDS,
    OBSERVATION_FIELDS,
    InvalidValueError,
    Task,
    _first,
    _Fleet,
    _spaces,
    _waypoints,
)
from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.body.wrench import cross
from boat_dynamics.physics.force_models.propulsion import lagged_throttle
from boat_dynamics.physics.scenario import Scenario, load_scenario
from boat_dynamics.tools.replay import follows_lockstep, parse_ready
from boat_msgs_py import names
from boat_msgs_py.qos import CLOCK_QOS, COMMAND_QOS, STATE_QOS

__all__ = ["ACTION_FIELDS", "OBSERVATION_FIELDS", "RosBoatEnv", "RosEnvError", "Task"]

#: s (wall) a reset waits for the new episode's odometry before asking again (a first
#: message can be lost while DDS matches the publisher: Fast-DDS#2641).
_ODOM_WAIT = 2.0


class RosEnvError(RuntimeError):
    """The simulation did not answer (time-out) or refused a reset (its message)."""


class RosBoatEnv(gymnasium.Env):
    """One boat of a running ``boatsim run --fast --lockstep`` steered to a waypoint.

    Args:
        scenario: the scenario the run was started with (a Scenario, or its file).
        boat: the boat's name or place in the scenario (default the first).
        task: the task (:class:`~boat_dynamics.gym.Task`); its control period must be a
            whole number of odometry periods (``simulation.publish_rate_hz``) and shorter
            than ``simulation.cmd_timeout``.
        node_name: this client's node name.
        timeout: s (wall) to wait for the simulation at each call before RosEnvError.

    Raises:
        InvalidValueError: an unknown boat, or a task the scenario's rates do not divide.
    """

    metadata: dict[str, Any] = {"render_modes": []}  # noqa: RUF012 (gymnasium's attribute)

    def __init__(self, scenario: Scenario | str, boat: str | int = 0, task: Task | None = None,
                 *, node_name: str = "boatsim_gym", timeout: float = 60.0) -> None:
        scenario = load_scenario(scenario) if not isinstance(scenario, Scenario) else scenario
        self._fleet = _Fleet(scenario, boat, 1, task or Task())
        self.observation_space, self.action_space = _spaces(self._fleet)
        self.task, self.timeout = self._fleet.task, timeout
        _check_rates(self.task, scenario)
        self._period_ns = round(self.task.control_period * 1e9)
        spec = self._fleet.spec
        self._context = rclpy.Context()
        rclpy.init(context=self._context)
        self._node = rclpy.create_node(node_name, context=self._context)
        self._executor = SingleThreadedExecutor(context=self._context)
        self._executor.add_node(self._node)
        node = self._node
        # the grant publisher first: it makes this node a lockstep client (the recipe, 1.)
        self._grant = node.create_publisher(Float64MultiArray, names.LOCKSTEP, COMMAND_QOS)
        self._topics = (names.boat_topic(spec.name, names.CMD_THRUST),
                        names.boat_topic(spec.name, names.CMD_RUDDER))
        self._commands = [node.create_publisher(Float64, t, COMMAND_QOS) for t in self._topics]
        self._clock: int | None = None  # ns, the last /clock
        self._ready: dict[str, set[str]] = {}
        self._odom: tuple[int, Odometry] | None = None  # (stamp ns, message): the last
        node.create_subscription(Clock, names.CLOCK, self._on_clock, CLOCK_QOS)
        node.create_subscription(String, names.LOCKSTEP_READY, self._on_ready, COMMAND_QOS)
        node.create_subscription(Odometry, names.boat_topic(spec.name, names.ODOM),
                                 self._on_odom, STATE_QOS)
        self._reset = node.create_client(Reset, names.RESET)
        self._connected = False
        self._sent = 0  # command messages published, the grant's n
        self._start_ns = self._now_ns = 0  # ns: the episode's time 0, the state's stamp

    # ------------------------------------------------------------------ ROS

    def _on_clock(self, msg: Clock) -> None:
        self._clock = _ns(msg.clock)

    def _on_ready(self, msg: String) -> None:
        node, topics = parse_ready(msg.data)
        self._ready[node] = topics

    def _on_odom(self, msg: Odometry) -> None:
        self._odom = (_ns(msg.header.stamp), msg)

    def _spin_until(self, done, what: str, timeout: float | None = None) -> None:
        timeout = self.timeout if timeout is None else timeout
        end = time.monotonic() + timeout
        while not done():
            if time.monotonic() > end:
                raise RosEnvError(f"timed out after {timeout:g} s waiting for {what} "
                                  f"(is `boatsim run SCENARIO --fast --lockstep` running?)")
            self._executor.spin_once(timeout_sec=0.02)

    def _announced(self) -> bool:
        """Every dynamics node subscribing to the command topics said it matched them."""
        for topic in self._topics:
            subs = {i.node_name for i in self._node.get_subscriptions_info_by_topic(topic)}
            if not subs or subs & {"", names.UNKNOWN_NODE}:
                return False
            if any(topic not in self._ready.get(n, set()) for n in subs if follows_lockstep(n)):
                return False
        return True

    def _connect(self) -> None:
        """The recipe's steps 2-4: subscribers and a follower, /clock, the ready word."""
        followers = lambda: any(follows_lockstep(i.node_name) for i in  # noqa: E731
                                self._node.get_subscriptions_info_by_topic(names.LOCKSTEP))
        self._spin_until(lambda: all(p.get_subscription_count() for p in self._commands)
                         and followers(), "the simulation's command and lockstep subscriptions")
        self._spin_until(lambda: self._clock is not None, names.CLOCK)
        self._spin_until(self._announced, names.LOCKSTEP_READY)
        if not self._reset.wait_for_service(timeout_sec=self.timeout):
            raise RosEnvError(f"{names.RESET}: no server within {self.timeout:g} s")
        self._connected = True

    def _call_reset(self, seed: int) -> Reset.Response:
        future = self._reset.call_async(Reset.Request(seed=seed))
        self._spin_until(future.done, f"{names.RESET}'s answer")
        response = future.result()
        if not response.success:
            raise RosEnvError(f"{names.RESET}: {response.message}")
        return response

    def _odom_at(self, stamp: int, timeout: float | None = None) -> Odometry:
        self._spin_until(lambda: self._odom is not None and self._odom[0] >= stamp,
                         f"odom stamped {stamp * 1e-9:.3f} s", timeout)
        if self._odom[0] != stamp:
            raise RosEnvError(f"odom stamped {self._odom[0] * 1e-9:.9f} s, expected "
                              f"{stamp * 1e-9:.9f} s (is the run --lockstep?)")
        return self._odom[1]

    # ------------------------------------------------------------------ the state

    def _take(self, msg: Odometry, throttle: np.ndarray) -> None:
        """The fleet's state from odometry (reference point -> centre of mass) and throttle."""
        pose, twist = msg.pose.pose, msg.twist.twist
        q = np.array([pose.orientation.x, pose.orientation.y, pose.orientation.z,
                      pose.orientation.w])
        w = np.array([twist.angular.x, twist.angular.y, twist.angular.z])
        c = self._fleet.system.center_of_mass[0]
        position = np.array([pose.position.x, pose.position.y, pose.position.z])
        velocity = np.array([twist.linear.x, twist.linear.y, twist.linear.z])
        self._now_ns = _ns(msg.header.stamp)
        fleet = self._fleet
        fleet.state = replace(fleet.state, t=(self._now_ns - self._start_ns) * 1e-9,
                              position=(position + rotation_matrix(q) @ c)[None],
                              orientation=q[None], velocity=(velocity + cross(w, c))[None],
                              angular_velocity=w[None], throttle=throttle)

    def _lagged(self) -> np.ndarray:
        """(1, T) the thrust fractions after a control period of the commands held."""
        fleet, state = self._fleet, self._fleet.state
        inputs, _ = fleet.intake.inputs(state.t, math.inf)
        throttle = state.throttle.copy()
        for _ in range(fleet.steps):  # as pipeline.step, at every physics step
            for g in fleet.system.groups:
                for j, model in enumerate(g.propulsion):
                    throttle[g.index, j] = lagged_throttle(model, throttle[g.index, j],
                                                           inputs.throttle_of(j)[g.index],
                                                           fleet.dt)
        return throttle

    # ------------------------------------------------------------------ gymnasium

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[np.ndarray, dict[str, Any]]:
        """A new episode of the run (``/boatsim/reset``) and a new waypoint.

        Args:
            seed: seeds the waypoint's draw (as BoatEnv) and the run's sensor noise; None:
                the scenario's ``simulation.seed`` for the sensors.
            options: ``{"waypoint": (x, y)}`` m, world frame: this waypoint, not a drawn one.

        Raises:
            RosEnvError: no simulation, or the reset refused.
        """
        super().reset(seed=seed)
        given = (options or {}).get("waypoint")
        if given is not None:
            given = _waypoints(given, 1, "options.waypoint")
        if not self._connected:
            self._connect()
        for attempt in range(3):  # a first odom can be lost while DDS matches (module docs)
            response = self._call_reset(-1 if seed is None else int(seed))
            self._start_ns = _ns(response.stamp)
            try:
                msg = self._odom_at(self._start_ns, _ODOM_WAIT if attempt < 2 else None)
                break
            except RosEnvError:
                if attempt == 2:
                    raise
        self._fleet.restart(self.np_random, given)  # the intake and the waypoint, as BoatEnv
        self._take(msg, self._fleet.initial.throttle)
        self._fleet.distance = self._fleet._distance()
        return self._fleet.observe()[0], _first(self._fleet.info_of())

    def step(self, action: np.ndarray
             ) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Hold ``action`` (throttle, rudder rad) for one control period of the run.

        Raises:
            InvalidValueError: a NaN or infinite action.
            RosEnvError: the simulation did not answer in ``timeout``.
        """
        fleet = self._fleet
        clamped = fleet.command(action)
        taken = fleet.intake.boats[0]
        for pub, value in zip(self._commands, (taken.throttle, taken.rudder), strict=True):
            pub.publish(Float64(data=float(value)))
            self._sent += 1
        target = self._now_ns + self._period_ns
        throttle = self._lagged()
        grant = Float64MultiArray(data=[target * 1e-9, float(self._sent)])
        end = time.monotonic() + self.timeout
        while True:  # the recipe's 5.: the grant again every 0.1 s until the run is there
            self._grant.publish(grant)
            try:
                msg = self._odom_at(target, 0.1)
                break
            except RosEnvError:
                if time.monotonic() > end:
                    raise
        self._take(msg, throttle)
        reward, terminated, truncated = fleet.score(np.zeros(1, bool))
        info = _first(fleet.info_of())
        info["clamped"] = bool(clamped[0])
        return (fleet.observe()[0], float(reward[0]), bool(terminated[0]), bool(truncated[0]),
                info)

    def close(self) -> None:
        """Leave the ROS graph (the run goes on: stop it with SIGINT)."""
        if self._context.ok():
            self._executor.shutdown(timeout_sec=1.0)
            self._node.destroy_node()
            rclpy.try_shutdown(context=self._context)


def _ns(stamp) -> int:
    """A builtin_interfaces/Time in integer ns."""
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def _check_rates(task: Task, scenario: Scenario) -> None:
    """The control period: whole odometry periods, shorter than the command time-out."""
    sim = scenario.simulation
    periods = task.control_period * sim.publish_rate_hz
    if abs(periods - round(periods)) > 1e-9:
        raise InvalidValueError("task.control_period", task.control_period,
                                f"must be a whole number of odometry periods of "
                                f"{1.0 / sim.publish_rate_hz:g} s (simulation.publish_rate_hz "
                                "of the scenario)")
    if task.control_period >= sim.cmd_timeout:
        raise InvalidValueError("task.control_period", task.control_period,
                                f"must be shorter than simulation.cmd_timeout "
                                f"({sim.cmd_timeout:g} s): the thrust would fall to 0 within "
                                "a period")
