"""Conversions between the numpy core and ROS messages."""

from __future__ import annotations

import array
import math

import numpy as np
from boat_msgs.msg import AisReport as AisReportMsg
from boat_msgs.msg import Environment as EnvironmentMsg
from boat_msgs.msg import WaveComponent as WaveComponentMsg
from boat_msgs.msg import WaveField as WaveFieldMsg
from builtin_interfaces.msg import Time
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from geometry_msgs.msg import (
    Point,
    PoseStamped,
    Quaternion,
    Transform,
    TransformStamped,
    TwistStamped,
    TwistWithCovarianceStamped,
    Vector3,
    WrenchStamped,
)
from nav_msgs.msg import Odometry
from sensor_msgs.msg import (
    Imu,
    LaserScan,
    MagneticField,
    NavSatFix,
    NavSatStatus,
    PointCloud2,
    PointField,
    Range,
)
from std_msgs.msg import Header
from tf2_msgs.msg import TFMessage

from boat_dynamics.physics.sensors import (
    AisReport,
    Datum,
    DepthReading,
    DepthSounderSpec,
    GnssReading,
    ImuReading,
    LidarSpec,
    MagnetometerReading,
    OdometryReading,
    enu_to_geodetic,
)
from boat_msgs_py.cdr import stamp_parts
from boat_msgs_py.names import MMSI_BASE, WORLD_FRAME
from ocean_sim.physics.environment import Environment, Wind
from ocean_sim.physics.waves import (
    MAX_COMPONENTS,
    InvalidSeaStateError,
    TileGrid,
    WaveComponent,
    WaveField,
)

__all__ = [
    "UNMEASURED_VARIANCE",
    "ais_report",
    "depth_range",
    "diagnostic_array",
    "environment_from_msg",
    "environment_to_msg",
    "gnss_heading",
    "gnss_velocity",
    "imu",
    "laser_scan",
    "lidar_points",
    "lockstep_grant",
    "magnetic_field",
    "nav_sat_fix",
    "noisy_odometry",
    "odometry",
    "pose_stamped",
    "radar_cloud",
    "seconds_to_time",
    "tf_message",
    "time_to_seconds",
    "twist_stamped",
    "vectors",
    "wave_field_from_msg",
    "wave_field_to_msg",
    "wrench_stamped",
]


def seconds_to_time(seconds: float, epoch: float = 0.0) -> Time:
    """builtin_interfaces/Time at ``seconds`` after ``epoch`` (s, >= 0), to the nanosecond.

    Each rounded to the ns on its own (:func:`boat_msgs_py.cdr.stamp_parts`).
    """
    sec, nanosec = stamp_parts(seconds, epoch)
    return Time(sec=sec, nanosec=nanosec)


def time_to_seconds(stamp: Time) -> float:
    """Float seconds of a builtin_interfaces/Time."""
    return stamp.sec + stamp.nanosec * 1e-9


def _header(stamp: Time, frame: str) -> Header:
    return Header(stamp=stamp, frame_id=frame)


def _quat(q: np.ndarray) -> Quaternion:
    return Quaternion(x=float(q[0]), y=float(q[1]), z=float(q[2]), w=float(q[3]))


def _vec(v: np.ndarray) -> Vector3:
    return Vector3(x=float(v[0]), y=float(v[1]), z=float(v[2]))


def vectors(rows: np.ndarray) -> list[Vector3]:
    """(N, 3) array -> list of geometry_msgs/Vector3."""
    return [Vector3(x=x, y=y, z=z) for x, y, z in np.asarray(rows, dtype=float).tolist()]


