"""The dynamics node: integrates every boat of a scenario and publishes its state and wrenches.

A thin adapter: it checks commands (:mod:`boat_dynamics.physics.core.commands`), calls the core
(:func:`boat_dynamics.physics.core.pipeline.step`, all boats as one fleet) and converts
(:mod:`boat_msgs_py.convert`). The runner (:mod:`boat_dynamics.ros.runner`) calls
:meth:`DynamicsNode.advance` once per physics step.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Literal

import numpy as np
from boat_msgs.msg import Environment as EnvironmentMsg
from boat_msgs.msg import WaveField as WaveFieldMsg
from boat_msgs.srv import Reset as ResetSrv
from builtin_interfaces.msg import Time
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor, SetParametersResult
from rclpy.context import Context
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.serialization import serialize_message
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64, Float64MultiArray, String

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.body.wrench import cross
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.boat import BoatState, reference_pose
from boat_dynamics.physics.core.commands import CommandCheck, Commanded, CommandIntake
from boat_dynamics.physics.core.contact import Contact, contact, reference_points
from boat_dynamics.physics.core.diagnostics import active_remedies, fleet_reports
from boat_dynamics.physics.core.model import BoatParams
from boat_dynamics.physics.core.snapshot import SnapshotError, flatten, restore
from boat_dynamics.physics.core.system import (
    DIVERGED_RATE,
    DIVERGED_SPEED,
    FleetForces,
    FleetInputs,
    FleetState,
    System,
)
from boat_dynamics.physics.force_models.carriage import body_wrench
from boat_dynamics.physics.force_models.control import CONTROL_MODES
from boat_dynamics.physics.potential_flow.radiation import POOR_FIT
from boat_dynamics.physics.scenario import BoatSpec, Scenario
from boat_dynamics.physics.scenario.specs import (
    ADVERTISED_WRENCH_BOATS,
    SimulationSettings,
    WrenchTopics,
)
from boat_dynamics.physics.wave_making.scattered_waves import no_waves_note
from boat_dynamics.ros.collisions import CollisionEvents
from boat_dynamics.ros.outputs import FleetPublisher, StartInterrupted
from boat_dynamics.ros.reset import ResetError, ResetPlan, check_request, placed_state
from boat_msgs_py import names
from boat_msgs_py.cdr import clock_template, stamp_ns
from boat_msgs_py.convert import (
    environment_from_msg,
    lockstep_grant,
    wave_field_from_msg,
)
from boat_msgs_py.qos import (
    CLOCK_QOS,
    COMMAND_QOS,
    ENVIRONMENT_QOS,
    WAVE_FIELD_QOS,
)
from boat_msgs_py.tap import GraphWatch, Tap, TappedPublisher
from ocean_sim.physics.environment import Environment
from ocean_sim.physics.waves import InvalidSeaStateError, WaveField

__all__ = ["DynamicsNode", "LockstepRole", "SimClock", "StartInterrupted", "advertises_wrenches",
           "ready_topics"]

#: How a dynamics node takes part in a lockstep replay (see :class:`DynamicsNode`).
LockstepRole = Literal["follow", "announce", "none"]


@dataclass
class SimClock:
    """The one simulation clock shared by the nodes of a run.

    A run's time goes on forward through its episodes (``/boatsim/reset``): each episode's
    simulation time starts at 0, and its stamps where the last one's ended, a step later.

    Attributes:
        rate_hz: physics steps per simulated second.
        epoch: s, message stamp of simulation time 0 of the first episode.
        steps: physics steps taken in this episode.
        offset_ns: ns between the first episode's time 0 and this one's (integer: a stamp
            stays exactly a step after the last, whatever the wall-clock epoch).
        episodes: episodes begun since the run started (the first is 0).
    """

    rate_hz: float
    epoch: float = 0.0
    steps: int = 0
    offset_ns: int = 0
    episodes: int = 0

    @property
    def t(self) -> float:
        """Simulation time, s (steps / rate, so it does not accumulate rounding)."""
        return self.steps / self.rate_hz

    @property
    def elapsed(self) -> float:
        """Simulation time since the run started, s: every episode's (t while never reset)."""
        return self.offset_ns * 1e-9 + self.t

    @property
    def episode_epoch(self) -> float:
        """s, the stamp of this episode's simulation time 0 (as a float: the ocean's epoch)."""
        return self.epoch + self.offset_ns * 1e-9

    def stamp_ns(self) -> int:
        """Message / bag timestamp of the current simulation time, ns (integer arithmetic)."""
        return self.stamp_ns_at(self.t)

    def stamp_ns_at(self, t: float) -> int:
        """The stamp, ns, of simulation time ``t`` (s) of this episode."""
        return stamp_ns(t, self.epoch) + self.offset_ns  # as the ocean's stamps

    def stamp(self) -> tuple[int, int]:
        """(sec, nanosec) of :meth:`stamp_ns`."""
        return divmod(self.stamp_ns(), 1_000_000_000)

    def new_episode(self) -> None:
        """Simulation time back to 0, stamped one step after the current step's stamp."""
        self.offset_ns += stamp_ns((self.steps + 1) / self.rate_hz)  # the next step's
        self.steps = 0
        self.episodes += 1


@dataclass
class _Boat:
    spec: BoatSpec
    index: int  # in the fleet (and in the command intake, and the fleet publisher)
    subs: list = field(default_factory=list)


