"""The sensors and transforms a dynamics node publishes: /tf, /tf_static and every sensor.

A thin adapter over :mod:`boat_dynamics.physics.sensors`: each sensor's noise state is kept
here between readings (the core's ``measure_*`` returns it), its stream keyed by the scenario
seed, the boat's name and the sensor's name; messages are built by :mod:`boat_msgs_py.convert`.
A sensor with a ``latency`` holds its messages (stamped when measured) in a
:class:`~boat_dynamics.physics.sensors.delay.DelayLine` until they are due.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from boat_msgs.msg import AisReport as AisReportMsg
from geometry_msgs.msg import TwistWithCovarianceStamped
from nav_msgs.msg import Odometry
from rclpy.node import Node
from sensor_msgs.msg import Imu, LaserScan, MagneticField, NavSatFix, PointCloud2, Range
from tf2_msgs.msg import TFMessage

from boat_dynamics.physics.body.rigid_body import quat_multiply, rotation_matrix
from boat_dynamics.physics.core.model import BoatState
from boat_dynamics.physics.core.snapshot import SnapshotError, flatten, restore
from boat_dynamics.physics.core.system import FleetState
from boat_dynamics.physics.scenario import BoatSpec, SimulationSettings
from boat_dynamics.physics.scenario.specs import TfFrames
from boat_dynamics.physics.sensors import (
    AisSpec,
    AisState,
    DeadReckoning,
    DelayLine,
    DepthSounderSpec,
    GnssSpec,
    ImuSpec,
    LidarSpec,
    MagnetometerSpec,
    OdometrySpec,
    RadarSpec,
    SensorSpec,
    ais_reports,
    dead_reckon,
    dropped,
    gnss_start,
    has_fix,
    imu_start,
    measure_depth,
    measure_gnss,
    measure_heading,
    measure_imu,
    measure_lidar,
    measure_magnetometer,
    measure_odometry,
    measure_radar,
    stream_key,
    true_motion,
)
from boat_dynamics.physics.sensors.lidar import lidar_directions
from boat_dynamics.physics.sensors.radar import radar_points, significant_height, spokes_due
from boat_dynamics.physics.world.footprints import Footprints
from boat_dynamics.physics.world.obstacles import World, floor_depth
from boat_msgs_py import names
from boat_msgs_py.cdr import FleetTemplate, tf_template
from boat_msgs_py.convert import (
    ais_report,
    depth_range,
    gnss_heading,
    gnss_velocity,
    imu,
    laser_scan,
    lidar_points,
    magnetic_field,
    nav_sat_fix,
    noisy_odometry,
    radar_cloud,
    tf_message,
)
from boat_msgs_py.qos import SENSOR_QOS, TF_QOS, TF_STATIC_QOS
from boat_msgs_py.tap import Tap, TappedPublisher
from ocean_sim.physics.waves import WaveField, sample_surface

__all__ = ["SensorPublisher", "TransformPublisher", "map_to_odom"]

_IDENTITY = np.array([0.0, 0.0, 0.0, 1.0])


@dataclass
class _Sensor:
    boat: BoatSpec
    spec: SensorSpec
    key: np.ndarray
    state: object  # ImuState | GnssState, or an int: the readings of a white-noise sensor
    pubs: list[TappedPublisher]
    frame: str
    #: its messages held until published (None: published when measured, no latency)
    delay: DelayLine | None = field(default=None)


class TransformPublisher:
    """``/tf`` (the boats' poses) and ``/tf_static`` (every sensor's mounting).

    ``frames: world``: ``world`` -> each ``<boat>/base_link``, the true pose. ``frames:
    rep105``: ``map`` -> each ``<boat>/odom`` -> its ``<boat>/base_link`` (REP-105): the
    boat's drifting odometry's pose in ``odom`` (the true pose where it has none), and
    ``map`` -> ``odom`` what puts that on the true pose; ``world`` -> ``map``, the identity,
    on /tf_static, so the topics in ``world`` stay in the same tree.

    Args:
        node: the owning node.
        boats: the boats, in fleet order.
        tap: the recorder's tap, or None.
        frames: the tree.
    """

    def __init__(self, node: Node, boats: list[BoatSpec], tap: Tap | None,
                 frames: TfFrames = "world") -> None:
        self._pub = TappedPublisher(node, TFMessage, names.TF, TF_QOS, tap)
        self._rep105 = frames == "rep105"
        links = ([(names.MAP_FRAME, names.odom_frame(b.name)) for b in boats]
                 + [(names.odom_frame(b.name), names.child_frame(b.name)) for b in boats]
                 if self._rep105 else
                 [(names.WORLD_FRAME, names.child_frame(b.name)) for b in boats])
        self._templates = []
        for parent, child in links:  # each the last one relabelled (CdrTemplate.relabel)
            self._templates.append(tf_template(parent, child,
                                               self._templates[-1] if self._templates else None))
        self._fleet = FleetTemplate(self._templates)  # every transform in one pass
        self._static = [(names.child_frame(b.name), names.sensor_frame(b.name, s.name),
                         s.position, _IDENTITY) for b in boats for s in b.sensors
                        if not isinstance(s, OdometrySpec)]
        if self._rep105:
            self._static.append((names.WORLD_FRAME, names.MAP_FRAME, np.zeros(3), _IDENTITY))
        self._static_pub = (TappedPublisher(node, TFMessage, names.TF_STATIC, TF_STATIC_QOS, tap)
                            if self._static else None)

    def publish_static(self, stamp) -> None:
        """``/tf_static``: every sensor's mounting (published once; latched)."""
        if self._static_pub is not None:
            self._static_pub.publish(tf_message(stamp, self._static))

    def publish(self, sec: int, nanosec: int, poses: np.ndarray, now: float,
                odometry: np.ndarray | None = None) -> None:
        """``/tf``, one message per transform.

        Only while someone subscribes or the run records.

        Args:
            sec: stamp, s part.
            nanosec: stamp, ns part.
            poses: (K, 7) each boat's reference point (m, world) and orientation (x, y, z, w).
            now: s, time.monotonic().
            odometry: (K, 7) each boat's pose in its odom frame (``rep105``; None: the true
                pose, an odom frame on the map's).
        """
        if not self._pub.wanted(now):
            return
        if self._rep105:
            estimate = poses if odometry is None else odometry
            poses = np.concatenate([map_to_odom(poses, estimate), estimate])
        for data in self._fleet.pack(sec, nanosec, poses):
            self._pub.publish(data)


