"""The ocean node: owns the sea state, publishes /ocean/wave_field, serves /ocean/sample_surface.

A thin adapter over :mod:`ocean_sim.waves`; names and QoS come from :mod:`boat_msgs_py`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from boat_msgs.msg import WaveField as WaveFieldMsg
from boat_msgs.srv import SampleSurface
from rclpy.node import Node

from boat_msgs_py.convert import seconds_to_time, time_to_seconds, vectors, wave_field_to_msg
from boat_msgs_py.names import SAMPLE_SURFACE, WAVE_FIELD
from boat_msgs_py.qos import WAVE_FIELD_QOS
from boat_msgs_py.tap import Tap, TappedPublisher
from ocean_sim.waves import WaveField, sample_surface

__all__ = ["MAX_SAMPLE_POINTS", "OceanNode"]

#: Largest batch /ocean/sample_surface answers in one call.
MAX_SAMPLE_POINTS = 100_000


class OceanNode(Node):
    """Publishes the wave field (reliable, transient-local) and answers surface queries.

    Args:
        sea: the sea state.
        now: returns the simulation time, s (the shared simulation clock).
        epoch: s, message stamp of simulation time 0 (0 when the simulation owns /clock,
            the wall-clock start time when it runs in real time).
        tap: also hand every published message to this (recording), or None.

    """

    def __init__(self, sea: WaveField, now: Callable[[], float], epoch: float = 0.0,
                 tap: Tap | None = None) -> None:
        super().__init__("ocean", namespace="/ocean")
        self._sea = sea
        self._now = now
        self._epoch = epoch
        self._field_pub = TappedPublisher(self, WaveFieldMsg, WAVE_FIELD, WAVE_FIELD_QOS, tap)
        self._service = self.create_service(SampleSurface, SAMPLE_SURFACE, self._on_sample)
        self.publish_wave_field()
        self.get_logger().info(
            f"sea state: {len(sea.components)} components, depth {sea.depth:g} m, "
            f"sum Q k a = {sea.steepness_sum:.3f}; serving {SAMPLE_SURFACE}"
        )

    @property
    def sea(self) -> WaveField:
        """The current sea state."""
        return self._sea

    def publish_wave_field(self) -> None:
        """(Re)publish the current sea state on /ocean/wave_field."""
        stamp = seconds_to_time(self._epoch + self._now())
        self._field_pub.publish(wave_field_to_msg(self._sea, stamp))

    def _on_sample(self, request: SampleSurface.Request, response: SampleSurface.Response
                   ) -> SampleSurface.Response:
        n = len(request.points)
        if n > MAX_SAMPLE_POINTS:
            response.success = False
            response.message = f"{n} points requested; at most {MAX_SAMPLE_POINTS} per call"
            return response
        xy = np.array([(p.x, p.y) for p in request.points], dtype=float).reshape(n, 2)
        bad = np.flatnonzero(~np.all(np.isfinite(xy), axis=1))
        if bad.size:
            response.success = False
            response.message = (f"points[{bad[0]}] = ({xy[bad[0], 0]}, {xy[bad[0], 1]}) is not "
                                f"finite ({bad.size} non-finite points); nothing computed")
            return response
        stamp = request.stamp
        t = self._now() if stamp.sec == 0 and stamp.nanosec == 0 else (
            time_to_seconds(stamp) - self._epoch)
        surface = sample_surface(self._sea, xy, t)
        response.success = True
        response.heights = surface.heights.tolist()
        response.normals = vectors(surface.normals)
        response.velocities = vectors(surface.velocities)
        return response
