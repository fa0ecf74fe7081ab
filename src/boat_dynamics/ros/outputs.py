"""What a dynamics node publishes of its fleet, from one object: :class:`FleetPublisher`.

Every boat has topics of its own (``<boat>/odom``, ``pose``, ``twist``, ``wrench/<source>``,
``wrench/carriage`` of a towed boat), so DDS has a publisher per boat and topic; the fleet
publisher packs each kind for every boat in one pass (:class:`boat_msgs_py.cdr.FleetTemplate`)
and hands each boat its message. It also owns the fleet-wide topics: /diagnostics (one status
per boat), /boatsim/fleet_state, /tf and /tf_static, and the sensors. The node decides what is
due at a step and gives the values; nothing here steps or reads the physics.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from boat_msgs.msg import FleetState as FleetStateMsg
from builtin_interfaces.msg import Time
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import PoseStamped, TwistStamped, WrenchStamped
from nav_msgs.msg import Odometry
from rclpy.node import Node

from boat_dynamics.physics.core.system import FleetForces, FleetState
from boat_dynamics.physics.scenario import BoatSpec
from boat_dynamics.physics.scenario.specs import SimulationSettings
from boat_dynamics.physics.wave_making.interaction import feels_made_waves
from boat_dynamics.physics.world.footprints import Footprints
from boat_dynamics.physics.world.obstacles import World
from boat_dynamics.ros.sensors import SensorPublisher, TransformPublisher
from boat_msgs_py import names
from boat_msgs_py.cdr import (
    FleetStateTemplate,
    FleetTemplate,
    diagnostic_array_cdr,
    odometry_template,
    pose_template,
    twist_template,
    wrench_template,
)
from boat_msgs_py.qos import DIAGNOSTICS_QOS, STATE_QOS
from boat_msgs_py.tap import SUBSCRIBER_CHECK_PERIOD, GraphWatch, Tap, TappedPublisher
from ocean_sim.physics.waves import WaveField

__all__ = ["FleetPublisher", "StartInterrupted"]

#: One status of /diagnostics: (name, level, message, ((key, value), ...)).
Status = tuple[str, int, str, tuple[tuple[str, str], ...]]


class StartInterrupted(RuntimeError):
    """The node was stopped (Ctrl-C) while it was being made."""


class FleetPublisher:
    """Every output topic of a fleet.

    Args:
        node: the dynamics node the publishers belong to.
        boats: the boats, in fleet order.
        sim: the simulation settings (``fleet_state``, the sensors' seed and rates).
        tap: the recorder's tap, or None.
        graph: wrench topics advertised once someone subscribes (None: all from the start).
        stopped: checked between boats: a large fleet's start-up stops on Ctrl-C (raises
            :class:`StartInterrupted`) instead of making every boat's publishers first.
        collisions: make every boat's wrench/collision (obstacles, or other boats).
        world: the obstacles the lidars see.
        footprints: the hulls the lidars see.
    """

    def __init__(self, node: Node, boats: Sequence[BoatSpec], sim: SimulationSettings,
                 tap: Tap | None, graph: GraphWatch | None,
                 stopped: Callable[[], bool] | None = None, collisions: bool = False,
                 world: World | None = None, footprints: Footprints | None = None) -> None:
        self.pubs: list[dict[str, TappedPublisher]] = []
        templates: list[dict] = []
        for i, spec in enumerate(boats):  # 36 ms a boat with 1000 (DDS endpoints)
            if stopped is not None and stopped():
                raise StartInterrupted(f"stopped while making boat {i} of {len(boats)}")
            self.pubs.append(_boat_publishers(node, spec, tap, graph, collisions,
                                              _feels_waves(boats, i)))
            templates.append(_boat_templates(spec, templates[-1] if templates else {}))
        self._diag_pub = TappedPublisher(node, DiagnosticArray, names.DIAGNOSTICS,
                                         DIAGNOSTICS_QOS, tap)
        # every boat's message of a kind packed in one pass
        self._fleet = {key: FleetTemplate([t[key] for t in templates])
                       for key in ("odom", "pose", "twist", "wrench")}
        self._odom = [p["odom"] for p in self.pubs]
        # every boat's wrench/<source> of every source, source after source, in one pass
        self._wrenches = FleetTemplate([t["wrench"] for _ in names.WRENCH_SOURCES
                                        for t in templates])
        # the optional topics: who wants them asked for the fleet at once
        self._topics = {key: _FleetTopic([(i, p[key]) for i, p in enumerate(self.pubs)
                                          if key in p])
                        for key in ("pose", "twist", *names.WRENCH_SOURCES,
                                    names.CARRIAGE_WRENCH, names.COLLISION_WRENCH,
                                    names.MOORING_WRENCH, names.MADE_WAVES_WRENCH)}
        self._state_pub, self._state = None, None  # every boat in one message
        if sim.fleet_state:
            self._state_pub = TappedPublisher(node, FleetStateMsg, names.FLEET_STATE,
                                              STATE_QOS, tap)
            self._state = FleetStateTemplate(names.WORLD_FRAME, [b.name for b in boats])
        self.transforms = TransformPublisher(node, list(boats), tap, sim.frames)
        self.sensors = SensorPublisher(node, list(boats), sim, tap, world, footprints)

    def states(self, sec: int, nanosec: int, values: np.ndarray, now: float,
               publish_tf: bool) -> None:
        """The odometry of every boat; pose, twist, fleet state and /tf for who wants them.

        Args:
            sec: stamp, s part.
            nanosec: stamp, ns part.
            values: (B, 13) each boat's reference point (m, world), orientation (x, y, z, w),
                its velocity (m/s, body frame) and angular velocity (rad/s, body frame).
            now: s, time.monotonic().
            publish_tf: publish /tf too.
        """
        for pub, data in zip(self._odom, self._fleet["odom"].pack(sec, nanosec, values),
                             strict=True):
            pub.publish(data)  # always
        if self._state_pub is not None:
            self._state_pub.publish(self._state.pack(sec, nanosec, values[:, :7],
                                                     values[:, 7:]))
        for key, columns in (("pose", values[:, :7]), ("twist", values[:, 7:])):
            self._publish_wanted(key, key, sec, nanosec, columns, now)
        if publish_tf:
            self.transforms.publish(sec, nanosec, values[:, :7], now,
                                    self._odometry_poses(values[:, :7]))

    def _odometry_poses(self, truth: np.ndarray) -> np.ndarray | None:
        """(B, 7) each boat's pose in its odom frame: its drifting odometry's, else the truth."""
        poses = self.sensors.odometry_poses(truth.shape[0])
        if poses is None:
            return None
        return np.where(np.isnan(poses[:, :1]), truth, poses)

    def wrenches(self, sec: int, nanosec: int, forces: FleetForces, now: float,
                 carriage: Callable[[int], np.ndarray] | None) -> None:
        """wrench/<source> of every boat that wants it, and wrench/carriage of towed ones.

        Args:
            sec: stamp, s part.
            nanosec: stamp, ns part.
            forces: the forces that acted during the last step.
            now: s, time.monotonic().
            carriage: boat index -> (6,) its carriage's force (N) and moment (N m), body frame,
                or None: no carriage has acted yet.
        """
        wanted = [(k, pubs) for k, source in enumerate(names.WRENCH_SOURCES)
                  if (pubs := self._topics[source].wanted(now))]
        if wanted:  # every source packed at once: row k B + i is source k of boat i
            every = [getattr(forces, source) for source in names.WRENCH_SOURCES]
            values = np.concatenate([np.stack([w.force for w in every]),
                                     np.stack([w.torque for w in every])], axis=2)
            packed = self._wrenches.pack(sec, nanosec, values.reshape(-1, 6))
            for k, pubs in wanted:
                for i, pub in pubs:
                    pub.publish(packed[k * len(self.pubs) + i])
        if carriage is not None:
            self._boat_wrenches(names.CARRIAGE_WRENCH, sec, nanosec, now, carriage)
        self._boat_wrenches(names.COLLISION_WRENCH, sec, nanosec, now, lambda i: np.concatenate(
            [forces.collision.force[i], forces.collision.torque[i]]))
        self._boat_wrenches(names.MOORING_WRENCH, sec, nanosec, now, lambda i: np.concatenate(
            [forces.mooring.force[i], forces.mooring.torque[i]]))
        self._boat_wrenches(names.MADE_WAVES_WRENCH, sec, nanosec, now, lambda i: np.concatenate(
            [forces.made_waves.force[i], forces.made_waves.torque[i]]))

    def _boat_wrenches(self, key: str, sec: int, nanosec: int, now: float,
                       value: Callable[[int], np.ndarray]) -> None:
        """wrench/<key> of every boat that has it and wants it (see :meth:`wrenches`).

        ``value``: boat index -> (6,) force (N) and moment (N m), body frame.
        """
        wanted = self._topics[key].wanted(now)
        if wanted:
            values = np.zeros((len(self.pubs), 6))
            for i, _ in wanted:
                values[i] = value(i)
            packed = self._fleet["wrench"].pack(sec, nanosec, values)
            for i, pub in wanted:
                pub.publish(packed[i])

    def diagnostics(self, sec: int, nanosec: int, statuses: Sequence[Status]) -> None:
        """/diagnostics: one status per boat."""
        self._diag_pub.publish(diagnostic_array_cdr(sec, nanosec, statuses))

    def sensor_readings(self, due: Callable[[float], bool], sec: int, nanosec: int,
                        center_of_mass: np.ndarray, before: FleetState,
                        after: FleetState, depth: float = math.inf,
                        sea: WaveField | None = None) -> None:
        """Every sensor whose rate is ``due`` (:meth:`SensorPublisher.publish_due`), stamped.

        ``depth``: m, the ocean's (depth sounders); ``sea``: the waves (lidars).
        """
        if len(self.sensors):
            self.sensors.publish_due(due, Time(sec=sec, nanosec=nanosec), center_of_mass,
                                     before, after, depth, sea)

    def _publish_wanted(self, topic_key: str, template_key: str, sec: int, nanosec: int,
                        values: np.ndarray, now: float) -> None:
        """A topic of every boat that wants it (subscribed or recorded), packed in one pass.

        Args:
            topic_key: the boats' publisher (``pose``, a wrench source).
            template_key: their fleet template (``pose``, ``wrench``).
            sec: stamp, s part.
            nanosec: stamp, ns part.
            values: (B, F) float64 fields of every boat.
            now: s, time.monotonic().
        """
        wanted = self._topics[topic_key].wanted(now)
        if wanted:
            packed = self._fleet[template_key].pack(sec, nanosec, values)
            for i, pub in wanted:
                pub.publish(packed[i])


class _FleetTopic:
    """One optional topic of every boat that has it, and which of them want a message now.

    Whether a boat's publisher wants one (:meth:`TappedPublisher.wanted`) is asked for the
    whole fleet at once, at most every :data:`SUBSCRIBER_CHECK_PERIOD` s: a publisher asks
    its subscriber count, and a graph watch the graph, that often anyway, so the answers are
    the same; a step in between costs no call per boat.

    Args:
        pubs: (boat index, its publisher of the topic), in fleet order.
    """

    def __init__(self, pubs: list[tuple[int, TappedPublisher]]) -> None:
        self._pubs = pubs
        self._wanted: list[tuple[int, TappedPublisher]] = []
        self._next_check = -math.inf

    def wanted(self, now: float) -> list[tuple[int, TappedPublisher]]:
        """(boat index, publisher) of the boats whose message is worth building.

        Args:
            now: s, the wall clock (time.monotonic()).
        """
        if now >= self._next_check:
            self._wanted = [(i, pub) for i, pub in self._pubs if pub.wanted(now)]
            self._next_check = now + SUBSCRIBER_CHECK_PERIOD
        return self._wanted


def _moored(params) -> bool:
    """Whether a boat is held by a line (``anchor_line``) or a soft mooring (``mooring``)."""
    soft = params.mooring is not None or (params.derive is not None
                                          and params.derive.mooring_period is not None)
    return soft or params.anchor_line is not None


def _feels_waves(boats: Sequence[BoatSpec], i: int) -> bool:
    """Whether boat i feels the waves other boats make (:mod:`.interaction`).

    It has coefficients (a file, or an estimate to be made) and another boat makes waves.
    """
    return feels_made_waves(boats[i].params) and any(
        j != i and b.params.made_waves != "none" for j, b in enumerate(boats))


def _boat_publishers(node: Node, spec: BoatSpec, tap: Tap | None, graph: GraphWatch | None,
                     collisions: bool, made_waves: bool) -> dict[str, TappedPublisher]:
    """One boat's publishers: odom, pose, twist, wrench/<source> (+ carriage, collision).

    wrench/carriage if the boat is towed; wrench/collision in a world with obstacles;
    wrench/mooring if it is moored (an anchor line, or a soft mooring); wrench/made_waves if
    it feels other boats' waves (``made_waves``).
    """
    pubs = {key: TappedPublisher(node, cls, names.boat_topic(spec.name, topic), STATE_QOS, tap)
            for key, cls, topic in (("odom", Odometry, names.ODOM),
                                    ("pose", PoseStamped, names.POSE),
                                    ("twist", TwistStamped, names.TWIST))}
    sources = [*names.WRENCH_SOURCES,
               *([names.CARRIAGE_WRENCH] if spec.params.carriage is not None else []),
               *([names.COLLISION_WRENCH] if collisions else []),
               *([names.MOORING_WRENCH] if _moored(spec.params) else []),
               *([names.MADE_WAVES_WRENCH] if made_waves else [])]
    for source in sources:
        pubs[source] = TappedPublisher(node, WrenchStamped, names.wrench_topic(spec.name, source),
                                       DIAGNOSTICS_QOS, tap, graph)
    return pubs


def _boat_templates(spec: BoatSpec, last: dict) -> dict:
    """One boat's message templates, the last boat's relabelled (CdrTemplate.relabel)."""
    child = names.child_frame(spec.name)
    return {"odom": odometry_template(names.WORLD_FRAME, child, last.get("odom")),
            "pose": pose_template(names.WORLD_FRAME, last.get("pose")),
            "twist": twist_template(child, last.get("twist")),
            "wrench": wrench_template(child, last.get("wrench"))}
