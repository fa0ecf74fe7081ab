"""`boatsim run`: the ocean node and the dynamics node in one process, on one clock.

The loop takes one physics step, publishes what is due, then serves ROS callbacks (commands,
parameter changes) until the next step is due: paced to the wall clock in real time, or with
no waiting at all in ``--fast`` mode. The simulation publishes /clock either way.

/ocean/sample_surface is served by a surface server process beside this one
(:mod:`ocean_sim.ros.surface_server`): a large request served here held the loop for up to
0.64 s (100,000 points), 1.8 s (1,000,000, refused).
"""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, replace
from typing import TextIO

import rclpy
from boat_msgs.srv import Reset as ResetSrv
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.signals import SignalHandlerOptions

from boat_dynamics.physics.body.rigid_body import quat_to_euler
from boat_dynamics.physics.core.boat import reference_pose
from boat_dynamics.physics.core.pipeline import init_scenario
from boat_dynamics.physics.scenario import Scenario
from boat_dynamics.ros.barrier import StepConductor, StepMember, shard_slice
from boat_dynamics.ros.node import (
    DynamicsNode,
    LockstepRole,
    SimClock,
    StartInterrupted,
    advertises_wrenches,
)
from boat_dynamics.ros.participants import PROFILE, Participants, use_profile
from boat_dynamics.ros.world import WorldPublisher
from boat_dynamics.tools.recording import BagWriter, TopicRecorder, declares_only, spin_pending
from boat_msgs_py import names
from boat_msgs_py.process import (
    SharedTime,
    start_child,
    stop_on_signals,
    stop_processes,
    watch_stdin,
)
from boat_msgs_py.qos import RECORD_QOS
from boat_msgs_py.tap import Tap
from ocean_sim.ros.node import OceanNode

__all__ = ["CHECKPOINT_PERIOD", "EXIT_STOPPED", "Lag", "ProcessRole", "RunOptions", "run"]

#: The exit status of a run that went to its end with a boat stopped because its state diverged
#: (the node's watchdog): not a crash, so a supervisor does not restart it.
EXIT_STOPPED = 3

#: Beyond this many publishers and subscriptions, a stopping process does not destroy them
#: one by one (2,408 took 2.8 s, 14,008 took 67 s: quadratic, measured).
_DESTROY_LIMIT = 2000
#: Beyond this many boats, say when the process's DDS start-up grows as the fleet's square.
_QUADRATIC_START = 100
#: How long a --processes child waits for the recorder to subscribe to it, s (wall).
_RECORDER_TIMEOUT = 60.0
#: How long a --processes child at its end waits for the recorder to acknowledge its last
#: messages, s (wall).
_ACK_TIMEOUT = 5.0
#: How long to wait for the dynamics node to receive the first wave field, s (wall).
_FIELD_TIMEOUT = 10.0
#: Wall-clock period of the live status line, s.
_STATUS_PERIOD = 0.25
#: Wall-clock period of the status line when stderr is not a terminal, s.
_LOG_STATUS_PERIOD = 5.0
#: Wall-clock period of the check for command publishers of a wrong type, s.
_TYPE_CHECK_PERIOD = 2.0
#: Wall-clock period of topic discovery for the recorder, s.
_DISCOVERY_PERIOD = 1.0
#: In --fast mode (and in real time while behind the wall clock), serve ROS callbacks
#: (commands, service calls) at most this often, s (wall).
#: rclpy rebuilds its wait set on every spin (about 5 ms with 10 boats' entities, measured),
#: so spinning after every physics step cost as much as the physics.
_FAST_SPIN_PERIOD = 0.05
#: ... and spend at most this fraction of the wall time on it: the wait set grows with the
#: boats (2 command subscriptions each), and with 100 boats a spin took 4 ms per 10 ms step,
#: more than the physics. With more boats, callbacks are then served less often than every
#: _FAST_SPIN_PERIOD (0.2 s of wall time with 100 boats).
_FAST_SPIN_SHARE = 0.1
#: A shard with a checkpoint saves its boats this often, s of simulation time.
CHECKPOINT_PERIOD = 1.0


