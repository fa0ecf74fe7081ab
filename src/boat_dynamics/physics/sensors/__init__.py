"""Sensor models of the core (pure numpy): what sensors on a boat read.

An IMU, a GNSS receiver, a noisy odometry, a magnetometer, a depth sounder, a lidar, an AIS
receiver and a radar.

Each sensor is a frozen spec, a frozen noise state and a function ``measure_*(spec, key,
state, truth...) -> (reading, state)``; the noise is drawn from the scenario seed by sample
index (:mod:`.noise`), so the same seed gives the same readings.
"""

from boat_dynamics.physics.sensors.ais import AisReport, AisSpec, AisState, ais_reports
from boat_dynamics.physics.sensors.delay import DelayLine
from boat_dynamics.physics.sensors.depth_sounder import (
    DepthReading,
    DepthSounderSpec,
    measure_depth,
    slant_range,
)
from boat_dynamics.physics.sensors.gnss import (
    Datum,
    GnssNoise,
    GnssReading,
    GnssSpec,
    GnssState,
    Multipath,
    enu_to_geodetic,
    geodetic_to_enu,
    gnss_start,
    has_fix,
    measure_gnss,
    measure_heading,
)
from boat_dynamics.physics.sensors.imu import (
    ImuReading,
    ImuSpec,
    ImuState,
    InertialNoise,
    imu_start,
    measure_imu,
    true_motion,
)
from boat_dynamics.physics.sensors.lidar import LidarSpec, measure_lidar
from boat_dynamics.physics.sensors.magnetometer import (
    EarthField,
    MagnetometerReading,
    MagnetometerSpec,
    measure_magnetometer,
)
from boat_dynamics.physics.sensors.noise import dropped, stream_key
from boat_dynamics.physics.sensors.odometry import (
    DeadReckoning,
    OdometryNoise,
    OdometryReading,
    OdometrySpec,
    dead_reckon,
    measure_odometry,
)
from boat_dynamics.physics.sensors.radar import RadarScan, RadarSpec, measure_radar

__all__ = [
    "AisReport",
    "AisSpec",
    "AisState",
    "Datum",
    "DeadReckoning",
    "DelayLine",
    "DepthReading",
    "DepthSounderSpec",
    "EarthField",
    "GnssNoise",
    "GnssReading",
    "GnssSpec",
    "GnssState",
    "ImuReading",
    "ImuSpec",
    "ImuState",
    "InertialNoise",
    "LidarSpec",
    "MagnetometerReading",
    "MagnetometerSpec",
    "Multipath",
    "OdometryNoise",
    "OdometryReading",
    "OdometrySpec",
    "RadarScan",
    "RadarSpec",
    "SensorSpec",
    "ais_reports", "dead_reckon",
    "dropped",
    "enu_to_geodetic",
    "geodetic_to_enu",
    "gnss_start",
    "has_fix",
    "imu_start",
    "measure_depth",
    "measure_gnss",
    "measure_heading",
    "measure_imu",
    "measure_lidar",
    "measure_magnetometer",
    "measure_odometry",
    "measure_radar",
    "slant_range",
    "stream_key",
    "true_motion",
]

#: A sensor of a boat's ``sensors`` list.
SensorSpec = (ImuSpec | GnssSpec | OdometrySpec | MagnetometerSpec | DepthSounderSpec
              | LidarSpec | AisSpec | RadarSpec)