def map_to_odom(truth: np.ndarray, estimate: np.ndarray) -> np.ndarray:
    """(K, 7) ``map`` -> ``odom`` that puts each odometry pose on the true one.

    T_map_odom = T_map_base T_odom_base^-1: R = R_t R_e^T, p = p_t - R p_e.

    Args:
        truth: (K, 7) the true poses (m, world; x, y, z, w).
        estimate: (K, 7) the poses in the odom frames.
    """
    q_e = estimate[:, 3:].copy()
    q_e[:, :3] *= -1.0  # the inverse (conjugate) of a unit quaternion
    q = np.array([quat_multiply(a, b) for a, b in zip(truth[:, 3:], q_e, strict=True)])
    p = truth[:, :3] - np.einsum("kij,kj->ki", rotation_matrix(q), estimate[:, :3])
    return np.concatenate([p, q], axis=1)


class SensorPublisher:
    """Every sensor of every boat: readings at each sensor's rate, from the true motion.

    Args:
        node: the owning node.
        boats: the boats, in fleet order.
        sim: the simulation settings (seed, datum, gravity, physics rate).
        tap: the recorder's tap, or None.
        world: the obstacles a lidar sees (None: none).
        footprints: the boats' hulls a lidar sees (None: none).
    """

    def __init__(self, node: Node, boats: list[BoatSpec], sim: SimulationSettings,
                 tap: Tap | None, world: World | None = None,
                 footprints: Footprints | None = None) -> None:
        self._sim = sim
        self._boats = [b.name for b in boats]  # AIS reports name them
        self._transponders = np.array([b.kind == "boat" for b in boats])  # buoys have none
        self._world = World() if world is None else world
        self._footprints = footprints  # the hulls a lidar sees
        self._sensors: list[tuple[int, _Sensor]] = []
        for index, boat in enumerate(boats):
            for spec in boat.sensors:
                key = stream_key(sim.seed, boat.name, spec.name)
                pubs, state = _publishers(node, boat.name, spec, key, tap)
                frame = (names.child_frame(boat.name) if isinstance(spec, OdometrySpec)
                         else names.sensor_frame(boat.name, spec.name))
                delay = DelayLine(spec.latency) if spec.latency > 0.0 else None
                self._sensors.append((index, _Sensor(boat, spec, key, state, pubs, frame,
                                                     delay)))
        self._delayed = [sensor for _, sensor in self._sensors if sensor.delay is not None]
        self._t = 0.0  # s, the time of the readings being taken

    def __len__(self) -> int:
        return len(self._sensors)

    def _names(self) -> list[str]:
        return [f"{sensor.boat.name}/{sensor.spec.name}" for _, sensor in self._sensors]

    def snapshot(self) -> dict[str, np.ndarray]:
        """Every sensor's noise state, as arrays (:mod:`boat_dynamics.physics.core.snapshot`)."""
        out: dict[str, np.ndarray] = {"sensors": np.array(self._names(), dtype=str)}
        for k, (_, sensor) in enumerate(self._sensors):
            if isinstance(sensor.state, int):  # white noise only: its reading count
                out[f"sensor{k}.count"] = np.asarray(sensor.state)
            else:
                out.update(flatten(sensor.state, f"sensor{k}."))
        return out

    def restore(self, arrays: dict[str, np.ndarray]) -> None:
        """Take every sensor's noise state from a :meth:`snapshot`.

        Raises:
            SnapshotError: it is not a snapshot of these sensors.
        """
        saved = arrays.get("sensors", np.array([], dtype=str)).tolist()
        if saved != self._names():
            raise SnapshotError(f"sensors: the snapshot's are {saved}, these are "
                                f"{self._names()}")
        for k, (_, sensor) in enumerate(self._sensors):
            if sensor.delay is not None:  # messages held are not in a snapshot: lost
                sensor.delay.clear()
            if isinstance(sensor.state, int):
                if f"sensor{k}.count" not in arrays:
                    raise SnapshotError(f"sensor{k}.count: missing (a snapshot of other "
                                        "sensors?)")
                sensor.state = int(arrays[f"sensor{k}.count"])
            else:
                sensor.state = restore(sensor.state, arrays, f"sensor{k}.")

    def reseed(self, seed: int) -> None:
        """A new episode: every sensor's noise from its first reading again, under ``seed``.

        Each stream's key is the one ``simulation.seed: seed`` gives (the boat's and the
        sensor's names under it); messages held for a latency are dropped.
        """
        for _, sensor in self._sensors:
            sensor.key = stream_key(seed, sensor.boat.name, sensor.spec.name)
            sensor.state = _first_state(sensor.spec, sensor.key)
            if sensor.delay is not None:
                sensor.delay.clear()
        self._t = 0.0

    def publish_due(self, due, stamp, center_of_mass: np.ndarray, before: FleetState,
                    after: FleetState, depth: float = math.inf,
                    sea: WaveField | None = None) -> None:
        """Read and publish the sensors ``due(rate_hz)`` says are due at this step.

        First the messages of sensors with a latency that are due now (taken ``latency`` s
        ago, or more by less than a step), then this step's readings.

        Args:
            due: rate (Hz) -> whether a stream at that rate publishes at this step.
            stamp: builtin_interfaces/Time of ``after``.
            center_of_mass: (K, 3) m, body frame, per boat.
            before: the boats' state at the start of the last step.
            after: their state now.
            depth: m, the ocean's (the sea floor's depth below the mean level; inf: deep).
            sea: the waves a lidar's rays meet (None: calm water).
        """
        self._t = float(after.t)
        for sensor in self._delayed:
            for pub, msg in sensor.delay.pop_due(self._t):
                pub.publish(msg)
        now: dict[int, BoatState] = {}  # each boat's state copied once, for all its sensors
        fleet: tuple[np.ndarray, np.ndarray] | None = None  # lidars' and AIS's, once
        for index, sensor in self._sensors:
            if not due(sensor.spec.rate_hz):
                continue
            if index not in now:
                now[index] = after.boat(index)
            sample = sensor.state if isinstance(sensor.state, int) else sensor.state.sample
            send = not dropped(sensor.key, sample, sensor.spec.dropout)  # measured either way
            if isinstance(sensor.spec, ImuSpec):
                self._imu(sensor, stamp, center_of_mass[index], before.boat(index), now[index],
                          send)
            elif isinstance(sensor.spec, GnssSpec):
                self._gnss(sensor, stamp, center_of_mass[index], now[index], send)
            elif isinstance(sensor.spec, MagnetometerSpec):
                self._magnetometer(sensor, stamp, now[index], send)
            elif isinstance(sensor.spec, DepthSounderSpec):
                self._depth(sensor, stamp, center_of_mass[index], now[index], depth, send)
            elif isinstance(sensor.spec, LidarSpec | AisSpec | RadarSpec):
                fleet = fleet or _fleet_frames(center_of_mass, after)
                if isinstance(sensor.spec, LidarSpec):
                    self._lidar(sensor, stamp, index, fleet, after, sea, send)
                elif isinstance(sensor.spec, RadarSpec):
                    self._radar(sensor, stamp, index, fleet, after, sea, send)
                else:
                    self._ais(sensor, stamp, index, fleet, center_of_mass, after, send)
            else:
                self._odometry(sensor, stamp, center_of_mass[index], now[index], send)

    def _send(self, sensor: _Sensor, pub: int, msg) -> None:
        """Publish ``msg`` on the sensor's publisher ``pub`` now, or after its latency."""
        if sensor.delay is None:
            sensor.pubs[pub].publish(msg)
        else:
            sensor.delay.push(self._t, (sensor.pubs[pub], msg))

    def _imu(self, sensor: _Sensor, stamp, com: np.ndarray, before: BoatState,
             after: BoatState, send: bool) -> None:
        spec = sensor.spec
        omega, force = true_motion(com, before, after, spec.position, self._sim.gravity)
        reading, sensor.state = measure_imu(spec, sensor.key, sensor.state, after.orientation,
                                            omega, force)
        if send:
            self._send(sensor, 0, imu(stamp, sensor.frame, reading))

    def _gnss(self, sensor: _Sensor, stamp, com: np.ndarray, after: BoatState,
              send: bool) -> None:
        spec: GnssSpec = sensor.spec
        rot = rotation_matrix(after.orientation)
        antenna = after.position + rot @ (spec.position - com)
        velocity = rot @ (after.velocity + np.cross(after.angular_velocity,
                                                    spec.position - com))
        yaw = measure_heading(spec, sensor.key, sensor.state.sample, after.orientation)
        reading, sensor.state = measure_gnss(spec, sensor.key, sensor.state, self._sim.datum,
                                             antenna, velocity)
        fix = has_fix(spec, after.t)  # in an outage: NO_FIX, and no velocity or heading
        if send:
            self._send(sensor, 0, nav_sat_fix(stamp, sensor.frame, reading, fix))
        if send and fix:
            self._send(sensor, 1, gnss_velocity(stamp, reading))
        if send and fix and yaw is not None:
            self._send(sensor, 2, gnss_heading(stamp, sensor.frame, yaw,
                                               spec.noise.heading_sigma))

    def _magnetometer(self, sensor: _Sensor, stamp, after: BoatState, send: bool) -> None:
        reading = measure_magnetometer(sensor.spec, sensor.key, sensor.state,
                                       self._sim.magnetic_field, after.orientation)
        sensor.state += 1
        if send:
            self._send(sensor, 0, magnetic_field(stamp, sensor.frame, reading))

    def _depth(self, sensor: _Sensor, stamp, com: np.ndarray, after: BoatState, depth: float,
               send: bool) -> None:
        transducer = after.position + rotation_matrix(after.orientation) @ (
            sensor.spec.position - com)
        floor = None
        if math.isfinite(self._world.shelving):
            def floor(xy: np.ndarray) -> float:  # shelving up to a shore
                return float(floor_depth(self._world, xy[None, :], depth)[0])
        reading = measure_depth(sensor.spec, sensor.key, sensor.state, transducer,
                                after.orientation, depth, floor)
        sensor.state += 1
        if send:
            self._send(sensor, 0, depth_range(stamp, sensor.frame, sensor.spec, reading))

    def _lidar(self, sensor: _Sensor, stamp, index: int,
               fleet: tuple[np.ndarray, np.ndarray], after: FleetState,
               sea: WaveField | None, send: bool) -> None:
        """A lidar's scan: the world, every other hull, the sea at ``after``'s time.

        ``fleet``: every boat's rotation and reference point (:func:`_fleet_frames`).
        """
        rot, ref = fleet
        hulls = None if self._footprints is None else (self._footprints, rot, ref)
        t = float(after.t)

        def heights(xy: np.ndarray) -> np.ndarray:
            return (np.zeros(xy.shape[0]) if sea is None
                    else sample_surface(sea, xy, t).heights)

        ranges = measure_lidar(sensor.spec, sensor.key, sensor.state, rot[index], ref[index],
                               self._world, hulls, heights, own=index)
        sensor.state += 1
        if send:
            spec = sensor.spec
            self._send(sensor, 0, laser_scan(stamp, sensor.frame, spec, ranges)
                       if spec.rings == 1 else
                       lidar_points(stamp, sensor.frame, lidar_directions(spec), ranges))

    def _radar(self, sensor: _Sensor, stamp, index: int,
               fleet: tuple[np.ndarray, np.ndarray], after: FleetState,
               sea: WaveField | None, send: bool) -> None:
        """A radar's spokes swept since its last message (none: no message).

        Its state is the next spoke's index; ``fleet`` as for :meth:`_lidar`.
        """
        rot, ref = fleet
        first, count = spokes_due(sensor.spec, sensor.state, float(after.t))
        if count == 0:
            return
        hulls = None if self._footprints is None else (self._footprints, rot, ref)
        height = (0.0 if sea is None else
                  significant_height(np.array([c.amplitude for c in sea.components])))
        scan = measure_radar(sensor.spec, sensor.key, first, count, rot[index], ref[index],
                             self._world, hulls, height, own=index)
        sensor.state = first + count
        if send:
            self._send(sensor, 0, radar_cloud(stamp, sensor.frame,
                                              radar_points(scan, rot[index]), scan.intensity))

    def _odometry(self, sensor: _Sensor, stamp, com: np.ndarray, after: BoatState,
                  send: bool) -> None:
        rot = rotation_matrix(after.orientation)
        truth = (after.position - rot @ com, after.orientation,
                 after.velocity - np.cross(after.angular_velocity, com), after.angular_velocity)
        if sensor.spec.drift:  # a dead reckoning, in its boat's odom frame
            reading, sensor.state = dead_reckon(sensor.spec, sensor.key, sensor.state, *truth)
            frame = names.odom_frame(sensor.boat.name)
        else:
            reading = measure_odometry(sensor.spec, sensor.key, sensor.state, *truth)
            sensor.state += 1
            frame = names.WORLD_FRAME
        if send:
            self._send(sensor, 0, noisy_odometry(stamp, sensor.frame, reading, frame))

    def _ais(self, sensor: _Sensor, stamp, index: int, fleet: tuple[np.ndarray, np.ndarray],
             center_of_mass: np.ndarray, after: FleetState, send: bool) -> None:
        """An AIS receiver's reports due now: every other boat's, at its interval.

        ``fleet``: every boat's rotation and reference point (:func:`_fleet_frames`).
        """
        rot, ref = fleet
        ground = np.einsum("bij,bj->bi", rot, after.velocity - np.cross(after.angular_velocity,
                                                                        center_of_mass))
        heading = np.arctan2(rot[:, 1, 0], rot[:, 0, 0])
        reports, sensor.state = ais_reports(sensor.spec, sensor.key, sensor.state,
                                            float(after.t), index, ref, ground, heading,
                                            self._transponders)
        if send:
            for r in reports:
                self._send(sensor, 0, ais_report(stamp, r, self._boats[r.boat],
                                                 self._sim.datum))

    def odometry_poses(self, count: int) -> np.ndarray | None:
        """(count, 7) each boat's first drifting odometry's pose (NaN rows: none), or None.

        The pose of its last reading (m, world-parallel odom frame; x, y, z, w).
        """
        out = None
        for index, sensor in self._sensors:
            if (isinstance(sensor.spec, OdometrySpec) and sensor.spec.drift
                    and sensor.state.position is not None):
                if out is None:
                    out = np.full((count, 7), np.nan)
                if np.isnan(out[index, 0]):
                    out[index] = np.concatenate([sensor.state.position,
                                                 sensor.state.orientation])
        return out