@dataclass(frozen=True)
class ProcessRole:
    """Which process of a run this is (one process: all of it).

    What the parent of ``--processes`` / ``--shards`` tells its children (``boatsim _node``),
    or ``--only`` a process started alone.

    Attributes:
        role: ``all`` (ocean and every boat), ``ocean`` or ``shard`` (one process of
            ``--processes`` or ``--shards``).
        shard: a ``shard`` role's (K, N): its boats are share K of N
            (:func:`boat_dynamics.ros.barrier.shard_slice`).
        shards: an ``ocean`` role with ``fast``: own the clock of this many shards (the step
            barrier, :mod:`boat_dynamics.ros.barrier`); 0 = none (real time).
        standalone: started alone (``--only``): wait for the ocean and the other processes
            as long as it takes, saying so.
        epoch: s (wall clock) of simulation time 0, shared by the processes of a run; None =
            now (or 0 with ``fast``).
        ready_fd: a ``--processes`` child's start-up handshake: write "ready" to this file
            descriptor once the nodes exist (and, with ``await_recorder``, the recorder
            subscribes to every publisher), then take the epoch from the parent's
            "go EPOCH" line on stdin; nothing stamped is published before. None = no
            handshake.
        supervised: a ``--processes`` child: end when stdin ends (the parent died).
        await_recorder: with ``ready_fd``: wait for the recorder before saying ready.
        checkpoint: a shard: save a snapshot of its boats here every
            :data:`CHECKPOINT_PERIOD` s of simulation time (and at its start), its bag
            flushed first; None = none.
        resume: a shard started in a dead one's place: continue from this snapshot (its
            step count, its boats' state and command intake) instead of the scenario's start.
    """

    role: str = "all"
    shard: tuple[int, int] | None = None
    shards: int = 0
    standalone: bool = False
    epoch: float | None = None
    ready_fd: int | None = None
    supervised: bool = False
    await_recorder: bool = False
    checkpoint: str | None = None
    resume: str | None = None


@dataclass(frozen=True)
class RunOptions:
    """How the user asked to run a scenario (``boatsim run``'s options), and which process.

    Attributes:
        fast: run as fast as possible (else paced to real time); /clock either way.
        duration: s of simulated time, None = until stopped.
        record: directory of a rosbag2 (MCAP) bag to write, or None.
        lockstep: with ``fast``: step only as far as a replayer (``boatsim replay``) grants.
        exclude_topics: topics the bag leaves out.
        process: this process's part in the run (one process: the default, all of it).
    """

    fast: bool = False
    duration: float | None = None
    record: str | None = None
    lockstep: bool = False
    exclude_topics: tuple[str, ...] = ()
    process: ProcessRole = ProcessRole()


class Lag:
    """How far a real-time run is behind the wall clock, and when to say so.

    A run behind the wall clock steps on as fast as it can to catch up (its stamps stay those
    of the simulation clock); the status line shows the lag, and the log says once when it
    passes :data:`BEHIND` and once when it is back within :data:`CAUGHT_UP`.
    """

    #: s behind the wall clock at which the log says so.
    BEHIND = 1.0
    #: s: back in step.
    CAUGHT_UP = 0.1

    def __init__(self) -> None:
        self.behind = False

    def check(self, lag: float, rtf: float) -> tuple[str, str | None, str | None]:
        """(status line suffix, log level or None, log line) for a lag of ``lag`` s.

        Args:
            lag: s of wall time past the simulation time since the loop started.
            rtf: the real-time factor so far.
        """
        suffix = f"  behind {lag:.1f} s" if lag > self.CAUGHT_UP else ""
        if lag > self.BEHIND and not self.behind:
            self.behind = True
            return suffix, "warning", (
                f"running behind real time by {lag:.1f} s (x{rtf:.2f} so far): it steps as fast "
                f"as it can to catch up, its stamps are the simulation's; fewer boats, a lower "
                f"rate_hz, or --fast avoid it; nodes with use_sim_time follow its /clock")
        if lag < self.CAUGHT_UP and self.behind:
            self.behind = False
            return suffix, "info", "caught up with real time"
        return suffix, None, None


class _Status:
    """The live status line: sim time, real-time factor, first boat's position, speed, heading.

    In real time, also how far the run is behind the wall clock (:class:`Lag`).
    """

    def __init__(self, stream: TextIO, n_boats: int, realtime: bool = False) -> None:
        self._stream = stream
        self._lag = Lag() if realtime else None
        self._tty = stream.isatty()
        self._period = _STATUS_PERIOD if self._tty else _LOG_STATUS_PERIOD
        self._n = n_boats
        self._wall0 = time.monotonic()
        self._t0 = 0.0
        self._next = self._wall0 + self._period
        self._written = False
        self._last_t: float | None = None

    def start(self, t: float) -> None:
        """The simulation loop starts at simulation time ``t``.

        The real-time factor counts from here: set-up and waiting for the sea state are not
        simulation.
        """
        self._wall0 = time.monotonic()
        self._t0 = t
        self._next = self._wall0 + self._period

    def update(self, node: DynamicsNode, t: float, force: bool = False) -> None:
        now = time.monotonic()
        if (not force and now < self._next) or t == self._last_t:
            return
        self._next = now + self._period
        self._last_t = t
        boat = node.boats[0]
        state = node.state_of(boat)
        pos, q = reference_pose(boat.spec.params, state)
        speed = math.hypot(state.velocity[0], state.velocity[1])
        heading = math.degrees(quat_to_euler(q)[2])
        rtf = (t - self._t0) / max(now - self._wall0, 1e-9)
        label = boat.spec.name or "boat"
        more = f" (+{self._n - 1} boats)" if self._n > 1 else ""
        line = (f"t {t:8.2f} s  x{rtf:6.2f}  {label}{more}: pos ({pos[0]:7.2f}, {pos[1]:7.2f}, "
                f"{pos[2]:5.2f}) m  speed {speed:5.2f} m/s  heading {heading:6.1f} deg")
        if self._lag is not None:
            suffix, level, said = self._lag.check((now - self._wall0) - (t - self._t0), rtf)
            line += suffix
            if level == "warning":
                node.get_logger().warning(said)
            elif level == "info":
                node.get_logger().info(said)
        if self._tty:
            self._stream.write("\r" + line)
            self._written = True
        else:
            self._stream.write(line + "\n")
        self._stream.flush()

    def close(self) -> None:
        if self._written:
            self._stream.write("\n")
            self._stream.flush()


