"""Topic, service and frame names (DESIGN.md, "ROS interface": public contract).

Per-boat names are relative to the boat's namespace; :func:`boat_topic` resolves them.
"""

from __future__ import annotations

__all__ = [
    "CARRIAGE_WRENCH",
    "CLOCK",
    "CLOCK_NODE",
    "CMD_RUDDER",
    "CMD_THRUST",
    "COLLISION",
    "COLLISION_WRENCH",
    "COMMAND_NAMES",
    "DIAGNOSTICS",
    "DYNAMICS_NODE",
    "ENVIRONMENT",
    "FLEET_STATE",
    "LOCKSTEP",
    "LOCKSTEP_READY",
    "MADE_WAVES_WRENCH",
    "MAP_FRAME",
    "MMSI_BASE",
    "MOORING_WRENCH",
    "ODOM",
    "PARAMETER_EVENTS",
    "POSE",
    "RECORDER_NODE",
    "REPLAY_NODE",
    "RESET",
    "ROSOUT",
    "SAMPLE_SURFACE",
    "STEP_DONE",
    "STEP_GRANT",
    "STEP_REFUSED",
    "SURFACE_CLOUD",
    "TF",
    "TF_STATIC",
    "THRUSTER_ANGLE",
    "THRUSTER_THRUST",
    "TWIST",
    "UNKNOWN_NODE",
    "WAVE_FIELD",
    "WORLD_FRAME",
    "WORLD_MARKERS",
    "WRENCH_SOURCES",
    "ais_topic",
    "boat_of",
    "boat_topic",
    "child_frame",
    "gnss_fix_topic",
    "gnss_heading_topic",
    "gnss_vel_topic",
    "imu_topic",
    "is_command_topic",
    "odom_frame",
    "points_topic",
    "scan_topic",
    "sensor_data_topic",
    "sensor_frame",
    "thruster_topic",
    "wrench_topic",
]

CMD_THRUST = "cmd_thrust"
CMD_RUDDER = "cmd_rudder"
#: The per-boat command names (a replay republishes these topics of a bag).
COMMAND_NAMES = (CMD_THRUST, CMD_RUDDER)
#: Per named thruster: ``thrusters/<name>/thrust`` (-1..1) and ``thrusters/<name>/angle`` (rad).
THRUSTER_THRUST = "thrust"
THRUSTER_ANGLE = "angle"
ODOM = "odom"
#: boat_msgs/Collision: a boat's contact with an obstacle began or ended (events).
COLLISION = "collision"
POSE = "pose"
TWIST = "twist"
#: wrench/<source> topics published by the dynamics node (``total`` includes gravity).
WRENCH_SOURCES = ("buoyancy", "damping", "drag", "thrust", "rudder", "diffraction", "slamming",
                  "wind", "total")
#: wrench/carriage: a towed boat's carriage force (the resistance), only for a boat on one.
CARRIAGE_WRENCH = "carriage"
#: wrench/mooring: a moored boat's or a buoy's line (``anchor_line``, ``mooring``), only for
#: one that has one.
MOORING_WRENCH = "mooring"
#: wrench/collision: the obstacles' push on a boat, only in a world with obstacles.
COLLISION_WRENCH = "collision"
#: wrench/made_waves: the other boats' waves on a boat (their Froude-Krylov and diffraction
#: force), only for a boat with coefficients in a fleet where another boat makes waves.
MADE_WAVES_WRENCH = "made_waves"