def _rate_descriptor(description: str, high: float) -> ParameterDescriptor:
    return ParameterDescriptor(
        description=description, read_only=True,
        floating_point_range=[FloatingPointRange(from_value=0.001, to_value=high)],
    )


def advertises_wrenches(setting: WrenchTopics, boats: int, recorder_process: bool) -> bool:
    """Whether a run makes every boat's ``wrench/<source>`` publishers from the start.

    Args:
        setting: ``simulation.wrench_topics``.
        boats: the scenario's boats (all of them, whichever share a process steps).
        recorder_process: a separate recorder process (``--processes --record`` in real
            time) records the topics it finds on the graph: they must be advertised.
    """
    return (setting == "advertised" or recorder_process
            or (setting == "auto" and boats <= ADVERTISED_WRENCH_BOATS))


def _boat_lines(spec: BoatSpec) -> list[tuple[str, str]]:
    """(log level, line) of what a boat starts with, for :meth:`DynamicsNode._log_boats`."""
    lines = [("info", _hydrodynamics(spec.params))]
    if spec.kind == "buoy":
        line = spec.params.anchor_line
        lines.append(("info", f"moored by a {line.length:.1f} m line to an anchor at "
                              f"{np.round(line.anchor, 2).tolist()} m; no command topics"))
    elif spec.commands is not None:
        lines.append(("info", "scripted commands; ignoring command topics"))
    hydro = spec.params.hydro
    if spec.params.made_waves in ("all", "scattered") and hydro is not None:
        note = no_waves_note(hydro)
        if note is not None:
            lines.append(("warning", note))
    memory = spec.params.radiation_memory
    if memory is not None and memory.error > POOR_FIT:
        lines.append(("warning",
                      f"its radiation memory fits the coefficients only within "
                      f"{100 * memory.error:.0f} % (sharp resonances of the hull's B(omega), "
                      "such as the gap between catamaran hulls, cannot be fitted); its "
                      "radiation may be wrong: consider hydrodynamics.radiation: resonance, "
                      "or buoyancy.pressure: froude_krylov without coefficients"))
    return lines


def _log_at(log, level: str, text: str) -> None:
    """Log ``text`` at ``level`` (``info`` or ``warning``), one call site per severity.

    rclpy refuses a call site whose severity changes between calls (ValueError: Logger
    severity cannot be changed between calls), so a loop cannot call ``getattr(log, level)``.
    """
    if level == "warning":
        log.warning(text)
    elif level == "info":
        log.info(text)
    else:
        raise ValueError(f"log level {level!r}: 'info' or 'warning'")


def ready_topics(seen: set[tuple[str, str, str]], before: set[tuple[str, str, str]]
                 ) -> set[str]:
    """The command topics a lockstep node may say it has matched (``announce_matches``).

    Args:
        seen: (client node, namespace, topic) of each command topic the graph shows a
            lockstep client publishing now.
        before: the same, at the previous look.

    Returns:
        The topics every client that publishes them was seen publishing at both looks.
    """
    fresh = {topic for *_, topic in seen - before}
    return {topic for *_, topic in seen} - fresh