def _fleet_frames(center_of_mass: np.ndarray, after: FleetState
                  ) -> tuple[np.ndarray, np.ndarray]:
    """(B, 3, 3) every boat's body-to-world rotation, (B, 3) m its hull reference point."""
    rot = rotation_matrix(after.orientation)
    return rot, after.position - np.einsum("bij,bj->bi", rot, center_of_mass)


def _first_state(spec: SensorSpec, key: np.ndarray) -> object:
    """A sensor's first noise state under ``key`` (white noise only: its sample count, 0)."""
    if isinstance(spec, ImuSpec):
        return imu_start(spec, key)
    if isinstance(spec, GnssSpec):
        return gnss_start(spec, key)
    if isinstance(spec, AisSpec):
        return AisState()
    if isinstance(spec, OdometrySpec) and spec.drift:
        return DeadReckoning()
    return 0


def _publishers(node: Node, boat: str, spec: SensorSpec, key: np.ndarray, tap: Tap | None
                ) -> tuple[list[TappedPublisher], object]:
    """A sensor's publishers and its first noise state (:func:`_first_state`)."""
    return _sensor_publishers(node, boat, spec, tap), _first_state(spec, key)


def _sensor_publishers(node: Node, boat: str, spec: SensorSpec, tap: Tap | None
                       ) -> list[TappedPublisher]:
    """A sensor's publishers."""
    if isinstance(spec, ImuSpec):
        return [TappedPublisher(node, Imu, names.imu_topic(boat, spec.name), SENSOR_QOS, tap)]
    if isinstance(spec, GnssSpec):
        heading = ([] if spec.heading_baseline is None else
                   [TappedPublisher(node, Imu, names.gnss_heading_topic(boat, spec.name),
                                    SENSOR_QOS, tap)])
        return [TappedPublisher(node, NavSatFix, names.gnss_fix_topic(boat, spec.name),
                                SENSOR_QOS, tap),
                TappedPublisher(node, TwistWithCovarianceStamped,
                                names.gnss_vel_topic(boat, spec.name), SENSOR_QOS, tap),
                *heading]
    if isinstance(spec, MagnetometerSpec | DepthSounderSpec):
        return [TappedPublisher(node, MagneticField if isinstance(spec, MagnetometerSpec)
                                else Range, names.sensor_data_topic(boat, spec.name),
                                SENSOR_QOS, tap)]
    if isinstance(spec, AisSpec):
        return [TappedPublisher(node, AisReportMsg, names.ais_topic(boat, spec.name),
                                SENSOR_QOS, tap)]
    if isinstance(spec, RadarSpec):
        return [TappedPublisher(node, PointCloud2, names.points_topic(boat, spec.name),
                                SENSOR_QOS, tap)]
    if isinstance(spec, LidarSpec):
        return [TappedPublisher(node, LaserScan, names.scan_topic(boat, spec.name), SENSOR_QOS,
                                tap) if spec.rings == 1 else
                TappedPublisher(node, PointCloud2, names.points_topic(boat, spec.name),
                                SENSOR_QOS, tap)]
    return [TappedPublisher(node, Odometry, names.boat_topic(boat, spec.name), SENSOR_QOS, tap)]