def odometry(stamp: Time, child: str, position: np.ndarray, orientation: np.ndarray,
             velocity: np.ndarray, angular_velocity: np.ndarray) -> Odometry:
    """nav_msgs/Odometry: pose of the hull reference point in ``world``, twist in the body frame.

    Args:
        stamp: message time.
        child: child frame id (``<boat>/base_link``).
        position: (3,) m, world.
        orientation: (4,) (x, y, z, w).
        velocity: (3,) m/s, body frame, of the reference point.
        angular_velocity: (3,) rad/s, body frame.
    """
    msg = Odometry(header=_header(stamp, WORLD_FRAME), child_frame_id=child)
    msg.pose.pose.position = Point(x=float(position[0]), y=float(position[1]),
                                   z=float(position[2]))
    msg.pose.pose.orientation = _quat(orientation)
    msg.twist.twist.linear = _vec(velocity)
    msg.twist.twist.angular = _vec(angular_velocity)
    return msg


def pose_stamped(odom: Odometry) -> PoseStamped:
    """The pose part of an Odometry message."""
    return PoseStamped(header=odom.header, pose=odom.pose.pose)


def twist_stamped(odom: Odometry) -> TwistStamped:
    """The twist part of an Odometry message (body frame)."""
    return TwistStamped(header=_header(odom.header.stamp, odom.child_frame_id),
                        twist=odom.twist.twist)


def wrench_stamped(stamp: Time, frame: str, force: np.ndarray, torque: np.ndarray
                   ) -> WrenchStamped:
    """geometry_msgs/WrenchStamped in the body frame ``frame``."""
    msg = WrenchStamped(header=_header(stamp, frame))
    msg.wrench.force = _vec(force)
    msg.wrench.torque = _vec(torque)
    return msg


def wave_field_to_msg(sea: WaveField, stamp: Time) -> WaveFieldMsg:
    """boat_msgs/WaveField of a core WaveField."""
    return WaveFieldMsg(
        header=_header(stamp, WORLD_FRAME),
        gravity=float(sea.gravity),
        depth=float(sea.depth),
        components=[
            WaveComponentMsg(amplitude=float(c.amplitude), wavelength=float(c.wavelength),
                             direction=float(c.direction), steepness=float(c.steepness),
                             phase=float(c.phase))
            for c in sea.components
        ],
        tile_size=0.0 if sea.tile is None else float(sea.tile.size),
        tile_resolution=0 if sea.tile is None else int(sea.tile.resolution),
    )


def wave_field_from_msg(msg: WaveFieldMsg) -> WaveField:
    """Core WaveField of a boat_msgs/WaveField (validated: may raise InvalidSeaStateError).

    At most :data:`~ocean_sim.physics.waves.MAX_COMPONENTS` components, counted first. A
    non-zero ``tile_size`` makes it an FFT tile (refused unless its components lie on the
    tile's lattice).
    """
    if len(msg.components) > MAX_COMPONENTS:
        raise InvalidSeaStateError("components", f"{len(msg.components)} components",
                                   f"at most {MAX_COMPONENTS}")
    size = getattr(msg, "tile_size", 0.0)  # a bag from before the tile fields: none
    return WaveField(
        tuple(WaveComponent(c.amplitude, c.wavelength, c.direction, c.steepness, c.phase)
              for c in msg.components),
        gravity=msg.gravity,
        depth=msg.depth,
        tile=TileGrid(size, int(msg.tile_resolution)) if size else None,
    )


def diagnostic_array(stamp: Time, statuses: list[tuple[str, int, str, tuple]]) -> DiagnosticArray:
    """diagnostic_msgs/DiagnosticArray of (name, level, message, ((key, value), ...)) entries."""
    return DiagnosticArray(
        header=_header(stamp, ""),
        status=[DiagnosticStatus(level=bytes([level]), name=name, message=message,
                                 hardware_id=name,
                                 values=[KeyValue(key=k, value=v) for k, v in values])
                for name, level, message, values in statuses])


def tf_message(stamp: Time, transforms: list[tuple[str, str, np.ndarray, np.ndarray]]
               ) -> TFMessage:
    """tf2_msgs/TFMessage of (parent, child, translation (3,) m, rotation (4,) xyzw) rows."""
    return TFMessage(transforms=[
        TransformStamped(header=_header(stamp, parent), child_frame_id=child,
                         transform=Transform(translation=_vec(p), rotation=_quat(q)))
        for parent, child, p, q in transforms])


