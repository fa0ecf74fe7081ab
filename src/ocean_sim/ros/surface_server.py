"""/ocean/sample_surface in a process of its own, beside a `boatsim run` process.

rclpy turns a whole request into Python objects before any callback can look at its size, and
the answer back: 0.5 s for 100,000 points, with pauses of the whole interpreter (its lock,
its garbage collector) of 12-54 ms at a time, measured. Served in the simulation's process,
even from a thread of its own, a 100,000-point request held the physics loop 0.29-0.64 s.
The surface server (node ``ocean_surface``) answers from the same physics
(:func:`ocean_sim.ros.node.answer_sample`) and the same inputs as the ocean node:

- the sea state and the epoch from /ocean/wave_field (latched, stamped at simulation time 0);
- the simulation time now: the latest /clock (``--fast``), else the wall clock minus the epoch;
- ``precision``: the /ocean node's parameter, followed on /parameter_events.

It ends on SIGINT or SIGTERM, when its stdin ends (the simulation's process died), or when
the simulation's process is gone (``--parent PID``).
"""

from __future__ import annotations

import os
import signal
import struct
import sys
import threading
import time

from boat_msgs.msg import WaveField as WaveFieldMsg
from boat_msgs.srv import SampleSurface
from rcl_interfaces.msg import ParameterEvent
from rclpy.node import Node
from rosgraph_msgs.msg import Clock

from boat_msgs_py.convert import time_to_seconds, wave_field_from_msg
from boat_msgs_py.names import CLOCK, PARAMETER_EVENTS, SAMPLE_SURFACE, WAVE_FIELD
from boat_msgs_py.qos import CLOCK_QOS, PARAMETER_EVENTS_QOS, WAVE_FIELD_QOS
from ocean_sim.physics.waves import PRECISIONS, InvalidSeaStateError
from ocean_sim.ros.node import answer_sample

__all__ = ["NODE_NAME", "SurfaceServer", "serve"]

#: The surface server's node name.
NODE_NAME = "ocean_surface"
#: The node whose ``precision`` parameter the server follows.
_OCEAN_NODE = "/ocean"


class SurfaceServer(Node):
    """Serves /ocean/sample_surface from the ocean's published sea state and clock.

    Args:
        context: the rclpy context (None = the default one).
    """

    def __init__(self, context=None) -> None:
        super().__init__(NODE_NAME, context=context)
        self._sea = None
        self._epoch: float | None = None
        self._clock: float | None = None  # s of simulation time, from /clock
        self._precision = "float32"  # the ocean node's default
        self.create_subscription(WaveFieldMsg, WAVE_FIELD, self._on_field, WAVE_FIELD_QOS)
        # raw: /clock comes every step in --fast mode; its 8 bytes of stamp are read directly
        self.create_subscription(Clock, CLOCK, self._on_clock, CLOCK_QOS, raw=True)
        self.create_subscription(ParameterEvent, PARAMETER_EVENTS, self._on_parameters,
                                 PARAMETER_EVENTS_QOS)
        self._service = None  # offered once the first sea state is in: a client that found
        # the service finds it ready

    def _offer(self) -> None:
        if self._service is None:
            self._service = self.create_service(SampleSurface, SAMPLE_SURFACE, self._on_sample)

    def _on_field(self, msg: WaveFieldMsg) -> None:
        try:
            self._sea = wave_field_from_msg(msg)
        except InvalidSeaStateError as exc:
            self.get_logger().error(f"ignoring invalid {WAVE_FIELD}: {exc}")
            return
        self._epoch = time_to_seconds(msg.header.stamp)
        self._offer()

    def _on_clock(self, data: bytes) -> None:
        """A serialized rosgraph_msgs/Clock: CDR header, then int32 sec, uint32 nanosec."""
        order = "<" if data[1] == 1 else ">"
        sec, nanosec = struct.unpack_from(order + "iI", data, 4)
        self._clock = sec + nanosec * 1e-9

    def _on_parameters(self, msg: ParameterEvent) -> None:
        if msg.node != _OCEAN_NODE:
            return
        for p in (*msg.new_parameters, *msg.changed_parameters):
            if p.name == "precision" and p.value.string_value in PRECISIONS:
                self._precision = p.value.string_value

    def now(self) -> float:
        """The simulation time now, s: /clock's, or the wall clock's since the epoch."""
        if self._clock is not None:
            return self._clock
        return max(time.time() - (self._epoch or time.time()), 0.0)

    def _on_sample(self, request: SampleSurface.Request, response: SampleSurface.Response
                   ) -> SampleSurface.Response:
        return answer_sample(request, response, self._sea, self.now(), self._epoch,
                             self._precision)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def serve(parent: int | None = None) -> int:
    """Run a :class:`SurfaceServer` until a signal, the end of stdin or ``parent``'s exit.

    Returns:
        The exit status, 0.
    """
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.signals import SignalHandlerOptions

    stop = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.set())

    def watch_stdin() -> None:
        for _ in sys.stdin:
            pass
        stop.set()

    threading.Thread(target=watch_stdin, daemon=True).start()
    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = SurfaceServer()
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    try:
        while not stop.is_set() and (parent is None or _alive(parent)):
            executor.spin_once(timeout_sec=0.1)
    finally:
        executor.shutdown(timeout_sec=0.1)
        node.destroy_node()
        rclpy.try_shutdown()
    return 0
