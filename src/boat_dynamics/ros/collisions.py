"""``<boat>/collision``: a boat's contact with an obstacle or a boat began or ended.

Events, not a stream: each physics step the node hands the step to :meth:`CollisionEvents.
observe`, which looks for contacts only while some boat is pushed by an obstacle or was
touching one (:func:`boat_dynamics.physics.core.forces.touches_of`); a change of the
obstacle or boat a boat touches (the deepest, if several) is an event (boat_msgs/Collision),
published after the step, stamped with the time of the state it was found in. Nothing is
made for a lone boat in a world without obstacles.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from boat_msgs.msg import Collision
from builtin_interfaces.msg import Time
from geometry_msgs.msg import Point, Vector3
from rclpy.node import Node

from boat_dynamics.physics.core.forces import touches_of
from boat_dynamics.physics.core.pipeline import Step
from boat_dynamics.physics.core.system import FleetState, System
from boat_dynamics.physics.force_models.collision import Touches
from boat_dynamics.physics.scenario import BoatSpec
from boat_dynamics.physics.world.obstacles import World
from boat_msgs_py import names
from boat_msgs_py.qos import COLLISION_QOS
from boat_msgs_py.tap import GraphWatch, Tap, TappedPublisher

__all__ = ["CollisionEvents"]


class CollisionEvents:
    """Finds and publishes every boat's contact events.

    Args:
        node: the owning node.
        boats: the boats, in fleet order.
        world: the scenario's obstacles.
        tap: the recorder's tap, or None.
        graph: made when a subscriber appears, as the wrenches of a large fleet
            (``simulation.wrench_topics``); None: at start-up.
    """

    def __init__(self, node: Node, boats: list[BoatSpec], world: World,
                 tap: Tap | None, graph: GraphWatch | None = None) -> None:
        self._world = world
        self._names = [b.name for b in boats]
        self._pubs = ([TappedPublisher(node, Collision, names.boat_topic(b.name, names.COLLISION),
                                       COLLISION_QOS, tap, graph) for b in boats]
                      if world.obstacles or len(boats) > 1 else [])
        #: the names an event's ``other`` index means: the obstacles', then the boats'
        self._others = [o.name for o in world.obstacles] + self._names
        count = len(boats)
        self._last = Touches.empty(count)
        self._queued: list[tuple[float, int, Collision]] = []

    def restart(self) -> None:
        """A new episode: nothing touching, nothing queued (no end event for the last one)."""
        self._last.other[:] = -1
        self._queued.clear()

    def observe(self, system: System, state: FleetState, done: Step) -> None:
        """Queue the events of the step from ``state`` (``done``: that step's result)."""
        if not self._pubs:
            return
        pushed = np.any(done.forces.collision.force != 0.0, axis=1)
        if not pushed.any() and not np.any(self._last.other >= 0):
            return
        now = touches_of(system, state, done.contact, self._world)
        t = float(state.t)
        for i in np.flatnonzero(now.other != self._last.other):
            if self._last.other[i] >= 0:
                self._queued.append((t, int(i), self._message(int(i), self._last, False)))
            if now.other[i] >= 0:
                self._queued.append((t, int(i), self._message(int(i), now, True)))
        held = now.other >= 0  # the last contact's place: what an end event says
        for mine, new in ((self._last.point, now.point), (self._last.normal, now.normal),
                          (self._last.depth, now.depth),
                          (self._last.approach_speed, now.approach_speed)):
            mine[held] = new[held]
        self._last.other[:] = now.other

    def publish(self, stamp_ns: Callable[[float], int]) -> None:
        """Publish the queued events (``stamp_ns``: a state's time, s -> its stamp, ns)."""
        for t, i, msg in self._queued:
            sec, nanosec = divmod(stamp_ns(t), 1_000_000_000)
            msg.header.stamp = Time(sec=sec, nanosec=nanosec)
            self._pubs[i].publish(msg)
        self._queued.clear()

    def _message(self, i: int, touch: Touches, touching: bool) -> Collision:
        """Boat ``i``'s event from ``touch`` (its stamp is set when published)."""
        msg = Collision(boat=self._names[i], other=self._others[touch.other[i]],
                        touching=touching, depth=float(touch.depth[i]),
                        approach_speed=float(touch.approach_speed[i]))
        msg.header.frame_id = names.WORLD_FRAME
        x, y, z = touch.point[i].tolist()
        msg.point = Point(x=x, y=y, z=z)
        nx, ny, nz = touch.normal[i].tolist()
        msg.normal = Vector3(x=nx, y=ny, z=nz)
        return msg
