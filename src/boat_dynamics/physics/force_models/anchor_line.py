"""An anchor line: an elastic line from an anchor on the sea floor to a point on the hull.

How a navigation buoy or an anchored boat is held: the line hangs slack while the hull is
within its reach (the watch circle) and pulls when stretched. Modelled as a massless elastic
line that takes tension only (Faltinsen, "Sea Loads on Ships and Offshore Structures", 1990,
sec. 8.2, the elastic cable without weight; OrcaFlex's "link" of a linear spring): with d the
distance from the anchor to the fairlead and L the line's unstretched length,

    T = max(0, k (d - L) + c d'),   only while d > L,

along the line from the fairlead towards the anchor, at the fairlead (so it also heels the
hull). k = EA / L for a line of axial stiffness EA; c damps the line's stretch. A chain's
catenary (its weight lifting off the floor) is left out: its restoring force grows from zero
as this one does, but smoothly, where this one starts at the watch circle's edge.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.wrench import Real, Wrench

__all__ = ["AnchorLine", "anchor_line_wrench", "line_tension"]


@dataclass(frozen=True)
class AnchorLine:
    """One hull's anchor line (stacked: each field gains a first axis of the boats).

    Attributes:
        anchor: (3,) m, world frame: where the line is made fast on the sea floor.
        fairlead: (3,) m, body frame, from the hull reference point: where it meets the hull.
        length: m, > 0, unstretched.
        stiffness: N/m, > 0 (EA / length).
        damping: N s/m, >= 0, on the line's rate of stretch.
    """

    anchor: np.ndarray
    fairlead: np.ndarray
    length: Real
    stiffness: Real
    damping: Real


def line_tension(distance: np.ndarray, rate: np.ndarray, length: np.ndarray,
                 stiffness: np.ndarray, damping: np.ndarray) -> np.ndarray:
    """(B,) N: T = max(0, k (d - L) + c d') where d > L, else 0 (a slack line).

    Args:
        distance: (B,) m, anchor to fairlead.
        rate: (B,) m/s, d'.
        length: (B,) m, unstretched.
        stiffness: (B,) N/m.
        damping: (B,) N s/m.
    """
    taut = distance > length
    pull = stiffness * (distance - length) + damping * rate
    return np.where(taut, np.maximum(pull, 0.0), 0.0)


def anchor_line_wrench(lines: AnchorLine, position: np.ndarray, rotation: np.ndarray,
                       velocity: np.ndarray, angular_velocity: np.ndarray,
                       center_of_mass: np.ndarray) -> Wrench:
    """The lines' wrenches, body frames, about the centres of mass.

    Args:
        lines: B lines stacked (a boat without one: stiffness and damping 0).
        position: (B, 3) m, centres of mass, world frame.
        rotation: (B, 3, 3) body to world.
        velocity: (B, 3) m/s, of the centres of mass, body frame.
        angular_velocity: (B, 3) rad/s, body frame.
        center_of_mass: (B, 3) m, body frame.

    Returns:
        Force (B, 3) N and torque (B, 3) N m, body frames.
    """
    lever = lines.fairlead - center_of_mass
    fairlead = position + np.einsum("bij,bj->bi", rotation, lever)
    along = lines.anchor - fairlead  # world, fairlead to anchor
    distance = np.linalg.norm(along, axis=1)
    unit = along / np.maximum(distance, 1e-12)[:, None]
    point_velocity = velocity + np.cross(angular_velocity, lever)  # body frame
    world_velocity = np.einsum("bij,bj->bi", rotation, point_velocity)
    rate = -np.einsum("bi,bi->b", unit, world_velocity)  # d' > 0: moving away from the anchor
    tension = line_tension(distance, rate, lines.length, lines.stiffness, lines.damping)
    force = np.einsum("bji,bj->bi", rotation, tension[:, None] * unit)
    return Wrench(force, np.cross(lever, force))