WAVE_FIELD = "/ocean/wave_field"
#: boat_msgs/Environment: the current and the wind (latched, republished on change).
ENVIRONMENT = "/ocean/environment"
SAMPLE_SURFACE = "/ocean/sample_surface"
#: sensor_msgs/PointCloud2 of the surface around the boats, for viewers (RViz, Foxglove).
SURFACE_CLOUD = "/ocean/surface"
CLOCK = "/clock"
#: std_msgs/Float64MultiArray [T, n]: a lockstep client's grant "advance while /clock < T; I have
#: sent n command messages" (``boatsim run --fast --lockstep`` obeys it, from any node:
#: ``boatsim replay`` or a client of any name, docs/DESIGN.md "Lockstep: the client's recipe").
LOCKSTEP = "/boatsim/lockstep"
#: std_msgs/String "NODE TOPIC ...": a lockstep dynamics node's word that its subscriptions
#: to these command topics have matched the publishers of every lockstep client publishing
#: them (each node that publishes ``LOCKSTEP``, and ``REPLAY_NODE``), said every 0.1 s (wall)
#: while it holds. A client sends no command before: a command
#: published before the subscription has matched the publisher is lost, and the simulation
#: would wait for it for ever.
LOCKSTEP_READY = "/boatsim/lockstep_ready"
#: boat_msgs/srv/Reset: a new episode, every boat at the scenario's initial state or a given
#: one, the sensors' noise seeded (the dynamics node of a one-process run serves it).
RESET = "/boatsim/reset"
#: std_msgs/UInt64, latched: the step barrier's grant "a dynamics process may step while its
#: step count is below this" (``run --fast`` over several processes: the clock owner, in the
#: ocean's process, publishes it).
STEP_GRANT = "/boatsim/step_grant"
#: std_msgs/UInt64MultiArray [K, N, steps, commands, digest]: dynamics process K of N has
#: taken ``steps`` steps and received ``commands`` command messages (its report to the
#: barrier); ``digest`` is its scenario's (the first 16 hex digits of ``Scenario.digest``).
STEP_DONE = "/boatsim/step_done"
#: std_msgs/UInt64MultiArray [K, N, digest]: the clock owner refuses dynamics process K of N,
#: whose scenario is not its own (``digest``: the owner's); that process stops, exit 2.
STEP_REFUSED = "/boatsim/step_refused"
#: boat_msgs/FleetState: every boat's pose and twist in one message (simulation.fleet_state).
FLEET_STATE = "/boatsim/fleet_state"
#: diagnostic_msgs/DiagnosticArray, one status per boat.
DIAGNOSTICS = "/diagnostics"
#: visualization_msgs/MarkerArray, latched: the scenario's fixed obstacles (``world``), once.
WORLD_MARKERS = "/world/markers"

#: ROS 2's own topics: logs and parameter events (never equal between two runs).
ROSOUT = "/rosout"
PARAMETER_EVENTS = "/parameter_events"

#: tf2_msgs/TFMessage: world -> <boat>/base_link of every boat (``publish_tf``).
TF = "/tf"
#: tf2_msgs/TFMessage, latched: <boat>/base_link -> <boat>/<sensor>_link of every sensor.
TF_STATIC = "/tf_static"

WORLD_FRAME = "world"
#: REP-105's map frame (``simulation.frames: rep105``): the world's, under it on /tf_static.
MAP_FRAME = "map"

#: The node of `boatsim record` (the --processes children wait until it subscribes to them).
RECORDER_NODE = "boatsim_record"
#: The dynamics node (one process), and the start of every dynamics process's node name
#: (``boat_dynamics_<boat>`` with --processes, ``boat_dynamics_shard_<K>`` with --shards).
DYNAMICS_NODE = "boat_dynamics"
#: The clock owner of a --fast run over several processes (the step barrier's conductor).
CLOCK_NODE = "boatsim_clock"
#: The node of `boatsim replay`.
REPLAY_NODE = "boatsim_replay"
#: The node name rmw gives an endpoint whose node it does not know yet (the graph lags).
UNKNOWN_NODE = "_NODE_NAME_UNKNOWN_"


def boat_topic(boat: str, name: str) -> str:
    """Absolute topic of a per-boat name: ``/odom`` for the root boat, ``/<boat>/odom`` else."""
    return f"/{boat}/{name}" if boat else f"/{name}"