class DynamicsNode(Node):
    """Steps the boats of a scenario and publishes their odometry and wrenches.

    Args:
        scenario: the scenario, its boats initialized
            (:func:`boat_dynamics.physics.core.pipeline.init_scenario`).
        clock: the shared simulation clock (advanced by this node).
        publish_clock: publish /clock at every step: the simulation's time (a run's one
            dynamics process, in --fast and in real time, where a run that falls behind the
            wall clock is followed by nodes with use_sim_time).
        tap: also hand every published message to this (recording), or None.
        name: the node name (``boat_dynamics``; one per boat with ``--processes``).
        deferred: publish nothing stamped before :meth:`start` (``--processes`` start-up,
            where the clock's epoch is known only once every process is ready).
        stopped: checked between boats while they are made: a large fleet's start-up stops
            on Ctrl-C (raises StartInterrupted) instead of making every boat first.
        lockstep: ``follow``: step only as far as a replayer grants on /boatsim/lockstep
            (``run --fast --lockstep``); ``announce``: subscribe to it without following it (a
            shard of a lockstep step barrier, whose clock owner follows the replayer): either
            way the subscription tells a replayer that the simulation is in lockstep, and it
            is made before the boats' command subscriptions, so a replayer that has discovered
            those has discovered it too (DDS announces a participant's endpoints in order);
            ``none``: no subscription (not in lockstep).
        context: the rclpy context (DDS participant) to live in; None = the default one.
        advertise_wrenches: make every boat's ``wrench/<source>`` publishers now; False = each
            once someone subscribes to it (:func:`advertises_wrenches`).
    """

    def __init__(self, scenario: Scenario, clock: SimClock, publish_clock: bool = False,
                 tap: Tap | None = None, name: str = names.DYNAMICS_NODE,
                 deferred: bool = False, stopped: Callable[[], bool] | None = None,
                 lockstep: LockstepRole = "none", context: Context | None = None,
                 advertise_wrenches: bool = True) -> None:
        super().__init__(name, context=context)
        sim = scenario.simulation
        self._sim_clock = clock
        self._declare_parameters(sim)
        self._rate = sim.rate_hz
        self._substeps = sim.substeps
        self._dt = 1.0 / (sim.rate_hz * sim.substeps)
        self._publish_rate = sim.publish_rate_hz
        self._diag_rate = sim.diagnostics_rate_hz
        self.sea: WaveField | None = None
        self._tap = tap
        self._clock_pub = (TappedPublisher(self, Clock, names.CLOCK, CLOCK_QOS, tap)
                           if publish_clock else None)
        self._field_sub = self.create_subscription(
            WaveFieldMsg, names.WAVE_FIELD, self._on_wave_field, WAVE_FIELD_QOS)
        # the scenario's current and wind from the first step; the ocean's changes as they come
        self.environment: Environment = scenario.environment
        self.world = scenario.world  # fixed obstacles: from the scenario, never changed
        self._environment_sub = self.create_subscription(
            EnvironmentMsg, names.ENVIRONMENT, self._on_environment, ENVIRONMENT_QOS)
        if any(spec.params.derive is not None for spec in scenario.boats):
            raise ValueError("scenario: its boats are not initialized (derive them and set "
                             "them afloat with boat_dynamics.physics.core.pipeline.init_scenario)")
        self._system = System.build([spec.params for spec in scenario.boats])
        self._state = FleetState.stack([spec.initial for spec in scenario.boats])
        self._initial = self._state  # where a reset (/boatsim/reset) starts the boats again
        self._seed = sim.seed  # the sensors' noise seed of a reset that gives none
        self._reset_service = None  # serve_reset
        self._new_episode: Callable[[], None] | None = None  # the run's part of a reset
        self._forces: FleetForces | None = None  # acting during the last step
        #: boat index -> the simulation time (s) its state diverged (non-finite, or faster
        #: than any boat): it is stopped (held where it was, at rest), reported, and the run
        #: exits 3
        self.stopped: dict[int, float] = {}
        self._towing: np.ndarray | None = None  # (B, 3) the carriages' of the last step
        # The surface contact of self._state, once /diagnostics or the wrenches needed it:
        # the next step starts from that state and takes it (one query and clip, not two).
        self._contact: Contact | None = None
        self._remedies: list[str] | None = None  # per boat, for /diagnostics (params only)
        self._clock_template = clock_template()
        self._command_topics: set[str] = set()  # every boat's, filled by _make_boat
        self._graph = None if advertise_wrenches else GraphWatch(self)  # wrench/*: on demand
        if not advertise_wrenches:
            self.get_logger().info(
                f"the {len(scenario.boats)} boats' wrench/<source> topics are advertised when "
                "someone subscribes to them (simulation.wrench_topics: "
                f"{sim.wrench_topics}; `advertised` lists them all from the start, with 9 DDS "
                "endpoints a boat more to make); a recording holds them all")
        self._make_lockstep(lockstep)  # before the boats' command subscriptions
        self._make_fleet(scenario, stopped)
        self._intake_start = self.intake.snapshot()  # no command yet: a reset's intake
        self._before: FleetState | None = None  # at the start of the last (sub)step: the IMUs'
        if not deferred:
            self.start()
        self.commands_received = 0
        #: topic -> messages refused on it (/ocean/wave_field, /ocean/environment, lockstep):
        #: the first is logged with its reason, all are counted on /diagnostics
        self.refused: dict[str, int] = {}
        # (command topic, "ignored" | "clamped") -> (wall time of its last warning, problems
        # not warned about since)
        self._warned: dict[tuple[str, str], tuple[float, int]] = {}
        self._wrong_types: set[tuple[str, str]] = set()  # (command topic, type) reported
        self._declare_control_modes()
        self.add_on_set_parameters_callback(self._on_set_parameters)
        self.add_post_set_parameters_callback(self._after_set_parameters)

    # ------------------------------------------------------------------ set-up

    def _declare_parameters(self, sim: SimulationSettings) -> None:
        """The node's rate, cmd_timeout and publish_tf parameters (units and ranges)."""
        self.declare_parameter("rate_hz", sim.rate_hz, _rate_descriptor(
            "Physics steps per simulated second, Hz (scenario simulation.rate_hz).", 10000.0))
        self.declare_parameter("publish_rate_hz", sim.publish_rate_hz, _rate_descriptor(
            "odom / pose / twist messages per simulated second, Hz.", sim.rate_hz))
        self.declare_parameter("diagnostics_rate_hz", sim.diagnostics_rate_hz, _rate_descriptor(
            "wrench/* messages per simulated second, Hz.", sim.rate_hz))
        self.declare_parameter("cmd_timeout", sim.cmd_timeout, ParameterDescriptor(
            description="s without a cmd_thrust message after which thrust is set to 0.",
            floating_point_range=[FloatingPointRange(from_value=0.01, to_value=3600.0)]))
        self._cmd_timeout = self.get_parameter("cmd_timeout").value  # read every step: cached
        self.declare_parameter("publish_tf", sim.publish_tf, ParameterDescriptor(
            description="Publish /tf world -> <boat>/base_link from the true pose (false: a "
                        "localization stack owns that transform)."))
        self._publish_tf = bool(self.get_parameter("publish_tf").value)

    def _make_lockstep(self, lockstep: LockstepRole) -> None:
        """The /boatsim/lockstep subscription and its ready word (see ``lockstep``)."""
        self.granted_until = 0.0  # lockstep: may step while t < this ...
        self.granted_commands = 0  # ... once this many commands have arrived
        self._lockstep_sub = None  # before the boats' command subscriptions (see lockstep)
        self._ready_pub = None  # lockstep: the word that the clients' commands will arrive
        # (client node, namespace, command topic) seen published at the last announcement
        self._client_topics: set[tuple[str, str, str]] = set()
        self._next_announcement = 0.0
        if lockstep != "none":
            self._lockstep_sub = self.create_subscription(
                Float64MultiArray, names.LOCKSTEP,
                self._on_lockstep if lockstep == "follow" else lambda msg: None, COMMAND_QOS)
            self._ready_pub = self.create_publisher(String, names.LOCKSTEP_READY, COMMAND_QOS)

    def _make_fleet(self, scenario: Scenario, stopped: Callable[[], bool] | None) -> None:
        """Every boat's publishers (one fleet publisher) and command subscriptions."""
        self.intake = CommandIntake([Commanded(spec.params, spec.commands, len(spec.thrusters))
                                     for spec in scenario.boats])
        self.outputs = FleetPublisher(self, scenario.boats, scenario.simulation, self._tap,
                                      self._graph, stopped,
                                      collisions=bool(scenario.world.obstacles)
                                      or len(scenario.boats) > 1, world=scenario.world,
                                      footprints=self._system.footprints)
        self.collisions = CollisionEvents(self, list(scenario.boats), scenario.world, self._tap,
                                          self._graph)
        self.boats = []
        for i, spec in enumerate(scenario.boats):
            if stopped is not None and stopped():
                raise StartInterrupted(f"stopped while subscribing boat {i} of "
                                       f"{len(scenario.boats)} to its commands")
            self.boats.append(self._make_boat(spec, i))
        self._log_boats(scenario.boats)

    def _declare_control_modes(self) -> None:
        """A ``[<boat>.]control_mode`` parameter per boat."""
        self._mode_params = {}
        for boat in self.boats:
            name = f"{boat.spec.name}.control_mode" if boat.spec.name else "control_mode"
            self._mode_params[name] = boat
            self.declare_parameter(name, boat.spec.params.control.mode, ParameterDescriptor(
                description=f"Control mode of boat {boat.spec.name or '(root)'}: one of "
                            f"{', '.join(CONTROL_MODES)}; switching ramps in over "
                            "control.transition s, without a jump."))

    def _make_boat(self, spec: BoatSpec, index: int) -> _Boat:
        """A boat's command subscriptions (none when its commands are scripted)."""
        boat = _Boat(spec=spec, index=index)
        if spec.commands is None:
            thrust_topic = names.boat_topic(spec.name, names.CMD_THRUST)
            rudder_topic = names.boat_topic(spec.name, names.CMD_RUDDER)
            intake, now = self.intake, lambda: self._sim_clock.t
            self._subscribe_command(boat, thrust_topic,
                                    lambda v, i=index: intake.thrust(i, v, now()))
            self._subscribe_command(boat, rudder_topic, lambda v, i=index: intake.rudder(i, v))
            if self._tap is not None:  # recorded here, at the simulation time they arrive
                self._tap.topics.update({thrust_topic, rudder_topic})
            self._command_topics.update({thrust_topic, rudder_topic})
            self._subscribe_thrusters(boat)
        return boat

    def _log_boats(self, specs: Sequence[BoatSpec]) -> None:
        """Each boat's start-up lines; beyond :data:`_LOGGED_BOATS` boats, alike ones together.

        A boat's own line (its start, its odometry topic) is left out of the grouped form:
        1000 boats' 2000 lines took 1.2 s to log and said little.
        """
        log = self.get_logger()
        groups: dict[tuple[str, str], list[str]] = {}  # (level, line) -> boat labels
        for spec in specs:
            label = spec.name or "(root namespace)"
            lines = _boat_lines(spec)
            if len(specs) <= _LOGGED_BOATS:
                pos, q = reference_pose(spec.params, spec.initial)
                vel = rotation_matrix(q) @ spec.initial.velocity
                log.info(f"{spec.kind} {label}: mass {spec.params.mass:g} kg, start at "
                         f"({pos[0]:.2f}, {pos[1]:.2f}, {pos[2]:.2f}) m, moving "
                         f"at ({vel[0]:.2f}, {vel[1]:.2f}, {vel[2]:.2f}) m/s; publishing "
                         f"{names.boat_topic(spec.name, names.ODOM)}")
                for level, line in lines:
                    _log_at(log, level, f"{spec.kind} {label}: {line}")
            for level_line in (("info", f"mass {spec.params.mass:g} kg"), *lines):
                groups.setdefault(level_line, []).append(label)
        if len(specs) <= _LOGGED_BOATS:
            return
        log.info(f"{len(specs)} boats, {specs[0].name} .. {specs[-1].name}, each publishing "
                 f"{names.boat_topic('<boat>', names.ODOM)} (more on /diagnostics)")
        for (level, line), labels in groups.items():
            who = (f"{len(labels)} boats ({labels[0]} .. {labels[-1]})" if len(labels) > 1
                   else f"boat {labels[0]}")
            _log_at(log, level, f"{who}: {line}")

    def _subscribe_thrusters(self, boat: _Boat) -> None:
        """Per named thruster: ``thrusters/<name>/thrust`` and, if steerable, ``.../angle``."""
        models = boat.spec.params.thrusters[:len(boat.spec.thrusters)]
        intake, now, i = self.intake, lambda: self._sim_clock.t, boat.index
        for j, (name, model) in enumerate(zip(boat.spec.thrusters, models, strict=True)):
            topic = names.thruster_topic(boat.spec.name, name, names.THRUSTER_THRUST)
            self._subscribe_command(boat, topic,
                                    lambda v, j=j: intake.thruster_thrust(i, j, v, now()))
            topics = {topic}
            if model.steerable:
                angle_topic = names.thruster_topic(boat.spec.name, name, names.THRUSTER_ANGLE)
                self._subscribe_command(boat, angle_topic,
                                        lambda v, j=j: intake.thruster_angle(i, j, v))
                topics.add(angle_topic)
            if self._tap is not None:
                self._tap.topics.update(topics)
            self._command_topics.update(topics)

    def _subscribe_command(self, boat: _Boat, topic: str,
                           take: Callable[[float], CommandCheck]) -> None:
        """A command topic of ``boat``: each message recorded, then handed to ``take``."""
        def on_message(msg: Float64) -> None:
            self._record_command(topic, msg)
            self._warn_about(topic, take(msg.data))

        boat.subs.append(self.create_subscription(Float64, topic, on_message, COMMAND_QOS))

    def start(self) -> None:
        """Publish what is published once, stamped with the clock (its epoch is now known)."""
        sec, nanosec = self._sim_clock.stamp()
        self.outputs.transforms.publish_static(Time(sec=sec, nanosec=nanosec))

    # ------------------------------------------------------------------ reset

    def serve_reset(self, new_episode: Callable[[], None]) -> None:
        """Serve /boatsim/reset (a one-process run: every boat and the ocean here).

        Args:
            new_episode: called once the boats and the clock are reset, before the new
                episode's first outputs: the run restarts the ocean's time there.
        """
        self._new_episode = new_episode
        self._reset_service = self.create_service(ResetSrv, names.RESET, self._on_reset)

    def _on_reset(self, request: ResetSrv.Request, response: ResetSrv.Response
                  ) -> ResetSrv.Response:
        """A reset request: checked whole, then applied; a refusal changes nothing."""
        response.episode = self._sim_clock.episodes
        try:
            plan = check_request(
                request.seed, list(request.names),
                [(p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y,
                  p.orientation.z, p.orientation.w) for p in request.poses],
                [(v.linear.x, v.linear.y, v.linear.z, v.angular.x, v.angular.y, v.angular.z)
                 for v in request.twists],
                [b.spec.name for b in self.boats])
        except ResetError as exc:
            response.success, response.message = False, f"refused: {exc}"
            self.get_logger().error(f"{names.RESET}: {response.message}")
            return response
        if self.sea is None:
            response.success, response.message = False, "refused: no sea state received yet"
            return response
        self.reset(plan)
        sec, nanosec = self._sim_clock.stamp()
        response.stamp = Time(sec=sec, nanosec=nanosec)
        response.success, response.episode = True, self._sim_clock.episodes
        response.message = (f"episode {self._sim_clock.episodes}: simulation time 0 at stamp "
                            f"{sec}.{nanosec:09d}; {len(plan.placed)} boat(s) placed, the "
                            f"others at the scenario's initial state; sensor seed "
                            f"{self._seed if plan.seed is None else plan.seed}")
        self.get_logger().info(f"{names.RESET}: {response.message}")
        return response

    def reset(self, plan: ResetPlan) -> None:
        """Begin a new episode: the boats at ``plan``'s state at t = 0, then its first outputs.

        The clock's stamps go on (:meth:`SimClock.new_episode`); the command intake, the
        sensors' noise (seeded by the plan), diverged boats and contact events start afresh.
        Parameters (control modes, cmd_timeout, publish_tf) and the lockstep counts stay.
        """
        self._state = placed_state(self._system, self._initial, plan)
        self._before = None  # no sensor readings at time 0, as at a run's start
        self._contact, self._forces, self._towing = None, None, None
        self.stopped.clear()
        counts = [(b.received, b.ignored, b.clamped) for b in self.intake.boats]
        self.intake.restore(self._intake_start)  # in place: the subscriptions hold it
        for b, (received, ignored, clamped) in zip(self.intake.boats, counts, strict=True):
            b.received, b.ignored, b.clamped = received, ignored, clamped  # the run's counts
        self.outputs.sensors.reseed(self._seed if plan.seed is None else plan.seed)
        self.collisions.restart()
        self._sim_clock.new_episode()
        if self._new_episode is not None:
            self._new_episode()
        self.publish_outputs()

    # ------------------------------------------------------------------ snapshots

    def snapshot(self) -> dict[str, np.ndarray]:
        """Everything a process resuming these boats needs, as arrays (physics.snapshot).

        The step count, the boats' state, their command intake (last commands, times,
        time-outs, counts), control modes and sensors' noise states. Not the sea, the
        environment or parameters other than the control modes: a resuming process gets
        those from the ocean and the scenario.
        """
        boats = self.boats
        out = {"format": np.asarray(SNAPSHOT_FORMAT), "steps": np.asarray(self._sim_clock.steps),
               "stamp_ns": np.asarray(self._sim_clock.stamp_ns()),
               "boats": np.array([b.spec.name for b in boats], dtype=str),
               "modes": np.array([b.spec.params.control.mode for b in boats], dtype=str),
               "commands_received": np.asarray(self.commands_received),
               **flatten(self._state, "state."), **self.outputs.sensors.snapshot(),
               **self.intake.snapshot()}
        return out

    def restore(self, arrays: dict[str, np.ndarray]) -> None:
        """Continue from a :meth:`snapshot` of the same boats (before the first step).

        Raises:
            SnapshotError: it is not a snapshot of these boats (names, format, shapes).
        """
        if int(arrays.get("format", -1)) != SNAPSHOT_FORMAT:
            raise SnapshotError(f"format: {arrays.get('format')}, expected {SNAPSHOT_FORMAT}")
        names_ = [b.spec.name for b in self.boats]
        if arrays["boats"].tolist() != names_:
            raise SnapshotError(f"boats: the snapshot's are {arrays['boats'].tolist()}, this "
                                f"process steps {names_}")
        modes = arrays["modes"].tolist()
        changed = [Parameter(f"{b.spec.name}.control_mode" if b.spec.name else "control_mode",
                             value=mode) for b, mode in zip(self.boats, modes, strict=True)
                   if mode != b.spec.params.control.mode]
        if changed:  # through the parameters, so that `param get` says it too
            self.set_parameters(changed)
        self._sim_clock.steps = int(arrays["steps"])
        self._state = restore(self._state, arrays, "state.")
        self._before = None  # the next step sets it (a resumed node publishes after it)
        self._contact, self._forces, self._towing = None, None, None
        self.commands_received = int(arrays["commands_received"])
        self.intake.restore(arrays)
        self.outputs.sensors.restore(arrays)

    def boat_positions(self) -> np.ndarray:
        """(K, 2) m, world x, y of every boat's hull reference point."""
        return self._reference_points()[:, :2]

    def state_of(self, boat: _Boat) -> BoatState:
        """One boat's current state."""
        return self._state.boat(boat.index)

    def _reference_points(self) -> np.ndarray:
        """(K, 3) m, world positions of the boats' hull reference points."""
        return reference_points(self._system, self._state)[1]

    # ------------------------------------------------------------------ callbacks

    def _on_set_parameters(self, params) -> SetParametersResult:
        """Check and apply a parameter set; an error while doing so refuses it (logged)."""
        try:
            return self._set_parameters(params)
        except Exception as exc:  # no parameter change may end the node
            self.get_logger().error(f"parameter change refused: {type(exc).__name__}: {exc}")
            return SetParametersResult(successful=False,
                                       reason=f"refused: {type(exc).__name__}: {exc}")

    def _set_parameters(self, params) -> SetParametersResult:
        for p in params:
            if p.name in self._mode_params and p.value not in CONTROL_MODES:
                return SetParametersResult(
                    successful=False,
                    reason=f"{p.name} = {p.value!r} is not allowed: one of "
                           f"{', '.join(CONTROL_MODES)}")
        for p in params:
            boat = self._mode_params.get(p.name)
            if boat is None or p.value == boat.spec.params.control.mode:
                continue
            spec = boat.spec
            control = replace(spec.params.control, mode=p.value)
            boat.spec = replace(spec, params=replace(spec.params, control=control))
            weights = self._state.control_weight.copy()
            weights[boat.index] = 0.0
            self._state = replace(self._state, control_weight=weights)
            self._system = System.build([b.spec.params for b in self.boats])
            self._remedies = None  # the mode is among them
            self.get_logger().info(f"{p.name}: now {p.value} (taking over in "
                                   f"{control.transition:g} s)")
        return SetParametersResult(successful=True)

    def _after_set_parameters(self, params) -> None:
        """Keep the cached copies of parameters read every step (called once they are set)."""
        for p in params:
            if p.name == "cmd_timeout":
                self._cmd_timeout = float(p.value)
            elif p.name == "publish_tf":
                self._publish_tf = bool(p.value)

    def _refuse(self, topic: str, reason: object, keeping: str) -> None:
        """Count a refused message; log the first one of ``topic`` with its reason."""
        count = self.refused[topic] = self.refused.get(topic, 0) + 1
        if count == 1:
            self.get_logger().error(
                f"ignoring invalid {topic}: {reason}; keeping {keeping} (later refusals on "
                f"this topic are counted on /diagnostics as messages_refused, not logged)")

    def _on_wave_field(self, msg: WaveFieldMsg) -> None:
        try:
            sea = wave_field_from_msg(msg)
        except InvalidSeaStateError as exc:
            self._refuse(names.WAVE_FIELD, exc, "the previous sea state")
            return
        first = self.sea is None
        self.sea = sea
        self.get_logger().info(
            f"{'received' if first else 'updated'} sea state: {len(sea.components)} components")

    def _on_environment(self, msg: EnvironmentMsg) -> None:
        try:
            environment = environment_from_msg(msg)
        except ValueError as exc:  # InvalidEnvironmentError, or a seed numpy refuses
            self._refuse(names.ENVIRONMENT, exc, "the previous current and wind")
            return
        self.environment = environment

    def _on_lockstep(self, msg: Float64MultiArray) -> None:
        """A replayer's grant [T s, n commands] (:func:`.convert.lockstep_grant`), or refused."""
        try:
            until, commands = lockstep_grant(msg.data)
        except ValueError as exc:
            self._refuse(names.LOCKSTEP, exc, "the grant so far")
            return
        self.granted_until = max(self.granted_until, until)
        self.granted_commands = max(self.granted_commands, commands)

    def announce_matches(self) -> None:
        """Lockstep, while holding: say which of the clients' topics the boats have matched.

        On ``names.LOCKSTEP_READY``, at most every 0.1 s (wall). The clients: every node that
        publishes ``names.LOCKSTEP`` (whatever its name: ``boatsim replay``, a test harness,
        a learning loop), and ``boatsim replay``'s node by its name. A command topic counts
        once this node's graph has shown each client that publishes it doing so at two
        announcements in a row: DDS matches a subscription to a publisher as it learns of
        the publisher, which the graph shows, and the second look leaves 0.1 s for that. (A
        publisher that has matched a subscription may still be unknown to the subscription,
        and what it publishes meanwhile is lost; the replayer saw its subscribers and sent at
        once, and a lockstep simulation then waited for a lost command for ever.)
        """
        now = time.monotonic()
        if self._ready_pub is None or now < self._next_announcement:
            return
        self._next_announcement = now + 0.1
        seen = set()
        for client, namespace in self._lockstep_clients():
            try:
                published = self.get_publisher_names_and_types_by_node(client, namespace)
            except RuntimeError:  # NodeNameNonExistentError: gone from the graph meanwhile
                continue
            seen |= {(client, namespace, topic) for topic, _ in published
                     if topic in self._command_topics}
        matched = ready_topics(seen, self._client_topics)
        self._client_topics = seen
        if matched:
            self._ready_pub.publish(String(data=" ".join([self.get_name(), *sorted(matched)])))

    def _lockstep_clients(self) -> set[tuple[str, str]]:
        """(name, namespace) of the nodes publishing grants, and ``boatsim replay``'s node."""
        clients = {(i.node_name, i.node_namespace)
                   for i in self.get_publishers_info_by_topic(names.LOCKSTEP)
                   if i.node_name not in ("", names.UNKNOWN_NODE)}  # not discovered yet
        return clients | {(names.REPLAY_NODE, "/")}  # looked up even before its grants

    def repeat_clock(self) -> None:
        """Republish /clock at the current time (lockstep hold: late joiners see it), unrecorded."""
        if self._clock_pub is not None:
            sec, nanosec = self._sim_clock.stamp()
            stamp = Time(sec=sec, nanosec=nanosec)
            self._clock_pub.publish_untapped(Clock(clock=stamp))

    def may_step(self) -> bool:
        """Lockstep: the replayer has granted the next step and its commands have arrived."""
        return (self._sim_clock.elapsed < self.granted_until - 1e-9
                and self.commands_received >= self.granted_commands)

    def _record_command(self, topic: str, msg: Float64) -> None:
        self.commands_received += 1
        if self._tap is not None:
            self._tap.sink(topic, "std_msgs/msg/Float64", serialize_message(msg))

    def _warn_about(self, topic: str, checked: CommandCheck) -> None:
        """Warn about a command clamped or ignored by the intake (:class:`CommandIntake`).

        At most every 2 s (wall) per topic and kind, saying how many it did not show; every
        one is counted on /diagnostics.
        """
        if not checked.problem:
            return
        kind = "ignored" if checked.value is None else "clamped"
        now = time.monotonic()
        last, unshown = self._warned.get((topic, kind), (-math.inf, 0))
        if now - last >= 2.0:
            more = (f" ({unshown} more {kind} since the last warning; counts on "
                    f"{names.DIAGNOSTICS})" if unshown else "")
            self.get_logger().warning(f"{topic}: {checked.problem}{more}")
            self._warned[(topic, kind)] = (now, 0)
        else:
            self._warned[(topic, kind)] = (last, unshown + 1)

    def check_command_types(self) -> None:
        """Report once per topic and type a publisher of another type on a command topic.

        Its messages never arrive (command topics take std_msgs/Float64). Called by the run
        loop every few seconds: one graph query for the whole fleet.
        """
        for topic, types in self.get_topic_names_and_types():
            if topic not in self._command_topics:
                continue
            for kind in types:
                if kind != _COMMAND_TYPE and (topic, kind) not in self._wrong_types:
                    self._wrong_types.add((topic, kind))
                    self.get_logger().error(
                        f"{topic}: a publisher of {kind} is ignored: command topics take "
                        f"{_COMMAND_TYPE} (the value in its data field)")

    # ------------------------------------------------------------------ stepping

    def _fleet_inputs(self) -> FleetInputs:
        """Every boat's inputs for the next step; a throttle that timed out is warned about."""
        inputs, fell = self.intake.inputs(self._sim_clock.t, self._cmd_timeout)
        for f in fell:
            spec = self.boats[f.boat].spec
            topic = names.boat_topic(spec.name, names.CMD_THRUST)
            if f.thruster is not None:
                own = names.thruster_topic(spec.name, spec.thrusters[f.thruster],
                                           names.THRUSTER_THRUST)
                topic = f"{own} (or {topic})"
            self.get_logger().warning(f"{topic}: no command for {self._cmd_timeout:g} s; "
                                      "thrust set to 0")
        return inputs

    @staticmethod
    def _due(k: int, rate: float, out_rate: float) -> bool:
        """True on the steps where a stream at ``out_rate`` Hz publishes (step 0 included)."""
        return k == 0 or math.floor(k * out_rate / rate) > math.floor((k - 1) * out_rate / rate)

    def _contact_if_known(self) -> Contact | None:
        """The kept surface contact, if it is the current state's (else None)."""
        c = self._contact
        return c if c is not None and c.belongs_to(self._system, self._state, self.sea) else None

    def _current_contact(self) -> Contact:
        """The surface contact of the current state, computed once and kept for the step."""
        self._contact = self._contact_if_known() or contact(self._system, self._state,
                                                            self.sea)
        return self._contact

    def advance(self) -> None:
        """Take one physics step for every boat, then publish what is due."""
        self.step()
        self.publish_outputs()

    def step(self) -> None:
        """Take one physics step for every boat (publishing nothing)."""
        if self.sea is None:
            raise RuntimeError("no sea state yet: /ocean/wave_field has not been received")
        inputs = self._fleet_inputs()
        for _ in range(self._substeps):
            done = pipeline.step(self._system, self._state, inputs, self.sea, self._dt,
                                 self._contact_if_known(), self.environment, self.world)
            self.collisions.observe(self._system, self._state, done)
            self._before = self._state
            self._state, self._forces, self._contact = done.state, done.forces, None
            self._towing = done.towing
            self._watch(done.state)

    def _watch(self, after: FleetState) -> None:
        """Stop the boats whose state diverged: held where they were, at rest."""
        bad = after.diverged()
        for i in np.flatnonzero(bad):
            if int(i) not in self.stopped:
                self.stopped[int(i)] = float(after.t)
                self.get_logger().error(
                    f"boat {self.boats[i].spec.name or '(root)'}: its state diverged at "
                    f"t = {after.t:.3f} s (non-finite, or faster than {DIVERGED_SPEED:g} m/s or "
                    f"{DIVERGED_RATE:g} rad/s: check its mass, inertia, damping and "
                    "coefficients); it is stopped where it was and the run will exit 3")
        if self.stopped:
            held = np.zeros(len(self.boats), dtype=bool)
            held[list(self.stopped)] = True
            self._state = after.held(self._before, held)
        self._sim_clock.steps += 1

    def publish_outputs(self) -> None:
        """Publish /clock, odometry, sensors, wrenches and diagnostics due at the current step."""
        k = self._sim_clock.steps
        sec, nanosec = self._sim_clock.stamp()
        if self._clock_pub is not None:
            self._clock_pub.publish(self._clock_template.pack(sec, nanosec))
        if self._due(k, self._rate, self._publish_rate):
            self.outputs.states(sec, nanosec, self._state_values(), time.monotonic(),
                                self._publish_tf)
        if self._before is not None:
            self.outputs.sensor_readings(lambda rate: self._due(k, self._rate, rate), sec,
                                         nanosec, self._system.center_of_mass, self._before,
                                         self._state, self.sea.depth, self.sea)
        if self._due(k, self._rate, self._diag_rate):
            forces = self._forces
            if forces is None:  # before the first step: the forces at the initial state
                forces, _ = pipeline.forces(self._system, self._state, self._fleet_inputs(),
                                            self._current_contact(), self.environment,
                                            self.world)
            self.outputs.wrenches(sec, nanosec, forces, time.monotonic(),
                                  self._carriage if self._towing is not None else None)
            self.outputs.diagnostics(sec, nanosec, self._statuses())
        self.collisions.publish(self._sim_clock.stamp_ns_at)

    def _state_values(self) -> np.ndarray:
        """(B, 13): each boat's reference point, orientation, its velocity and angular velocity.

        The reference point's velocity v_com + w x (r_ref - r_com), body frame.
        """
        state = self._state
        return np.concatenate([
            self._reference_points(), state.orientation,
            state.velocity - cross(state.angular_velocity, self._system.center_of_mass),
            state.angular_velocity], axis=1)

    def _carriage(self, i: int) -> np.ndarray:
        """(6,) boat ``i``'s carriage force and moment over the last step, body frame."""
        return body_wrench(self._system.params[i].carriage,
                           rotation_matrix(self._state.orientation[i]), self._towing[i])

    def _statuses(self) -> list:
        """/diagnostics: one status per boat (hydrostatics, mode, remedies, command counts)."""
        if self._remedies is None:
            self._remedies = ["; ".join(active_remedies(b.spec.params, self._substeps))
                              for b in self.boats]
        reports = fleet_reports(self._system, self._state, self._current_contact(),
                                self._substeps, remedies=self._remedies)
        refused = ("messages_refused", str(sum(self.refused.values())))  # the node's
        return [
            (f"boatsim: {boat.spec.name or 'boat'}",
             *((2, f"stopped: its state diverged at t = {self.stopped[boat.index]:.3f} s")
               if boat.index in self.stopped else (r.level, r.message)),
             (*r.values, ("commands_received", str(intake.received)), refused,
              ("commands_ignored_not_finite", str(intake.ignored)),
              ("commands_clamped", str(intake.clamped))))
            for boat, intake, r in zip(self.boats, self.intake.boats, reports, strict=True)]