def run(scenario: Scenario, options: RunOptions, status: TextIO | None = None) -> int:
    """Run a scenario until its duration, Ctrl-C or SIGTERM. Returns the exit status (0).

    SIGINT and SIGTERM only set a flag that the loop checks after every step, so the step in
    progress completes, the bag is finalized and the nodes are destroyed before ROS shuts down.

    Raises:
        RecordError: the bag directory cannot be created.
        InitError: a boat's hull sinks.
    """
    status = sys.stderr if status is None else status  # now, not at import
    sim = scenario.simulation
    fast = options.fast or not sim.realtime
    # one process in real time: provisional, until the loop starts (_Loop._epoch_at_loop_start)
    given = options.process.epoch
    epoch = given if given is not None else (0.0 if fast else time.time())
    clock = SimClock(rate_hz=sim.rate_hz, epoch=epoch)
    if options.process.epoch is not None and not fast:  # joining a run that started at the epoch
        clock.steps = max(0, round((time.time() - epoch) * sim.rate_hz))
    advertise = advertises_wrenches(sim.wrench_topics, len(scenario.boats),
                                    options.process.await_recorder)  # the whole fleet's count
    if options.process.role == "shard":  # a share of the boats, joining at clock.t
        scenario = replace(scenario, boats=scenario.boats[shard_slice(
            *options.process.shard, len(scenario.boats))])
    if options.process.role in ("all", "shard"):  # derived parameters, afloat at clock.t: once
        scenario = init_scenario(scenario, clock.t)
    bag = (BagWriter(options.record, exclude=set(options.exclude_topics)) if options.record
           else None)
    stop = threading.Event()
    restore_signals = stop_on_signals(stop)
    child = options.process.supervised or options.process.ready_fd is not None
    parent = _Parent(stop) if child else None
    dds_note = use_profile()  # before the process's first participant
    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    loop = _Loop(scenario, options, clock, fast, bag, stop,
                 _Status(status, len(scenario.boats), realtime=not fast), parent=parent,
                 dds_note=dds_note, advertise_wrenches=advertise)
    code = 0
    try:
        code = loop.run()
    except (KeyboardInterrupt, ExternalShutdownException):
        code = 0
    except StartInterrupted:  # the half-made node cannot be destroyed quickly either
        code, loop.abandoned = 0, True
    finally:
        loop.close(status)
        loop.participants.shutdown()
        rclpy.try_shutdown()
        restore_signals()
    if bag is not None and bag.failed is not None and code == 0:
        code = 1  # the recording asked for is incomplete
    if loop.abandoned:  # see _Loop.close: destroying the endpoints would take minutes
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    return code


class _Parent:
    """The parent of a ``--processes`` child, heard on stdin.

    Its "go EPOCH" line starts the run; its death (stdin ends) stops the child.

    Args:
        stop: set when stdin ends.
    """

    def __init__(self, stop: threading.Event) -> None:
        self.epoch: float | None = None
        self.go = threading.Event()
        watch_stdin(stop, self._on_line)  # stdin's end: the parent is gone, end cleanly

    def _on_line(self, line: str) -> None:
        words = line.split()
        if len(words) == 2 and words[0] == "go":
            self.epoch = float(words[1])
            self.go.set()


def _refuse_reset(request: ResetSrv.Request, response: ResetSrv.Response) -> ResetSrv.Response:
    """/boatsim/reset in a run of several processes: refused, saying why."""
    response.success = False
    response.message = ("refused: a run of several processes (--processes, --shards) cannot "
                        "be reset: its boats' processes step apart; reset is served by a "
                        "one-process `boatsim run` (--fast --lockstep for learning loops)")
    return response


def _lockstep_role(options: RunOptions) -> LockstepRole:
    """The dynamics node's part in a lockstep replay: a shard's clock owner follows it."""
    if not options.lockstep:
        return "none"
    return "announce" if options.process.shard is not None else "follow"


def _dynamics_name(scenario: Scenario, options: RunOptions) -> str:
    """The dynamics node's name: ``boat_dynamics``, or a shard's.

    A shard's is ``boat_dynamics_<boat>`` when it has one named boat (as ``--processes``
    makes them), else ``boat_dynamics_shard_<K>``.
    """
    if options.process.shard is None:
        return names.DYNAMICS_NODE
    if len(scenario.boats) == 1 and scenario.boats[0].name:
        return f"{names.DYNAMICS_NODE}_{scenario.boats[0].name}"
    return f"{names.DYNAMICS_NODE}_shard_{options.process.shard[0]}"