def _cov9(matrix: np.ndarray) -> list[float]:
    return [float(x) for x in np.asarray(matrix, dtype=float).reshape(9)]


def imu(stamp: Time, frame: str, reading: ImuReading) -> Imu:
    """sensor_msgs/Imu of a reading: attitude, body rate, specific force, covariances."""
    return Imu(header=_header(stamp, frame), orientation=_quat(reading.orientation),
               orientation_covariance=_cov9(reading.orientation_covariance),
               angular_velocity=_vec(reading.angular_velocity),
               angular_velocity_covariance=_cov9(reading.angular_velocity_covariance),
               linear_acceleration=_vec(reading.linear_acceleration),
               linear_acceleration_covariance=_cov9(reading.linear_acceleration_covariance))


def magnetic_field(stamp: Time, frame: str, reading: MagnetometerReading) -> MagneticField:
    """sensor_msgs/MagneticField of a reading: T, the sensor's frame; covariance T^2."""
    return MagneticField(header=_header(stamp, frame), magnetic_field=_vec(reading.field),
                         magnetic_field_covariance=_cov9(reading.covariance))


def depth_range(stamp: Time, frame: str, spec: DepthSounderSpec, reading: DepthReading
                ) -> Range:
    """sensor_msgs/Range of a depth sounder's reading: ULTRASOUND, m, its cone in rad.

    +inf: no echo within ``max_range``; -inf: nearer than ``min_range`` (REP-117).
    """
    return Range(header=_header(stamp, frame), radiation_type=Range.ULTRASOUND,
                 field_of_view=float(spec.field_of_view), min_range=float(spec.min_range),
                 max_range=float(spec.max_range), range=float(reading.range),
                 variance=float(reading.variance))


def ais_report(stamp: Time, report: AisReport, name: str, datum: Datum) -> AisReportMsg:
    """boat_msgs/AisReport of one report: WGS-84 degrees, AIS's angles (true, clockwise)."""
    lat, lon, _ = enu_to_geodetic(datum, report.position)
    return AisReportMsg(header=_header(stamp, WORLD_FRAME), mmsi=MMSI_BASE + report.boat,
                        name=name, latitude_deg=math.degrees(lat),
                        longitude_deg=math.degrees(lon),
                        course_over_ground_deg=_compass_deg(report.course),
                        speed_over_ground=float(report.speed),
                        true_heading_deg=_compass_deg(report.heading))


def _compass_deg(angle: float) -> float:
    """Degrees in [0, 360), clockwise from north, of an ENU angle (rad, ccw from east)."""
    return float((90.0 - math.degrees(angle)) % 360.0)


def laser_scan(stamp: Time, frame: str, spec: LidarSpec, ranges: np.ndarray) -> LaserScan:
    """sensor_msgs/LaserScan of a one-ring lidar's scan: m, rad, counter-clockwise from x.

    No return: +inf (REP-117). ``scan_time``: the period between scans.
    """
    az = spec.azimuths
    step = float(az[1] - az[0]) if az.shape[0] > 1 else 0.0
    return LaserScan(header=_header(stamp, frame), angle_min=float(az[0]),
                     angle_max=float(az[-1]), angle_increment=step, time_increment=0.0,
                     scan_time=1.0 / spec.rate_hz, range_min=float(spec.min_range),
                     range_max=float(spec.max_range),
                     ranges=array.array("f", np.asarray(ranges, dtype=np.float32).tobytes()))


#: PointCloud2 fields x, y, z (float32, m, the sensor's frame).
_XYZ = [PointField(name=n, offset=4 * k, datatype=PointField.FLOAT32, count=1)
        for k, n in enumerate("xyz")]


