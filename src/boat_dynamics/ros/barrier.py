"""The step barrier: one simulation clock across processes (``run --fast`` with shards).

The clock owner (:class:`StepConductor`, in the ocean's process) grants steps on
/boatsim/step_grant; each dynamics process (:class:`StepMember`) steps its boats while its
step count is below the grant and reports on /boatsim/step_done every
:data:`REPORT_EVERY` steps and whenever it has to wait. The owner
publishes /clock as the slowest process completes a step and grants at most
:data:`WINDOW_STEPS` beyond it, so no process runs further ahead of another. Under
``--lockstep`` the owner grants only what a replayer granted it on /boatsim/lockstep, and only
once every process together has received as many commands as the replayer sent: each
command then takes effect at the same step as in one process.

Each report carries the process's scenario digest (``Scenario.digest``); the owner refuses
a process whose digest is not its own on /boatsim/step_refused, and that process stops (a
shard started with another scenario once ran beside the rest, and the owner waited for ever).

Reports are cumulative and repeated while a process waits, the grant is latched: a lost or
late message delays, never breaks, the barrier. Each side spins a node of its own, so waiting
for the barrier does not rebuild the wait set of a fleet's command subscriptions.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable

from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64MultiArray, UInt64, UInt64MultiArray

from boat_dynamics.ros.node import SimClock
from boat_msgs_py import names
from boat_msgs_py.cdr import clock_template, uint64_multi_array_cdr
from boat_msgs_py.convert import lockstep_grant
from boat_msgs_py.qos import CLOCK_QOS, COMMAND_QOS, STEP_DONE_QOS, STEP_GRANT_QOS
from boat_msgs_py.tap import Tap, TappedPublisher

__all__ = ["REPORT_EVERY", "SILENT_AFTER", "WINDOW_STEPS", "StepConductor", "StepMember",
           "shard_slice"]

#: How many steps a dynamics process may run ahead of the slowest one (the grant's lead).
#: A wider window absorbs a shard's pauses (a spin for callbacks, a /diagnostics step): 100
#: mesh boats on 2 shards ran at 7.8-8.2x real time with 16, 8.6 with 32, 9.0 with 64
#: (docs/scale.md).
WINDOW_STEPS = 64
#: A dynamics process reports every this many steps (and whenever it must wait): half the
#: window, so a new grant is usually on its way before the last one runs out. A report every
#: step cost the clock owner a spin per report: 10 mesh boats on 2 shards ran at half the
#: speed of one process.
REPORT_EVERY = WINDOW_STEPS // 2
#: While waiting, reports and grants are repeated this often, s (wall).
_REPEAT_PERIOD = 0.1
#: A conductor waiting for its processes says which it lacks this often, s (wall).
_MISSING_LOG_PERIOD = 5.0
#: A dynamics process reports at least this often, s (wall), even while it steps ...
_REPORT_PERIOD = 0.5
#: ... so one not heard of for this long has stopped (died, or is being restarted), s.
SILENT_AFTER = 2.0


def shard_slice(index: int, count: int, boats: int) -> slice:
    """The boats of shard ``index`` of ``count``: a contiguous share, in scenario order.

    Args:
        index: 0 .. count - 1.
        count: shards, 1 .. boats.
        boats: boats of the scenario.
    """
    return slice(index * boats // count, (index + 1) * boats // count)


class StepMember(Node):
    """A dynamics process's side of the barrier: reports its steps, waits for grants.

    Args:
        index: this process's place, 0 .. count - 1.
        count: the dynamics processes of the run.
        digest: its scenario's digest (16 hex digits, ``Scenario.digest``).
        context: the rclpy context (DDS participant) to live in; None = the default one.
    """

    def __init__(self, index: int, count: int, digest: str,
                 context: Context | None = None) -> None:
        super().__init__(f"boatsim_step_{index}", context=context)
        self.index, self.count, self.digest = index, count, int(digest or "0", 16)
        self.granted = 0  # steps this process may have taken
        #: The clock owner's digest once it refused this process (another scenario), or None.
        self.refused_by: str | None = None
        self._done = self.create_publisher(UInt64MultiArray, names.STEP_DONE, STEP_DONE_QOS)
        self.create_subscription(UInt64, names.STEP_GRANT, self._on_grant, STEP_GRANT_QOS)
        self.create_subscription(UInt64MultiArray, names.STEP_REFUSED, self._on_refused,
                                 STEP_DONE_QOS)
        self.executor_ = SingleThreadedExecutor(context=self.context)
        self.executor_.add_node(self)
        self._last: tuple[int, int] | None = None
        self._next_repeat = self._next_report = 0.0

    def _on_grant(self, msg: UInt64) -> None:
        self.granted = max(self.granted, int(msg.data))

    def _on_refused(self, msg: UInt64MultiArray) -> None:
        if len(msg.data) == 3 and (int(msg.data[0]), int(msg.data[1])) == (self.index,
                                                                            self.count):
            if int(msg.data[2]) != self.digest:
                self.refused_by = f"{int(msg.data[2]):016x}"

    def stepped(self, steps: int, commands: int) -> None:
        """After a step: report every REPORT_EVERY steps and when the grant is used up.

        And at least every half second (wall): the conductor tells a slow process from a dead
        one by that.
        """
        if (steps % REPORT_EVERY == 0 or steps >= self.granted
                or time.monotonic() >= self._next_report):
            self.report(steps, commands)

    def report(self, steps: int, commands: int) -> None:
        """Say that ``steps`` steps are taken and ``commands`` commands received."""
        self._done.publish(uint64_multi_array_cdr((self.index, self.count, steps, commands,
                                                   self.digest)))
        self._last = (steps, commands)
        now = time.monotonic()
        self._next_repeat = now + _REPEAT_PERIOD
        self._next_report = now + _REPORT_PERIOD

    def wait(self, steps: int, commands: Callable[[], int], stop: threading.Event,
             serve: Callable[[], None]) -> bool:
        """Serve callbacks until the next step is granted; False on a stop.

        Args:
            steps: steps taken so far.
            commands: the command messages received so far (reported again when it changes:
                the conductor may be waiting for them).
            stop: set by SIGINT / SIGTERM.
            serve: the process's other callbacks (commands, parameters), called every round.
        """
        while self.granted <= steps:
            if stop.is_set() or self.refused_by is not None:
                return False
            self.executor_.spin_once(timeout_sec=0.01)
            serve()
            received = commands()
            if (steps, received) != self._last or time.monotonic() >= self._next_repeat:
                self.report(steps, received)
        return True


class StepConductor(Node):
    """The clock owner: grants steps and publishes /clock as the slowest process advances.

    Args:
        count: the dynamics processes to wait for.
        digest: the owner's scenario digest (16 hex digits); a process with another is
            refused.
        clock: the owner's simulation clock (advanced by :meth:`completed`).
        duration: s of simulation to grant, None = unbounded.
        lockstep: grant only as far as a replayer grants on /boatsim/lockstep.
        tap: also hand /clock to this (recording), or None.
        context: the rclpy context (DDS participant) to live in; None = the default one.
    """

    def __init__(self, count: int, digest: str, clock: SimClock, duration: float | None,
                 lockstep: bool, tap: Tap | None = None, context: Context | None = None
                 ) -> None:
        super().__init__(names.CLOCK_NODE, context=context)
        self.count, self.clock, self.lockstep = count, clock, lockstep
        self.digest = int(digest or "0", 16)
        #: The step count at which the run ends (inf = none).
        self.end = math.inf if duration is None else round(duration * clock.rate_hz)
        self._reports: dict[int, tuple[int, int]] = {}  # process -> (steps, commands)
        self.granted = 0
        self.granted_until = 0.0 if lockstep else math.inf
        self.granted_commands = 0
        self._grant = self.create_publisher(UInt64, names.STEP_GRANT, STEP_GRANT_QOS)
        self._clock_pub = TappedPublisher(self, Clock, names.CLOCK, CLOCK_QOS, tap)
        self._clock_template = clock_template()
        self.create_subscription(UInt64MultiArray, names.STEP_DONE, self._on_done,
                                 STEP_DONE_QOS)
        self._refuse = self.create_publisher(UInt64MultiArray, names.STEP_REFUSED,
                                             STEP_DONE_QOS)
        self._refused: set[tuple[int, int]] = set()  # (process, digest) logged
        if lockstep:
            self.create_subscription(Float64MultiArray, names.LOCKSTEP, self._on_lockstep,
                                     COMMAND_QOS)
        self.executor_ = SingleThreadedExecutor(context=self.context)
        self.executor_.add_node(self)
        self._wrong: set[int] = set()
        self._next_repeat = 0.0
        self._next_clock = 0.0
        self._heard: dict[int, float] = {}  # process -> wall time (monotonic) of its report
        self._silent: set[int] = set()  # processes said to be silent
        self._refused_grant = False  # a bad /boatsim/lockstep grant was logged

    def _on_done(self, msg: UInt64MultiArray) -> None:
        if len(msg.data) != 5:
            return
        index, count, steps, commands, digest = (int(v) for v in msg.data)
        if digest != self.digest:
            self._refuse_process(index, count, digest)
            return
        if count != self.count or index >= count:
            if count not in self._wrong:
                self._wrong.add(count)
                self.get_logger().error(
                    f"{names.STEP_DONE}: a dynamics process says it is {index} of {count}; "
                    f"this run has {self.count} (start every process with the same count)")
            return
        previous = self._reports.get(index, (0, 0))
        self._reports[index] = (max(previous[0], steps), commands)
        self._heard[index] = time.monotonic()
        if index in self._silent:
            self._silent.discard(index)
            self.get_logger().info(f"dynamics process {index}/{count} reports again (at step "
                                   f"{steps}; the run is at step {self.done()}): going on")

    def _refuse_process(self, index: int, count: int, digest: int) -> None:
        """Tell process ``index`` of ``count`` it runs another scenario; log it once."""
        self._refuse.publish(uint64_multi_array_cdr((index, count, self.digest)))
        if (index, digest) not in self._refused:
            self._refused.add((index, digest))
            self.get_logger().error(
                f"refusing dynamics process {index}/{count}: its scenario (digest "
                f"{digest:016x}) is not this run's ({self.digest:016x}); start every "
                "process of a run with the same scenario file")

    def _on_lockstep(self, msg: Float64MultiArray) -> None:
        try:
            until, commands = lockstep_grant(msg.data)
        except ValueError as exc:  # logged once; a bad grant changes nothing
            if not self._refused_grant:
                self.get_logger().error(f"ignoring invalid {names.LOCKSTEP}: {exc}")
            self._refused_grant = True
            return
        self.granted_until = max(self.granted_until, until)
        self.granted_commands = max(self.granted_commands, commands)

    def missing(self) -> list[int]:
        """The processes that have not reported yet."""
        return [k for k in range(self.count) if k not in self._reports]

    def done(self) -> int | None:
        """Steps every process has taken, or None while one has not reported."""
        if len(self._reports) < self.count:
            return None
        return min(steps for steps, _ in self._reports.values())

    def _allowed(self, done: int) -> int:
        """The grant: up to WINDOW_STEPS beyond ``done``, within the duration and lockstep."""
        if self.lockstep and sum(c for _, c in self._reports.values()) < self.granted_commands:
            return done  # a command is on its way: no step before it arrives
        limit = min(done + WINDOW_STEPS, self.end)
        grant = done
        # the one-process rule, step by step: step from k while k / rate < until - 1e-9
        while grant < limit and grant / self.clock.rate_hz < self.granted_until - 1e-9:
            grant += 1
        return grant

    def serve(self, timeout: float) -> int | None:
        """Spin once (``timeout`` s at most), grant what is allowed; returns :meth:`done`."""
        self.executor_.spin_once(timeout_sec=timeout)
        done = self.done()
        if done is None:
            return None
        grant = max(self.granted, self._allowed(done))
        now = time.monotonic()
        if grant > self.granted or now >= self._next_repeat:
            self.granted = grant
            self._grant.publish(UInt64(data=grant))
            self._next_repeat = now + _REPEAT_PERIOD
            if grant == done and self.lockstep:  # holding: late joiners see where we are
                self.publish_clock(tapped=False)
        return done

    def repeat_clock(self) -> None:
        """/clock again, unrecorded, at most every 0.1 s.

        While the owner waits (for its processes, for the parent's go), a replayer then sees
        a simulation that follows /clock.
        """
        now = time.monotonic()
        if now >= self._next_clock:
            self._next_clock = now + _REPEAT_PERIOD
            self.publish_clock(tapped=False)

    def publish_clock(self, tapped: bool = True) -> None:
        """/clock at the owner's simulation time (``tapped``: also into the bag)."""
        sec, nanosec = self.clock.stamp()
        data = self._clock_template.pack(sec, nanosec)
        if tapped:
            self._clock_pub.publish(data)
        else:
            self._clock_pub.publish_untapped(data)

    def log_silent(self) -> None:
        """Say once when a process stops reporting: the run waits for it."""
        now = time.monotonic()
        for index, heard in self._heard.items():
            if index not in self._silent and now - heard > SILENT_AFTER:
                self._silent.add(index)
                self.get_logger().warning(
                    f"dynamics process {index}/{self.count} has not reported for "
                    f"{SILENT_AFTER:g} s (its last step: {self._reports[index][0]}): the run "
                    "waits for it")

    def log_missing(self, since: float) -> float:
        """Log which processes are missing, every few seconds; returns the next log time."""
        if time.monotonic() < since:
            return since
        shards = ", ".join(f"{k}/{self.count}" for k in self.missing())
        self.get_logger().info(f"waiting for dynamics process(es) {shards} "
                               f"(`boatsim run SCENARIO --only shard K/{self.count}`)")
        return time.monotonic() + _MISSING_LOG_PERIOD
