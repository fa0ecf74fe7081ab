"""Client side of the ocean: `boatsim query` asks /ocean/sample_surface of a running ocean."""

from __future__ import annotations

import time
from dataclasses import dataclass

import rclpy
from boat_msgs.msg import WaveField as WaveFieldMsg
from boat_msgs.srv import SampleSurface
from geometry_msgs.msg import Point
from rclpy.executors import SingleThreadedExecutor

from boat_msgs_py.convert import seconds_to_time, time_to_seconds
from boat_msgs_py.names import SAMPLE_SURFACE, WAVE_FIELD
from boat_msgs_py.qos import WAVE_FIELD_QOS

__all__ = ["OceanUnavailableError", "QueryResult", "query_surface"]


class OceanUnavailableError(RuntimeError):
    """No ocean answered in time (no `boatsim run` on this ROS_DOMAIN_ID?)."""


@dataclass(frozen=True)
class QueryResult:
    """An answer of /ocean/sample_surface.

    Attributes:
        points: the (x, y) queried, m.
        time: simulation time of the answer, s, or None for "the ocean's current time".
        response: the service response.
    """

    points: list[tuple[float, float]]
    time: float | None
    response: SampleSurface.Response


def query_surface(points: list[tuple[float, float]], sim_time: float | None = None,
                  timeout: float = 5.0) -> QueryResult:
    """Ask the running ocean for the surface at ``points``.

    Args:
        points: world (x, y), m.
        sim_time: simulation time to sample at, s; None = the ocean's current time.
        timeout: s to wait for the ocean (wall clock).

    Raises:
        OceanUnavailableError: no ocean answered within ``timeout``.
    """
    context = rclpy.Context()
    rclpy.init(context=context)
    node = rclpy.create_node("boatsim_query", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    try:
        deadline = time.monotonic() + timeout
        stamp = seconds_to_time(0.0)
        if sim_time is not None:
            # The wave field is stamped at simulation time 0: it gives the clock's epoch.
            fields: list[WaveFieldMsg] = []
            node.create_subscription(WaveFieldMsg, WAVE_FIELD, fields.append, WAVE_FIELD_QOS)
            while not fields:
                if time.monotonic() > deadline:
                    raise OceanUnavailableError(f"no {WAVE_FIELD} within {timeout:g} s")
                executor.spin_once(timeout_sec=0.05)
            stamp = seconds_to_time(time_to_seconds(fields[0].header.stamp) + sim_time)
        client = node.create_client(SampleSurface, SAMPLE_SURFACE)
        if not client.wait_for_service(timeout_sec=max(deadline - time.monotonic(), 0.01)):
            raise OceanUnavailableError(f"{SAMPLE_SURFACE} did not answer within {timeout:g} s")
        request = SampleSurface.Request(stamp=stamp,
                                        points=[Point(x=x, y=y) for x, y in points])
        future = client.call_async(request)
        while not future.done():
            if not client.service_is_ready():  # the server left the graph: no answer comes
                raise OceanUnavailableError(
                    f"{SAMPLE_SURFACE}: its server left the ROS graph without answering (it "
                    "stopped or died)")
            if time.monotonic() > deadline:
                raise OceanUnavailableError(
                    f"{SAMPLE_SURFACE} did not answer within {timeout:g} s (a server that "
                    "died stays listed until its DDS lease runs out: 4 s for boatsim's "
                    "processes, 20 s for Fast DDS's default)")
            executor.spin_once(timeout_sec=0.05)
        return QueryResult(points, sim_time, future.result())
    finally:
        executor.shutdown(timeout_sec=0.1)
        node.destroy_node()
        rclpy.try_shutdown(context=context)