def boat_of(topic: str, name: str) -> str | None:
    """The boat whose per-boat ``name`` topic ``topic`` is ("" = root), or None.

    ``boat_of("/alpha/odom", ODOM)`` is ``"alpha"``, ``boat_of("/odom", ODOM)`` is ``""``.
    """
    head, sep, tail = topic.rpartition("/")
    return head.lstrip("/") if sep and tail == name and "/" not in name else None


def wrench_topic(boat: str, source: str) -> str:
    """Absolute ``wrench/<source>`` topic of a boat."""
    return boat_topic(boat, f"wrench/{source}")


def odom_frame(boat: str) -> str:
    """A boat's REP-105 odometry frame: ``<boat>/odom`` (``odom`` for the root boat)."""
    return f"{boat}/odom" if boat else "odom"


def child_frame(boat: str) -> str:
    """The body frame id of a boat: ``<boat>/base_link`` (``base_link`` for the root boat)."""
    return f"{boat}/base_link" if boat else "base_link"


def sensor_frame(boat: str, sensor: str) -> str:
    """A sensor's frame id: ``<boat>/<sensor>_link`` (``<sensor>_link`` for the root boat)."""
    return f"{boat}/{sensor}_link" if boat else f"{sensor}_link"


def imu_topic(boat: str, sensor: str) -> str:
    """sensor_msgs/Imu of an IMU named ``sensor``: ``<boat>/<sensor>/data``."""
    return boat_topic(boat, f"{sensor}/data")


def sensor_data_topic(boat: str, sensor: str) -> str:
    """A magnetometer's or depth sounder's readings: ``<boat>/<sensor>/data``."""
    return boat_topic(boat, f"{sensor}/data")


def gnss_fix_topic(boat: str, sensor: str) -> str:
    """sensor_msgs/NavSatFix of a GNSS receiver named ``sensor``: ``<boat>/<sensor>/fix``."""
    return boat_topic(boat, f"{sensor}/fix")


def ais_topic(boat: str, sensor: str) -> str:
    """boat_msgs/AisReport of an AIS receiver: ``<boat>/<sensor>/reports``."""
    return boat_topic(boat, f"{sensor}/reports")


#: An AIS report's MMSI of the boat at fleet place k: this plus k (boatsim's own range).
MMSI_BASE = 200_000_000


def scan_topic(boat: str, sensor: str) -> str:
    """sensor_msgs/LaserScan of a one-ring lidar: ``<boat>/<sensor>/scan``."""
    return boat_topic(boat, f"{sensor}/scan")


def points_topic(boat: str, sensor: str) -> str:
    """sensor_msgs/PointCloud2 of a lidar of several rings: ``<boat>/<sensor>/points``."""
    return boat_topic(boat, f"{sensor}/points")


def gnss_heading_topic(boat: str, sensor: str) -> str:
    """sensor_msgs/Imu, a dual-antenna receiver's yaw alone: ``<boat>/<sensor>/heading``."""
    return boat_topic(boat, f"{sensor}/heading")


def gnss_vel_topic(boat: str, sensor: str) -> str:
    """geometry_msgs/TwistWithCovarianceStamped, ENU: ``<boat>/<sensor>/vel``."""
    return boat_topic(boat, f"{sensor}/vel")


def thruster_topic(boat: str, thruster: str, command: str) -> str:
    """A named thruster's command topic: ``<boat>/thrusters/<thruster>/<thrust|angle>``."""
    return boat_topic(boat, f"thrusters/{thruster}/{command}")


def is_command_topic(topic: str) -> bool:
    """Whether ``topic`` is a boat's command: what a replay republishes.

    The commands: ``cmd_thrust``, ``cmd_rudder``, and a named thruster's thrust or angle.
    """
    if any(boat_of(topic, n) is not None for n in COMMAND_NAMES):
        return True
    parts = topic.split("/")
    return (len(parts) >= 4 and parts[-3] == "thrusters" and parts[-2] != ""
            and parts[-1] in (THRUSTER_THRUST, THRUSTER_ANGLE))