def lidar_points(stamp: Time, frame: str, directions: np.ndarray, ranges: np.ndarray
                 ) -> PointCloud2:
    """sensor_msgs/PointCloud2 (x, y, z float32, m, sensor frame) of a lidar's returns.

    Args:
        stamp: when the scan was taken.
        frame: the sensor's frame.
        directions: (R, 3) its rays' unit directions, sensor frame.
        ranges: (R,) m (inf: no return, left out).
    """
    hit = np.isfinite(ranges)
    points = (directions[hit] * ranges[hit, None]).astype(np.float32)
    return PointCloud2(header=_header(stamp, frame), height=1, width=points.shape[0],
                       fields=_XYZ, is_bigendian=False, point_step=12,
                       row_step=12 * points.shape[0], is_dense=True,
                       data=array.array("B", points.tobytes()))


_XYZI = [PointField(name=n, offset=4 * k, datatype=PointField.FLOAT32, count=1)
         for k, n in enumerate(("x", "y", "z", "intensity"))]


def radar_cloud(stamp: Time, frame: str, points: np.ndarray, intensity: np.ndarray
                ) -> PointCloud2:
    """sensor_msgs/PointCloud2 (x, y, z, intensity float32) of a radar's detections.

    Args:
        stamp: when the spokes were taken.
        frame: the sensor's frame.
        points: (P, 3) m, sensor frame (:func:`boat_dynamics.physics.sensors.radar.
            radar_points`).
        intensity: (P,) the echo power relative to the detection threshold (linear, >= 1).
    """
    data = np.column_stack([points, intensity]).astype(np.float32)
    return PointCloud2(header=_header(stamp, frame), height=1, width=data.shape[0],
                       fields=_XYZI, is_bigendian=False, point_step=16,
                       row_step=16 * data.shape[0], is_dense=True,
                       data=array.array("B", data.tobytes()))


def nav_sat_fix(stamp: Time, frame: str, reading: GnssReading, fix: bool = True) -> NavSatFix:
    """sensor_msgs/NavSatFix (degrees, WGS-84; covariance ENU, m^2, diagonal known).

    Without a fix (an outage): status ``STATUS_NO_FIX``, the position NaN and its covariance
    unknown, as receivers' drivers publish it.
    """
    if not fix:
        return NavSatFix(
            header=_header(stamp, frame),
            status=NavSatStatus(status=NavSatStatus.STATUS_NO_FIX,
                                service=NavSatStatus.SERVICE_GPS),
            latitude=math.nan, longitude=math.nan, altitude=math.nan,
            position_covariance_type=NavSatFix.COVARIANCE_TYPE_UNKNOWN)
    return NavSatFix(
        header=_header(stamp, frame),
        status=NavSatStatus(status=NavSatStatus.STATUS_FIX, service=NavSatStatus.SERVICE_GPS),
        latitude=float(np.degrees(reading.latitude)),
        longitude=float(np.degrees(reading.longitude)), altitude=float(reading.altitude),
        position_covariance=_cov9(reading.position_covariance),
        position_covariance_type=NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN)


#: (rad/s)^2, the covariance diagonal of the angular velocity a GNSS receiver does not
#: measure: geometry_msgs/TwistWithCovariance has no "unknown" flag (sensor_msgs/Imu's -1 is
#: not its convention, and makes the matrix indefinite), so a variance far beyond any boat's
#: turn rate (a standard deviation of 1000 rad/s), which a filter fusing it learns nothing from.
UNMEASURED_VARIANCE = 1e6


def gnss_heading(stamp: Time, frame: str, yaw: float, sigma: float) -> Imu:
    """sensor_msgs/Imu of a dual-antenna heading: the yaw alone (ENU, rad).

    As GNSS drivers publish one (ublox's ``navheading``): the orientation is the rotation by
    ``yaw`` about z; its covariance sigma^2 (rad^2) on yaw and :data:`UNMEASURED_VARIANCE`
    (as rad^2: nothing a filter learns from) on roll and pitch; no angular velocity or
    acceleration (their covariances' first element -1, as sensor_msgs/Imu says).
    """
    cov = np.diag([UNMEASURED_VARIANCE, UNMEASURED_VARIANCE, sigma ** 2])
    none = [-1.0] + [0.0] * 8
    return Imu(header=_header(stamp, frame),
               orientation=_quat(np.array([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)])),
               orientation_covariance=_cov9(cov), angular_velocity_covariance=none,
               linear_acceleration_covariance=none)


