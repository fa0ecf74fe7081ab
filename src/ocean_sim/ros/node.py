"""The ocean node: owns the sea state, publishes /ocean/wave_field, serves /ocean/sample_surface.

A thin adapter over :mod:`ocean_sim.physics.waves`; names and QoS come from :mod:`boat_msgs_py`.

The sea state is a set of ROS parameters (``gravity``, ``depth`` and one array per component
field: ``components.amplitude`` ...). A scenario sets them at start; a parameter change at run
time (rclpy parameter service, ``ros2 param set``) is validated as a whole sea: refused with the
reason and the old sea kept, or applied and republished on /ocean/wave_field. Arrays of
different lengths must be set together (``set_parameters_atomically``).
"""

from __future__ import annotations

import array
import math
import time
from collections.abc import Callable

import numpy as np
from boat_msgs.msg import WaveField as WaveFieldMsg
from boat_msgs.srv import SampleSurface
from rcl_interfaces.msg import (
    FloatingPointRange,
    ParameterDescriptor,
    ParameterType,
    SetParametersResult,
)
from rclpy.context import Context
from rclpy.node import Node
from rclpy.parameter import Parameter
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import Header

from boat_msgs_py.convert import seconds_to_time, time_to_seconds, vectors, wave_field_to_msg
from boat_msgs_py.names import SAMPLE_SURFACE, SURFACE_CLOUD, WAVE_FIELD, WORLD_FRAME
from boat_msgs_py.qos import SURFACE_QOS, WAVE_FIELD_QOS
from boat_msgs_py.tap import Tap, TappedPublisher
from ocean_sim.physics.environment import Environment
from ocean_sim.physics.fft import grid_points, grid_surface
from ocean_sim.physics.waves import (
    DEFAULT_PRECISION,
    PRECISIONS,
    InvalidSeaStateError,
    WaveComponent,
    WaveField,
)
from ocean_sim.physics.waves import sample_surface as sample
from ocean_sim.ros.environment import EnvironmentParameters, describe

__all__ = ["COMPONENT_FIELDS", "MAX_CLOUD_POINTS", "MAX_SAMPLE_COORDINATE", "MAX_SAMPLE_POINTS",
           "OceanNode",
           "answer_sample"]

#: Largest batch /ocean/sample_surface answers in one call.
MAX_SAMPLE_POINTS = 100_000
#: Largest |x| or |y| of a /ocean/sample_surface point, m (as far as a boat may start: beyond,
#: float32 phases overflow and nothing physical is asked).
MAX_SAMPLE_COORDINATE = 1e7

#: Most points of the /ocean/surface clouds together (a parameter change asking for more is
#: refused: 1.6 billion took the node down with MemoryError).
MAX_CLOUD_POINTS = 1_000_000

#: Component parameters: name -> (WaveComponent field, description with unit).
COMPONENT_FIELDS = {
    "components.amplitude": ("amplitude", "Amplitude a of each component, m, >= 0."),
    "components.wavelength": ("wavelength", "Wavelength of each component, m, > 0."),
    "components.direction": ("direction",
                             "Direction each component travels toward, rad, CCW from +x."),
    "components.steepness": ("steepness", "Steepness Q of each component, 0..1."),
    "components.phase": ("phase", "Phase of each component, rad."),
}

_CLOUD_FIELDS = [
    PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1)
    for i, n in enumerate(("x", "y", "z", "normal_x", "normal_y", "normal_z"))
]


