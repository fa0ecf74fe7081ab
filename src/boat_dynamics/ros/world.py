"""``/world/markers``: the scenario's fixed obstacles as a latched MarkerArray, once.

A prism is a TRIANGLE_LIST of its walls, from :data:`BASE` below the calm surface to its
top, and a LINE_STRIP round its top; a cylinder is a CYLINDER from the same base. Frame
``world`` (ENU), stamp zero (static: "the latest transform"), namespace ``obstacles``, ids
in scenario order (a prism's outline: its id + :data:`OUTLINE_ID`), so RViz and Foxglove
draw the world once they subscribe, however late.
"""

from __future__ import annotations

import numpy as np
from builtin_interfaces.msg import Time
from geometry_msgs.msg import Point
from rclpy.node import Node
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray

from boat_dynamics.physics.world.obstacles import Cylinder, Prism, World
from boat_msgs_py import names
from boat_msgs_py.qos import WORLD_QOS
from boat_msgs_py.tap import Tap, TappedPublisher

__all__ = ["BASE", "OUTLINE_ID", "WorldPublisher", "world_markers"]

#: m, world z: where the drawn obstacles start (they stand on the sea floor; drawn from here).
BASE = -2.0
#: A prism's outline marker's id: the prism's own plus this.
OUTLINE_ID = 100_000
_COLOR = ColorRGBA(r=0.55, g=0.5, b=0.45, a=1.0)
_EDGE = ColorRGBA(r=0.2, g=0.2, b=0.2, a=1.0)


class WorldPublisher:
    """Publishes ``/world/markers`` once (latched), if the world has obstacles.

    Args:
        node: the owning node.
        world: the scenario's obstacles.
        tap: the recorder's tap, or None.
    """

    def __init__(self, node: Node, world: World, tap: Tap | None) -> None:
        self._world = world
        self._pub = (TappedPublisher(node, MarkerArray, names.WORLD_MARKERS, WORLD_QOS, tap)
                     if world.obstacles else None)

    def publish(self) -> None:
        """The markers (nothing without obstacles)."""
        if self._pub is not None:
            self._pub.publish(world_markers(self._world))


def world_markers(world: World) -> MarkerArray:
    """Every obstacle of ``world`` as markers (module docs)."""
    out = []
    for k, o in enumerate(world.obstacles):
        if isinstance(o, Prism):
            out += [_walls(k, o), _outline(k, o)]
        else:
            out.append(_cylinder(k, o))
    return MarkerArray(markers=out)


def _marker(k: int, kind: int, color: ColorRGBA) -> Marker:
    m = Marker(type=kind, action=Marker.ADD, ns="obstacles", id=k, color=color)
    m.header.frame_id = names.WORLD_FRAME
    m.header.stamp = Time()
    m.pose.orientation.w = 1.0
    m.scale.x = m.scale.y = m.scale.z = 1.0
    return m


def _walls(k: int, prism: Prism) -> Marker:
    """The prism's walls: two triangles per edge, from :data:`BASE` to its top."""
    m = _marker(k, Marker.TRIANGLE_LIST, _COLOR)
    a = prism.points
    b = np.roll(a, -1, axis=0)
    low, high = min(BASE, prism.top), prism.top
    for (x0, y0), (x1, y1) in zip(a.tolist(), b.tolist(), strict=True):
        quad = [Point(x=x0, y=y0, z=low), Point(x=x1, y=y1, z=low),
                Point(x=x1, y=y1, z=high), Point(x=x0, y=y0, z=high)]
        m.points += [quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]]
    return m


def _outline(k: int, prism: Prism) -> Marker:
    """A closed line round the prism's top."""
    m = _marker(k + OUTLINE_ID, Marker.LINE_STRIP, _EDGE)
    m.scale.x = 0.05  # m, the line's width
    ring = [*prism.points.tolist(), prism.points[0].tolist()]
    m.points = [Point(x=x, y=y, z=prism.top) for x, y in ring]
    return m


def _cylinder(k: int, cylinder: Cylinder) -> Marker:
    """The cylinder from :data:`BASE` to its top."""
    m = _marker(k, Marker.CYLINDER, _COLOR)
    low = min(BASE, cylinder.top)
    m.pose.position = Point(x=float(cylinder.center[0]), y=float(cylinder.center[1]),
                            z=0.5 * (low + cylinder.top))
    m.scale.x = m.scale.y = 2.0 * cylinder.radius
    m.scale.z = max(cylinder.top - low, 1e-3)
    return m