def gnss_velocity(stamp: Time, reading: GnssReading) -> TwistWithCovarianceStamped:
    """geometry_msgs/TwistWithCovarianceStamped: the antenna's velocity in the world (ENU) frame.

    The header names the frame the twist is expressed in (``world``, as tf2 and
    robot_localization read it), not the antenna's link. Linear only; the angular part is not
    measured: :data:`UNMEASURED_VARIANCE` on its covariance diagonal.
    """
    msg = TwistWithCovarianceStamped(header=_header(stamp, WORLD_FRAME))
    msg.twist.twist.linear = _vec(reading.velocity)
    cov = np.zeros((6, 6))
    cov[:3, :3] = reading.velocity_covariance
    cov[3, 3] = cov[4, 4] = cov[5, 5] = UNMEASURED_VARIANCE
    msg.twist.covariance = [float(x) for x in cov.reshape(36)]
    return msg


def environment_to_msg(environment: Environment, stamp: Time) -> EnvironmentMsg:
    """boat_msgs/Environment of the current and the wind (the gusts by model, count, seed)."""
    wind = environment.wind
    return EnvironmentMsg(header=_header(stamp, WORLD_FRAME),
                          current_speed=float(environment.current_speed),
                          current_direction=float(environment.current_direction),
                          wind_speed=float(wind.speed), wind_direction=float(wind.direction),
                          gusts=wind.gusts, gust_components=int(wind.components),
                          seed=int(wind.seed))


def lockstep_grant(data) -> tuple[float, int]:
    """A /boatsim/lockstep grant [until s, commands sent] as (until, commands).

    Raises:
        ValueError: fewer than two values, or one non-finite, negative, or a count past 2^53
            (an infinite count raised OverflowError in the subscriber's callback).
    """
    if len(data) < 2:
        raise ValueError(f"{len(data)} values: a grant is [until_s, commands]")
    until, commands = float(data[0]), float(data[1])
    if not (math.isfinite(until) and until >= 0.0 and math.isfinite(commands)
            and 0.0 <= commands <= 2.0**53):
        raise ValueError(f"[{until}, {commands}]: both finite and >= 0 (the count at most 2^53)")
    return until, int(commands)


def environment_from_msg(msg: EnvironmentMsg) -> Environment:
    """The core's Environment (the gust components drawn again from the message's seed).

    Within the bounds the scenario and the ocean node's parameters have
    (:mod:`ocean_sim.physics.environment`), checked before anything is allocated: a message
    from any node on the domain cannot ask for more.

    Raises:
        InvalidEnvironmentError: a value out of its bounds, naming its key.
    """
    wind = Wind.make(msg.wind_speed, msg.wind_direction, msg.gusts, msg.gust_components,
                     msg.seed)
    return Environment(msg.current_speed, msg.current_direction, wind)


def noisy_odometry(stamp: Time, child: str, reading: OdometryReading,
                   frame: str = WORLD_FRAME) -> Odometry:
    """nav_msgs/Odometry of a noisy odometry reading, its covariances filled.

    ``frame``: its pose's frame (``world``; a drifting odometry's ``<boat>/odom``).
    """
    msg = odometry(stamp, child, reading.position, reading.orientation, reading.velocity,
                   reading.angular_velocity)
    msg.header.frame_id = frame
    msg.pose.covariance = [float(x) for x in reading.pose_covariance.reshape(36)]
    msg.twist.covariance = [float(x) for x in reading.twist_covariance.reshape(36)]
    return msg