#: The step barrier's protocol and a lockstep node's word to the replayer, not recorded (as
#: /boatsim/lockstep, it is no simulation data; how often the word is said depends on the
#: wall clock, and two identical runs would record different bags).
_BARRIER_TOPICS = frozenset({names.STEP_GRANT, names.STEP_DONE, names.LOCKSTEP_READY})
#: Topics every node has or that only the clock owner's recorder records.
_NOT_SHARDS = frozenset({names.ROSOUT, names.PARAMETER_EVENTS, names.LOCKSTEP})




def _command_topics(boats) -> frozenset[str]:
    """The command topics the boats' dynamics nodes subscribe to (and so record).

    ``cmd_thrust`` and ``cmd_rudder`` of each boat not scripted, its named thrusters' thrust,
    and the steerable ones' angle (as :meth:`node.DynamicsNode` subscribes).
    """
    out = set()
    for b in boats:
        if b.commands is not None:
            continue
        out |= {names.boat_topic(b.name, names.CMD_THRUST),
                names.boat_topic(b.name, names.CMD_RUDDER)}
        for name, model in zip(b.thrusters, b.params.thrusters, strict=False):
            out.add(names.thruster_topic(b.name, name, names.THRUSTER_THRUST))
            if model.steerable:
                out.add(names.thruster_topic(b.name, name, names.THRUSTER_ANGLE))
    return frozenset(out)


def _tapped_by_shards(node, topic: str) -> bool | None:
    """Whether a shard's dynamics node publishes or subscribes ``topic`` (it taps it).

    None while an endpoint's node is not known yet (the graph lags the endpoints): ask again.
    """
    if topic in _NOT_SHARDS:
        return False
    infos = (*node.get_publishers_info_by_topic(topic),
             *node.get_subscriptions_info_by_topic(topic))
    if any(info.node_name.startswith(names.DYNAMICS_NODE) for info in infos):
        return True
    if any(info.node_name in ("", names.UNKNOWN_NODE) for info in infos):
        return None
    return False


def _recorded(node, publisher) -> bool:
    """Whether the recorder subscribes to ``publisher``'s topic and a subscription matched."""
    return publisher.get_subscription_count() > 0 and any(
        info.node_name == names.RECORDER_NODE
        for info in node.get_subscriptions_info_by_topic(publisher.topic_name))