#: The layout of :meth:`DynamicsNode.snapshot` (a resuming process refuses another).
SNAPSHOT_FORMAT = 1
#: The type of every command topic.
_COMMAND_TYPE = "std_msgs/msg/Float64"

#: A radiation memory fitting its coefficients worse than this (relative) is warned about.
#: Up to this many boats, a node logs each boat's start-up lines; beyond, alike ones together.
_LOGGED_BOATS = 20


def _hydrodynamics(params: BoatParams) -> str:
    """One line on the boat's wave radiation and diffraction, for the start-up log."""
    memory = params.radiation_memory
    if params.hydro is None:
        return ("no potential-flow coefficients (hydrodynamics.coefficients): added mass and "
                "damping as the scenario gives them, no diffraction")
    source = params.hydro.source
    if source.startswith("estimate"):
        source = (f"ESTIMATED ({source}; `boatsim hydro SCENARIO` solves the hull's own, "
                  f"with the bem extra)")
    if memory is not None:
        return (f"potential-flow coefficients {source}: Cummins radiation (A_inf 6 x 6, memory "
                f"of {memory.poles.shape[0]} modes fitting B and A within "
                f"{100 * memory.error:.1f} %), diffraction")
    return (f"potential-flow coefficients {source}: added mass and radiation damping at the "
            f"natural frequencies (radiation: resonance), diffraction")