def _cloud_cells(centers: np.ndarray, size: float, spacing: float) -> np.ndarray:
    """(K, 2) integer cells of one world-aligned grid of ``spacing`` (m) around the centres.

    A square of side ``size`` (m) around each centre (C, 2); each cell once where the squares
    overlap (the grid does not swim with the boats).
    """
    ticks = np.arange(-size / 2, size / 2 + 1e-9, spacing)
    gx, gy = np.meshgrid(ticks, ticks, indexing="ij")
    grid = np.stack([gx.ravel(), gy.ravel()], axis=1)
    cells = np.round((centers[:, None, :] + grid[None]) / spacing).reshape(-1, 2)
    cells = cells.astype(np.int64)
    low = cells.min(axis=0)
    span = int(cells[:, 1].max() - low[1]) + 1
    keys = np.unique((cells[:, 0] - low[0]) * span + (cells[:, 1] - low[1]))  # 1-D: fast
    return np.column_stack([keys // span + low[0], keys % span + low[1]])


def answer_sample(request: SampleSurface.Request, response: SampleSurface.Response,
                  sea: WaveField | None, now: float, epoch: float | None, precision: str,
                  log: Callable[[str], None] | None = None) -> SampleSurface.Response:
    """Fill ``response`` to ``request`` (/ocean/sample_surface), checks first.

    An exception while computing is answered (``success: false``, what went wrong) and
    handed to ``log``: it never ends the serving node.

    Args:
        request: the points and the stamp (zero = ``now``).
        response: filled and returned.
        sea: the sea state; None = none yet (refused).
        now: s, the simulation time now.
        epoch: s, the stamp of simulation time 0; None = not known yet (a stamped request
            is refused).
        precision: one of PRECISIONS.
        log: where an unexpected exception is reported (an error log), or None.
    """
    n = len(request.points)
    refusal = None
    if n > MAX_SAMPLE_POINTS:
        refusal = f"{n} points requested; at most {MAX_SAMPLE_POINTS} per call"
    elif sea is None:
        refusal = "no sea state yet (the ocean has not published /ocean/wave_field)"
    elif epoch is None and (request.stamp.sec or request.stamp.nanosec):
        refusal = ("the simulation has not started: its clock has no stamp yet (ask with a "
                   "zero stamp for simulation time 0)")
    if refusal is not None:
        response.success, response.message = False, refusal
        return response
    xy = np.array([(p.x, p.y) for p in request.points], dtype=float).reshape(n, 2)
    bad = np.flatnonzero(~np.all(np.abs(xy) <= MAX_SAMPLE_COORDINATE, axis=1))
    if bad.size:
        response.success = False
        response.message = (f"points[{bad[0]}] = ({xy[bad[0], 0]}, {xy[bad[0], 1]}) is not "
                            f"finite or beyond +-{MAX_SAMPLE_COORDINATE:g} m ({bad.size} such "
                            "points); nothing computed")
        return response
    stamp = request.stamp
    t = now if stamp.sec == 0 and stamp.nanosec == 0 else time_to_seconds(stamp) - epoch
    try:
        surface = sample(sea, xy, t, precision=precision)
    except Exception as exc:  # answered, logged: a request never ends the node
        response.success = False
        response.message = f"could not sample the surface: {type(exc).__name__}: {exc}"
        if log is not None:
            log(f"{response.message} ({n} points, t = {t:g} s)")
        return response
    response.success = True
    response.message = ""
    response.heights = surface.heights.tolist()
    response.normals = vectors(surface.normals)
    response.velocities = vectors(surface.velocities)
    return response


def _range(low: float, high: float) -> list[FloatingPointRange]:
    return [FloatingPointRange(from_value=low, to_value=high)]


class OceanNode(Node):
    """Publishes the wave field (reliable, transient-local) and answers surface queries.

    Args:
        sea: the initial sea state.
        now: returns the simulation time, s (the shared simulation clock).
        epoch: s, message stamp of simulation time 0 (0 when the simulation owns /clock,
            the wall-clock start time when it runs in real time); None = not known yet:
            nothing stamped is published before :meth:`start` (``--processes`` start-up).
        tap: also hand every published message to this (recording), or None.
        surface_centers: returns (K, 2) m, centres of the /ocean/surface grids (the boats);
            None = one grid at the origin.
        environment: the current and the wind (:mod:`ocean_sim.ros.environment`); None =
            calm.
        serve_surface: serve /ocean/sample_surface here; False when a surface server
            (:mod:`ocean_sim.ros.surface_server`) serves it in a process of its own.
        context: the rclpy context (DDS participant) to live in; None = the default one.
    """

    def __init__(self, sea: WaveField, now: Callable[[], float], epoch: float | None = 0.0,
                 tap: Tap | None = None,
                 surface_centers: Callable[[], np.ndarray] | None = None,
                 environment: Environment | None = None, serve_surface: bool = True,
                 context: Context | None = None) -> None:
        super().__init__("ocean", context=context)
        self._sea = sea
        self._now = now
        self._epoch = epoch
        self._centers = surface_centers
        self._declare_sea_parameters(sea)
        self.declare_parameter("precision", DEFAULT_PRECISION, ParameterDescriptor(
            description=f"Arithmetic of /ocean/sample_surface: one of {', '.join(PRECISIONS)} "
                        "(float64: compiled, the reference; float32: numpy's, within 0.1 mm "
                        "for physical seas)."))
        self.declare_parameter("surface.rate_hz", 1.0, ParameterDescriptor(
            description="/ocean/surface clouds per simulated second, Hz; 0 = off.",
            floating_point_range=_range(0.0, 50.0)))
        self.declare_parameter("surface.size", 40.0, ParameterDescriptor(
            description="Side of the square /ocean/surface grid around each boat, m.",
            floating_point_range=_range(1.0, 2000.0)))
        self.declare_parameter("surface.resolution", 1.0, ParameterDescriptor(
            description="Spacing of the /ocean/surface grid points, m.",
            floating_point_range=_range(0.05, 100.0)))
        # declared (and first published) before the callback, which checks their changes
        self.environment = EnvironmentParameters(self, environment or Environment(), epoch, tap)
        self.add_on_set_parameters_callback(self._on_set_parameters)
        self._cloud_rate = self.get_parameter("surface.rate_hz").value  # read every step
        self.add_post_set_parameters_callback(self._after_set_parameters)
        self._field_pub = TappedPublisher(self, WaveFieldMsg, WAVE_FIELD, WAVE_FIELD_QOS, tap)
        self._cloud_pub = TappedPublisher(self, PointCloud2, SURFACE_CLOUD, SURFACE_QOS, tap)
        self._next_cloud_t = 0.0
        self._service = (self.create_service(SampleSurface, SAMPLE_SURFACE, self._on_sample)
                         if serve_surface else None)
        if epoch is not None:
            self.publish_wave_field()
        self.get_logger().info(f"{self._describe(sea)}; {describe(self.environment.environment)}"
                               + (f"; serving {SAMPLE_SURFACE}" if serve_surface else ""))

    # ------------------------------------------------------------------ sea state

    @property
    def sea(self) -> WaveField:
        """The current sea state."""
        return self._sea

    @staticmethod
    def _describe(sea: WaveField) -> str:
        return (f"sea state: {len(sea.components)} components, depth {sea.depth:g} m, "
                f"sum Q k a = {sea.steepness_sum:.3f}")

    def _declare_sea_parameters(self, sea: WaveField) -> None:
        self.declare_parameter("gravity", sea.gravity, ParameterDescriptor(
            description="Gravitational acceleration, m/s^2.",
            floating_point_range=_range(0.01, 100.0)))
        self.declare_parameter("depth", sea.depth, ParameterDescriptor(
            description="Water depth, m, > 0; .inf = deep water."))
        for name, (_, text) in COMPONENT_FIELDS.items():
            self.declare_parameter(name, Parameter.Type.DOUBLE_ARRAY, ParameterDescriptor(
                type=ParameterType.PARAMETER_DOUBLE_ARRAY, description=text))
        self.set_parameters([
            Parameter(name, Parameter.Type.DOUBLE_ARRAY,
                      [float(getattr(c, attr)) for c in sea.components])
            for name, (attr, _) in COMPONENT_FIELDS.items()
        ])

    def _on_set_parameters(self, params: list[Parameter]) -> SetParametersResult:
        """Check a parameter set as a whole; an error while checking refuses it (logged)."""
        try:
            return self._check_and_apply({p.name: p.value for p in params}, params)
        except Exception as exc:  # no parameter change may end the node
            self.get_logger().error(f"parameter change refused: {type(exc).__name__}: {exc}")
            return SetParametersResult(successful=False,
                                       reason=f"refused: {type(exc).__name__}: {exc}")

    def _cloud_points(self, changes: dict) -> int:
        """Points of the /ocean/surface clouds with ``changes`` applied (every boat's grid)."""
        size = changes.get("surface.size", self.get_parameter("surface.size").value)
        res = changes.get("surface.resolution", self.get_parameter("surface.resolution").value)
        boats = 1 if self._centers is None else len(np.asarray(self._centers()).reshape(-1, 2))
        return boats * (math.floor(size / res) + 1) ** 2

    def _check_and_apply(self, changes: dict, params: list[Parameter]) -> SetParametersResult:
        if {"surface.size", "surface.resolution"} & changes.keys():
            points = self._cloud_points(changes)
            if points > MAX_CLOUD_POINTS:
                return SetParametersResult(successful=False, reason=(
                    f"surface.size / surface.resolution would make {points:.3g} "
                    f"/ocean/surface points; at most {MAX_CLOUD_POINTS:g} (raise the "
                    "resolution or shrink the size)"))
        for p in params:
            if p.name == "precision" and p.value not in PRECISIONS:
                return SetParametersResult(
                    successful=False,
                    reason=f"precision = {p.value!r} is not allowed: one of {PRECISIONS}")
        environment = None
        if EnvironmentParameters.names() & changes.keys():
            environment, reason = self.environment.check(changes)
            if reason is not None:
                return SetParametersResult(successful=False, reason=reason)
        result = self._set_sea(changes)
        if result.successful and environment is not None:  # both checked: apply
            self.environment.apply(environment)
        return result

    def _set_sea(self, changes: dict) -> SetParametersResult:
        """Check and apply a change of the sea-state parameters (none: nothing to do)."""
        sea_keys = {"gravity", "depth", *COMPONENT_FIELDS}
        if not sea_keys & changes.keys():
            return SetParametersResult(successful=True)
        value = {k: changes.get(k, self.get_parameter(k).value) for k in sea_keys}
        arrays = {k: list(value[k] or []) for k in COMPONENT_FIELDS}
        lengths = {k: len(v) for k, v in arrays.items()}
        if len(set(lengths.values())) > 1:
            detail = ", ".join(f"{k} has {n}" for k, n in lengths.items())
            return SetParametersResult(
                successful=False,
                reason=f"component arrays must have the same length ({detail}); set them "
                       "together with set_parameters_atomically")
        n = next(iter(lengths.values()))
        try:
            comps = tuple(WaveComponent(**{COMPONENT_FIELDS[k][0]: float(arrays[k][i])
                                           for k in COMPONENT_FIELDS}) for i in range(n))
            # an FFT tile stays one while its components do (gravity and depth change only
            # the frequencies); other components are a Gerstner sum
            sea = WaveField(comps, gravity=float(value["gravity"]), depth=float(value["depth"]),
                            tile=self._sea.tile if comps == self._sea.components else None)
        except (InvalidSeaStateError, TypeError, ValueError) as exc:
            return SetParametersResult(successful=False, reason=f"sea state refused: {exc}")
        if sea != self._sea:
            self._sea = sea
            self.publish_wave_field()
            self.get_logger().info(f"new {self._describe(sea)}")
        return SetParametersResult(successful=True)

    def _after_set_parameters(self, params: list[Parameter]) -> None:
        """Keep the cached copies of parameters read every step (called once they are set)."""
        for p in params:
            if p.name == "surface.rate_hz":
                self._cloud_rate = float(p.value)

    def start(self, epoch: float) -> None:
        """Take the stamp of simulation time 0 (s); publish the sea state and environment.

        Also a new episode's (``/boatsim/reset``): its time 0 is stamped later, and the
        surface cloud's schedule starts again from it.
        """
        self._epoch = epoch
        self._next_cloud_t = 0.0
        self.environment.start(epoch)
        self.publish_wave_field()

    def publish_wave_field(self) -> None:
        """(Re)publish the current sea state on /ocean/wave_field, stamped at simulation time 0.

        The stamp is the epoch (the stamp of simulation time 0) so that subscribers can turn
        any message stamp into simulation time.
        """
        if self._epoch is None:
            return  # published by start()
        self._field_pub.publish(wave_field_to_msg(self._sea, seconds_to_time(self._epoch)))

    # ------------------------------------------------------------------ surface cloud

    def advance(self, t: float) -> None:
        """Called by the runner after each physics step: publish /ocean/surface when due.

        Only while someone subscribes or the run records (asked once a second of wall time):
        with 100 boats the cloud is 160,000 points, about 28 ms to sample each time.
        """
        rate = self._cloud_rate
        if rate <= 0.0 or t + 1e-9 < self._next_cloud_t:
            return
        self._next_cloud_t = t + 1.0 / rate
        if self._cloud_pub.wanted(time.monotonic()):
            self._cloud_pub.publish(self.surface_cloud(t))

    def surface_cloud(self, t: float) -> PointCloud2:
        """PointCloud2 (x, y, z, normal_x, normal_y, normal_z; float32) of the surface at t.

        A Gerstner sum: the inverted query at the world-fixed grid's points. An FFT tile
        (``sea.tile``): the surface particles of the world-fixed rest points of the tile's FFT
        grid (spacing L / M <= ``surface.resolution``; fft.grid_surface), exact there, their
        x, y displaced; the direct sum as for Gerstner when that grid would be too fine.
        """
        size = self.get_parameter("surface.size").value
        res = self.get_parameter("surface.resolution").value
        centers = (np.zeros((1, 2)) if self._centers is None
                   else np.asarray(self._centers(), dtype=float).reshape(-1, 2))
        m = None if self._sea.tile is None else grid_points(self._sea.tile, res)
        if m is None:
            xy = _cloud_cells(centers, size, res) * res
            surface = sample(self._sea, xy, t)
            points = np.column_stack([xy, surface.heights, surface.normals])
        else:
            spacing = self._sea.tile.size / m
            points = np.column_stack(grid_surface(self._sea, t,
                                                  _cloud_cells(centers, size, spacing), m))
        points = points.astype(np.float32)
        return PointCloud2(
            header=Header(stamp=seconds_to_time(t, self._epoch), frame_id=WORLD_FRAME),
            height=1, width=points.shape[0],
            fields=_CLOUD_FIELDS, is_bigendian=False, point_step=24,
            row_step=24 * points.shape[0], is_dense=True,
            # an array.array('B') skips rclpy's per-byte check of a bytes value (~10 ms)
            data=array.array("B", points.tobytes()))

    # ------------------------------------------------------------------ service

    def _on_sample(self, request: SampleSurface.Request, response: SampleSurface.Response
                   ) -> SampleSurface.Response:
        return answer_sample(request, response, self._sea, self._now(), self._epoch,
                             self.get_parameter("precision").value, self.get_logger().error)