class _Loop:
    """The nodes of one ``boatsim run`` process and the loop that steps them.

    Args:
        scenario: the scenario (for a ``boat`` role: its one boat, afloat at the clock).
        options: how to run.
        clock: the simulation clock.
        fast: as fast as possible (``--fast``, or ``realtime: false``).
        bag: the bag to record to, or None.
        stop: set by SIGINT / SIGTERM.
        display: the status line.
        parent: a --processes child's link to its parent, or None.
        dds_note: why boatsim's Fast DDS profile is not in use, or None.
        advertise_wrenches: every wrench/<source> publisher from the start (else made on
            subscription).
    """

    def __init__(self, scenario: Scenario, options: RunOptions, clock: SimClock, fast: bool,
                 bag: BagWriter | None, stop: threading.Event, display: _Status, *,
                 parent: _Parent | None = None, dds_note: str | None = None,
                 advertise_wrenches: bool = True) -> None:
        self.scenario, self.options, self.clock, self.fast = scenario, options, clock, fast
        self.bag, self.stop, self.display = bag, stop, display
        self._told_bag_failed = False  # a failed bag write was logged
        self.duration = (options.duration if options.duration is not None
                         else scenario.simulation.duration)
        self.executor = SingleThreadedExecutor()
        self.dynamics = self.ocean = self.recorder = None
        self.member: StepMember | None = None  # a shard's side of the step barrier
        self.conductor: StepConductor | None = None  # the clock owner's side
        self.parent = parent
        self.surface_server: subprocess.Popen | None = None
        self.shared_time: SharedTime | None = None  # the simulation time, for the server
        self.abandoned = False  # the DDS endpoints are left to the process's exit
        self.logger = rclpy.logging.get_logger("boatsim")  # the first node's, once made
        self.nodes = []
        self.participants = Participants()  # the nodes' participants but the default one
        self.dds_note = dds_note
        self.advertise_wrenches = advertise_wrenches
        # fast mode, or real time behind the wall clock: the next callback round (monotonic)
        self._next_spin = 0.0

    def _make_nodes(self) -> None:
        """The dynamics and/or ocean node of this process's role, and the recorder."""
        options, clock, bag, fast = self.options, self.clock, self.bag, self.fast
        scenario = self.scenario
        tap = bag.tap(clock.stamp_ns) if bag is not None else None
        # the epoch comes with the parent's go, or (one process, real time) at the loop's start
        deferred = options.process.ready_fd is not None or self._epoch_at_loop_start
        if options.process.role == "all":  # the surface service beside this process (module docs)
            # its own session: a terminal's Ctrl-C is this process's to handle
            self.shared_time = SharedTime()
            self.surface_server = start_child(["_surface", "--time-file",
                                               str(self.shared_time.path)],
                                              start_new_session=True)
        # The ocean first: its participant discovers the boats' endpoints while they are made
        # (on the other core), and the wave field reaches the dynamics node before them.
        if options.process.role in ("all", "ocean"):
            self._make_ocean(tap, deferred)
        if options.process.role in ("all", "shard"):
            self.dynamics = DynamicsNode(scenario, clock,
                                         publish_clock=not options.process.shard,
                                         tap=tap, name=_dynamics_name(scenario, options),
                                         deferred=deferred or options.process.resume is not None,
                                         stopped=self.stop.is_set,
                                         lockstep=_lockstep_role(options),
                                         advertise_wrenches=self.advertise_wrenches,
                                         context=self.participants.new() if self.nodes else None)
            self.nodes.append(self.dynamics)
            if options.process.role == "all":
                self.dynamics.serve_reset(self._new_episode)
            if options.process.resume is not None:
                self._resume(deferred)
            if fast and options.process.shard is not None:
                # in the dynamics node's participant: they never talk to each other, and a
                # participant of its own made 100 boats over 2 shards 2.5x slower (measured)
                self.member = StepMember(*options.process.shard, scenario.digest,
                                         context=self.dynamics.context)
                self.nodes.append(self.member)
        self.logger = (self.dynamics if self.dynamics is not None else self.nodes[0]).get_logger()
        if self.dds_note is not None and len(scenario.boats) > _QUADRATIC_START:
            self.logger.info(f"boatsim's Fast DDS profile is not loaded: {self.dds_note}; "
                             "each DDS endpoint is paired with every other of its participant "
                             "as it is made: start-up grows as the square of the fleet "
                             f"(boat_dynamics/ros/{PROFILE.name} avoids it)")
        if bag is not None and options.process.role != "shard":
            self._make_recorder(tap)
        for n in self.nodes:
            if n is not self.member and n is not self.conductor:  # they spin on their own
                self.executor.add_node(n)

    def _make_ocean(self, tap: Tap | None, deferred: bool) -> None:
        """The ocean node; with shards in fast mode, the step barrier's clock owner beside it."""
        options, clock, scenario = self.options, self.clock, self.scenario
        self.ocean = OceanNode(scenario.sea, now=lambda: clock.t,
                               epoch=None if deferred else clock.epoch, tap=tap,
                               serve_surface=options.process.role == "ocean",
                               surface_centers=(lambda: self.dynamics.boat_positions())
                               if options.process.role == "all" else None,
                               environment=scenario.environment)
        self.nodes.append(self.ocean)
        if options.process.role == "ocean":  # its boats are in other processes
            self.ocean.create_service(ResetSrv, names.RESET, _refuse_reset)
        # the obstacles, latched, by the one process that owns the ocean
        self.world_markers = WorldPublisher(self.ocean, scenario.world, tap)
        self.world_markers.publish()
        if self.fast and options.process.shards:
            self.conductor = StepConductor(options.process.shards, scenario.digest, clock,
                                           self.duration, options.lockstep, tap,
                                           context=self.ocean.context)  # as the member
            self.nodes.append(self.conductor)

    def _make_recorder(self, tap: Tap) -> None:
        """The recorder of what this process's publishers do not tap, in a participant of its own.

        The sim's own topics are tapped at their publishers; the recorder takes the rest
        (with shards: what no shard taps; it looks once every shard has reported). The boats'
        command topics are their shards' whatever the graph says yet: it can show a
        replayer's publisher before the shard's subscription, and the recorder then took a
        command the shard records too (twice in the bag: a lockstep test, once in a few runs).
        """
        self.recorder_node = rclpy.create_node(names.RECORDER_NODE,
                                               context=self.participants.new())
        self.nodes.append(self.recorder_node)
        shards = self.options.process.shards
        commands = _command_topics(self.scenario.boats) if shards else frozenset()
        self.recorder = TopicRecorder(self.recorder_node, self.bag, self.clock.stamp_ns,
                                      skip=tap.topics | _BARRIER_TOPICS | commands,
                                      qos=RECORD_QOS,
                                      skip_if=(_tapped_by_shards if self.options.process.shards
                                               else None),
                                      drop={names.PARAMETER_EVENTS: declares_only})
        if self.conductor is None:
            self.recorder.discover()

    def run(self) -> int:
        """Make the nodes, wait for the sea state, step until the duration or a stop.

        Returns:
            The exit status: 0, 1 when no wave field arrived, 2 when the clock owner refused
            this process (another scenario), :data:`EXIT_STOPPED` when a boat was stopped,
            its state diverged.
        """
        self._make_nodes()
        if self.options.process.ready_fd is not None and not self._handshake():
            return 0  # stopped before the start
        if self._epoch_at_loop_start:
            self._start(time.time())
        if self.conductor is not None:
            return self._conduct()
        if not self._wait_for_sea():
            return 1
        if self.stop.is_set():
            return 0
        wall0 = self.clock.epoch  # real time: a late process catches up, no time is skipped
        if not self.fast:
            self._serve_callbacks(wall0)  # real time: the outputs at t go out at wall0 + t
        if self.dynamics is not None:
            if self.options.process.resume is None:  # a resumed shard's were its predecessor's
                self.dynamics.publish_outputs()
            self._report()
            self._checkpoint()
        if self.ocean is not None:
            self.ocean.advance(self.clock.t)
        self._log_start()
        rate = self.scenario.simulation.rate_hz
        next_discovery = time.monotonic() + _DISCOVERY_PERIOD
        next_type_check = time.monotonic() + _TYPE_CHECK_PERIOD
        self.display.start(self.clock.elapsed)
        # the duration is the run's, every episode's (/boatsim/reset)
        while ((self.duration is None or self.clock.elapsed < self.duration - 0.5 / rate)
               and not self.stop.is_set()):
            if not self._hold_for_grant(wall0):
                break
            self._step(wall0)
            next_discovery = self._record_due(next_discovery)
            if self.dynamics is not None:
                self.display.update(self.dynamics, self.clock.elapsed)
                if time.monotonic() > next_type_check:
                    next_type_check = time.monotonic() + _TYPE_CHECK_PERIOD
                    self.dynamics.check_command_types()
        if self.member is not None and self.member.refused_by is not None:
            self.logger.error(f"exit 2: the clock owner refused this process: its scenario "
                              f"{self.scenario.source} (digest {self.scenario.digest}) is not "
                              f"the run's (digest {self.member.refused_by}); start every "
                              "process of a run with the same scenario file")
            return 2
        if self.dynamics is not None:
            self.display.update(self.dynamics, self.clock.elapsed, force=True)
            if self.dynamics.stopped:
                names_ = ", ".join(self.dynamics.boats[i].spec.name or "(root)"
                                   for i in self.dynamics.stopped)
                self.logger.error(f"exit {EXIT_STOPPED}: stopped, their state diverged: "
                                  f"{names_}")
                return EXIT_STOPPED
        return 0

    def _step(self, wall0: float) -> None:
        """One step, then its outputs: in real time at their wall-clock time wall0 + t.

        Callbacks are served between (real time: until then) or after (fast): commands
        received take effect at the next step either way.
        """
        if self.dynamics is not None:
            self.dynamics.step()
        else:
            self.clock.steps += 1
        episode = self.clock.episodes
        if not self.fast:  # after the step is due, not a step early
            self._serve_callbacks(wall0)
            if self.clock.episodes != episode:  # reset meanwhile: its outputs are out
                return
        if self.dynamics is not None:
            self.dynamics.publish_outputs()
            self._report()
            if self.clock.steps % self._checkpoint_steps == 0:
                self._checkpoint()
        if self.ocean is not None:
            self.ocean.advance(self.clock.t)
        if self.shared_time is not None:
            self.shared_time.write(self.clock.t)
        if self.fast:
            self._serve_callbacks(wall0)

    def _resume(self, deferred: bool) -> None:
        """Take the boats' state from ``options.process.resume`` (a dead shard's last snapshot)."""
        from boat_dynamics.physics.core.snapshot import load

        self.dynamics.restore(load(self.options.process.resume))
        self.logger.info(f"resuming at t = {self.clock.t:g} s from {self.options.process.resume}")
        if not deferred:
            self.dynamics.start()  # /tf_static, stamped with the resumed time

    @property
    def _checkpoint_steps(self) -> int:
        return max(1, round(CHECKPOINT_PERIOD * self.scenario.simulation.rate_hz))

    def _checkpoint(self) -> None:
        """With ``options.process.checkpoint``: flush the bag, then save the boats' snapshot.

        In that order, a bag part that survives its process's death holds every message up
        to the snapshot's time: the resuming process publishes from the next step on.
        """
        if self.options.process.checkpoint is None:
            return
        from boat_dynamics.physics.core.snapshot import save

        if self.bag is not None:
            self.bag.flush()
        save(self.options.process.checkpoint, self.dynamics.snapshot())

    def _new_episode(self) -> None:
        """A reset's part outside the dynamics node: the ocean's time 0 is the new episode's.

        /ocean/wave_field (and /ocean/environment) are republished stamped with it, the
        surface server's time goes back to 0 (sampled as the boats meet the waves again).
        """
        if self.ocean is not None:
            self.ocean.start(self.clock.episode_epoch)
            self.ocean.advance(self.clock.t)
        if self.shared_time is not None:
            self.shared_time.write(self.clock.t)

    def _handshake(self) -> bool:
        """--processes start-up: say ready, wait for the parent's epoch, publish with it.

        Returns:
            False when stopped before the parent's go.
        """
        if self.options.process.await_recorder:
            self._await_recorder()
        os.write(self.options.process.ready_fd, b"ready\n")
        os.close(self.options.process.ready_fd)
        while not self.parent.go.is_set():
            if self.stop.is_set():
                return False
            self.executor.spin_once(timeout_sec=0.05)
            if self.conductor is not None:  # a replayer waiting for /clock knows we are here
                self.conductor.repeat_clock()
        self._start(self.parent.epoch)
        return True

    @property
    def _epoch_at_loop_start(self) -> bool:
        """One process in real time: simulation time 0 is the wall-clock time the loop starts.

        Not when the process started: making the nodes took 0.5 s (the default scenario),
        and every stamp then lagged the wall clock by that much.
        """
        process = self.options.process
        return not self.fast and process.epoch is None and process.ready_fd is None

    def _start(self, epoch: float) -> None:
        """Take ``epoch`` (s, the stamp of simulation time 0); publish what waited for it."""
        self.clock.epoch = epoch
        if self.ocean is not None:
            self.ocean.start(epoch)
        if self.dynamics is not None:
            self.dynamics.start()

    def _await_recorder(self) -> None:
        """Serve callbacks until the recorder subscribes to every publisher of this process."""
        deadline = time.monotonic() + _RECORDER_TIMEOUT
        publishers = [(n, p) for n in self.nodes for p in n.publishers]
        while not self.stop.is_set():
            missing = sorted({p.topic_name for n, p in publishers if not _recorded(n, p)})
            if not missing:
                return
            if time.monotonic() > deadline:
                self.logger.warning(f"the recorder has not subscribed to {', '.join(missing)} "
                                    f"after {_RECORDER_TIMEOUT:g} s; starting without it")
                return
            self.executor.spin_once(timeout_sec=0.1)

    def _await_acks(self) -> None:
        """--processes with a recorder: it has received every message before this process ends.

        The parent stops the recorder once its children have ended; a message still in
        flight then (the last step's, on a loaded machine) would be lost.
        """
        from rclpy.duration import Duration

        deadline = time.monotonic() + _ACK_TIMEOUT
        for node in self.nodes:
            for publisher in node.publishers:
                left = deadline - time.monotonic()
                if left <= 0.0 or not publisher.wait_for_all_acked(Duration(seconds=left)):
                    self.logger.warning(f"{publisher.topic_name}: the recorder did not "
                                        f"acknowledge every message within "
                                        f"{_ACK_TIMEOUT:g} s; the bag may lack the last")
                    return

    def _wait_for_sea(self) -> bool:
        """Serve callbacks until the dynamics node has the wave field; False on a time-out.

        A process started alone (``--only``) waits as long as it takes, saying so.
        """
        deadline = time.monotonic() + _FIELD_TIMEOUT
        while self.dynamics is not None and self.dynamics.sea is None and not self.stop.is_set():
            if time.monotonic() > deadline:
                if not self.options.process.standalone:
                    self.logger.error("no wave field received from the ocean node")
                    return False
                self.logger.info(f"waiting for {names.WAVE_FIELD} (`boatsim run SCENARIO "
                                 "--only ocean` starts the ocean)")
                deadline = time.monotonic() + _FIELD_TIMEOUT
            self.executor.spin_once(timeout_sec=0.05)
        return True

    def _conduct(self) -> int:
        """The clock owner's loop: grant steps, follow the slowest shard with /clock and sea.

        Returns:
            The exit status (0).
        """
        conductor, clock = self.conductor, self.clock
        next_log = time.monotonic() + 1.0
        while (done := conductor.serve(0.05)) is None:  # every shard has reported
            if self.stop.is_set():
                return 0
            next_log = conductor.log_missing(next_log)
            conductor.repeat_clock()
            spin_pending(self.executor)
        clock.steps = done  # a restarted owner joins where the shards are
        if self.recorder is not None:
            self.recorder.discover()  # now every shard's topics are known: what is left
        conductor.publish_clock()
        self.ocean.advance(clock.t)
        self._log_start()
        next_discovery = time.monotonic() + _DISCOVERY_PERIOD
        while clock.steps < conductor.end and not self.stop.is_set():
            done = conductor.serve(0.01)
            conductor.log_silent()
            while clock.steps < done:
                clock.steps += 1
                conductor.publish_clock()
                self.ocean.advance(clock.t)
            self._serve_callbacks(0.0)
            next_discovery = self._record_due(next_discovery)
        return 0

    def _record_due(self, next_discovery: float) -> float:
        """Once a second (wall): the recorder looks for new topics, a quiet chunk is written.

        Args:
            next_discovery: s (time.monotonic()) when it is due.

        Returns:
            When it is due next.
        """
        if self.bag is None or time.monotonic() <= next_discovery:
            return next_discovery
        if self.bag.failed is not None and not self._told_bag_failed:
            self._told_bag_failed = True  # once; the simulation goes on
            self.logger.error(f"{self.bag.stopped_line()}; the simulation goes on")
        if self.recorder is None:
            return time.monotonic() + _DISCOVERY_PERIOD
        self.recorder.discover()
        self.bag.flush_due(self.clock.stamp_ns())  # a quiet second is on disk too
        return time.monotonic() + _DISCOVERY_PERIOD

    def _log_start(self) -> None:
        sim = self.scenario.simulation
        boats = len(self.scenario.boats) if self.dynamics else 0
        self.logger.info(
            f"running {self.scenario.source}: {boats} boat(s) at {sim.rate_hz:g} Hz, "
            f"{self._pace()}"
            + (f", for {self.duration:g} s" if self.duration else "")
            + (f", recording to {self.bag.path}" if self.bag else ""))

    def _report(self) -> None:
        """A shard's report to the step barrier: the steps taken, the commands received."""
        if self.member is not None:
            self.member.stepped(self.clock.steps, self.dynamics.commands_received)

    def _pace(self) -> str:
        if not self.fast:
            return "real time"
        if self.member is not None:
            return (f"as fast as the step barrier grants (shard {self.options.process.shard[0]}/"
                    f"{self.options.process.shard[1]}; /clock from the ocean's process)")
        if self.conductor is not None:
            return (f"owning the clock of {self.options.process.shards} dynamics process(es): "
                    "granting steps, publishing /clock")
        return "as fast as possible (/clock published)"

    def _hold_for_grant(self, wall0: float) -> bool:
        """Serve callbacks until the next step is granted; False on a stop.

        A shard waits for the step barrier; a lockstep run for the replayer.
        """
        if self.member is not None:
            def serve() -> None:
                self._serve_callbacks(wall0)
                self.dynamics.announce_matches()  # a lockstep shard's word to the replayer

            return self.member.wait(self.clock.steps, lambda: self.dynamics.commands_received,
                                    self.stop, serve)
        if not self.options.lockstep or self.dynamics is None:
            return True
        next_repeat = time.monotonic() + 0.1
        while not self.dynamics.may_step() and not self.stop.is_set():
            self.executor.spin_once(timeout_sec=0.01)
            self.dynamics.announce_matches()
            if time.monotonic() >= next_repeat:
                self.dynamics.repeat_clock()
                next_repeat = time.monotonic() + 0.1
        return not self.stop.is_set()

    def _serve_callbacks(self, wall0: float) -> None:
        """Serve ROS callbacks after a step.

        All ready ones (lockstep); at most _FAST_SPIN_SHARE of the wall time (fast, and a
        real-time run behind the wall clock, which steps on to catch up); or until the next
        step is due on the wall clock (real time). (A real-time run behind the wall clock
        used to serve none: on a busy machine, or with a fleet too large for it, commands and
        parameter calls waited until it caught up, which it might never do.)
        """
        if self.fast and self.options.lockstep:
            spin_pending(self.executor)
            return
        step_due = wall0 + self.clock.elapsed
        if self.fast or step_due <= time.time():
            if (now := time.monotonic()) >= self._next_spin:
                spin_pending(self.executor)
                spent = time.monotonic() - now
                self._next_spin = now + spent + max(_FAST_SPIN_PERIOD,
                                                    spent / _FAST_SPIN_SHARE)
            return
        while (remaining := step_due - time.time()) > 0 and not self.stop.is_set():
            self.executor.spin_once(timeout_sec=remaining)

    def close(self, status: TextIO) -> None:
        """Finalize the bag, destroy the nodes, stop the executor."""
        self.display.close()
        if self.options.process.await_recorder:
            self._await_acks()
        if self.bag is not None:
            self.bag.close()
            total = sum(self.bag.counts.values())
            if self.bag.failed is not None:
                print(f"boatsim: error: {self.bag.stopped_line()}", file=status)
            else:
                print(f"boatsim: wrote {total} messages on {len(self.bag.counts)} topics to "
                      f"{self.bag.path}", file=status)
        endpoints = sum(1 for n in self.nodes for _ in (*n.publishers, *n.subscriptions))
        for barrier in (self.member, self.conductor):
            if barrier is not None:
                barrier.executor_.shutdown(timeout_sec=0.1)
        if self.member is not None or self.conductor is not None:
            # A process of the step barrier: destroying its nodes once hung at 100 % CPU
            # inside rclpy's Node.destroy_node (rcl's node fini, with Fast DDS; 1 run in
            # about 20; py-spy: StepMember). Its bag is final: it exits as the large ones do.
            self.abandoned = True
            self.logger.debug("leaving the DDS endpoints to the process's exit")
        elif self.abandoned or endpoints > _DESTROY_LIMIT:
            # rmw publishes the process's whole endpoint list on every change, so destroying
            # N endpoints one by one costs N^2: 67 s for 1000 boats' 14,000. The process
            # exits instead (run() ends with os._exit); ROS peers drop the endpoints when
            # the DDS participant's lease runs out.
            self.abandoned = True
            self.logger.info(f"leaving {endpoints} DDS endpoints to the process's exit "
                             "(one by one they would take minutes); ROS peers drop them "
                             "within the DDS lease")
        else:
            for n in self.nodes:
                if n in self.executor.get_nodes():
                    self.executor.remove_node(n)
                n.destroy_node()
        self.executor.shutdown(timeout_sec=0.1)
        if self.surface_server is not None:  # SIGTERM: quiet even while it still imports
            stop_processes([self.surface_server], signal.SIGTERM, timeout=2.0)
        if self.shared_time is not None:
            self.shared_time.close()
