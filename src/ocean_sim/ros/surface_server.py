"""/ocean/sample_surface in a process of its own, beside a `boatsim run` process.

rclpy turns a whole request into Python objects before any callback can look at its size, and
the answer back: 0.5 s for 100,000 points, with pauses of the whole interpreter (its lock,
its garbage collector) of 12-54 ms at a time, measured. Served in the simulation's process,
even from a thread of its own, a 100,000-point request held the physics loop 0.29-0.64 s.
The surface server (node ``ocean_surface``) answers from the same physics
(:func:`ocean_sim.ros.node.answer_sample`) and the same inputs as the ocean node:

- the sea state and the epoch from /ocean/wave_field (latched, stamped at simulation time 0);
- the simulation time now: what the simulation writes every step into a shared 8-byte file
  (``--time-file``; :class:`boat_msgs_py.process.SharedTime`), so a zero-stamp request is
  answered at the time the ocean node would have used, within a step;
- ``precision``: the /ocean node's parameter, followed on /parameter_events.

It ends on SIGINT or SIGTERM, or when its stdin ends (the simulation's process died; on
Linux it also gets SIGTERM then).
"""

from __future__ import annotations

import threading
from collections.abc import Callable

from boat_msgs.msg import WaveField as WaveFieldMsg
from boat_msgs.srv import SampleSurface
from rcl_interfaces.msg import ParameterEvent
from rclpy.node import Node

from boat_msgs_py.convert import time_to_seconds, wave_field_from_msg
from boat_msgs_py.names import PARAMETER_EVENTS, SAMPLE_SURFACE, WAVE_FIELD
from boat_msgs_py.qos import PARAMETER_EVENTS_QOS, WAVE_FIELD_QOS
from ocean_sim.physics.waves import DEFAULT_PRECISION, PRECISIONS, InvalidSeaStateError
from ocean_sim.ros.node import answer_sample

__all__ = ["NODE_NAME", "SurfaceServer", "serve"]

#: The surface server's node name.
NODE_NAME = "ocean_surface"
#: The node whose ``precision`` parameter the server follows.
_OCEAN_NODE = "/ocean"


class SurfaceServer(Node):
    """Serves /ocean/sample_surface from the ocean's published sea state and clock.

    Args:
        now: returns the simulation time now, s.
        context: the rclpy context (None = the default one).
    """

    def __init__(self, now: Callable[[], float], context=None) -> None:
        super().__init__(NODE_NAME, context=context)
        self.now = now
        self._sea = None
        self._epoch: float | None = None
        self._precision = DEFAULT_PRECISION  # the ocean node's default
        self.create_subscription(WaveFieldMsg, WAVE_FIELD, self._on_field, WAVE_FIELD_QOS)
        self.create_subscription(ParameterEvent, PARAMETER_EVENTS, self._on_parameters,
                                 PARAMETER_EVENTS_QOS)
        self.refused = 0  # invalid /ocean/wave_field messages
        self._service = None  # offered once the first sea state is in: a client that found
        # the service finds it ready

    def _offer(self) -> None:
        if self._service is None:
            self._service = self.create_service(SampleSurface, SAMPLE_SURFACE, self._on_sample)

    def _on_field(self, msg: WaveFieldMsg) -> None:
        try:
            self._sea = wave_field_from_msg(msg)
        except InvalidSeaStateError as exc:
            self.refused += 1  # the first logged with its reason, the rest counted
            if self.refused == 1:
                self.get_logger().error(f"ignoring invalid {WAVE_FIELD}: {exc} (later "
                                        "refusals are counted, not logged)")
            return
        self._epoch = time_to_seconds(msg.header.stamp)
        self._offer()

    def _on_parameters(self, msg: ParameterEvent) -> None:
        if msg.node != _OCEAN_NODE:
            return
        for p in (*msg.new_parameters, *msg.changed_parameters):
            if p.name == "precision" and p.value.string_value in PRECISIONS:
                self._precision = p.value.string_value

    def _on_sample(self, request: SampleSurface.Request, response: SampleSurface.Response
                   ) -> SampleSurface.Response:
        return answer_sample(request, response, self._sea, self.now(), self._epoch,
                             self._precision, self.get_logger().error)


def serve(time_file: str) -> int:
    """Run a :class:`SurfaceServer` until a signal or the end of stdin (the run is gone).

    Args:
        time_file: the simulation's :class:`boat_msgs_py.process.SharedTime` file.

    Returns:
        The exit status, 0.
    """
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.signals import SignalHandlerOptions

    from boat_msgs_py.process import SharedTime, stop_on_signals, watch_stdin

    stop = threading.Event()
    restore_signals = stop_on_signals(stop)
    watch_stdin(stop)

    shared = SharedTime(time_file)
    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = SurfaceServer(shared.read)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    try:
        while not stop.is_set():
            executor.spin_once(timeout_sec=0.1)
    finally:
        executor.shutdown(timeout_sec=0.1)
        node.destroy_node()
        rclpy.try_shutdown()
        shared.close()
        restore_signals()
    return 0
