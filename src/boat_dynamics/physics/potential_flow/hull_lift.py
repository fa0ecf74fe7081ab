"""The hull's lift at speed: the sway momentum its trailing section leaves in the wake.

Slender-body theory gives each section of a hull moving ahead at U and across at
V(x) = v + x r the lateral force f(x) = U d(a22 V)/dx (a22(x) the section's sway added mass,
steady flow, Newman 1977, "Marine Hydrodynamics", sec. 7.8). Integrated from a bow where a22
starts at zero, its moment is the Munk moment -U integral(a22 V) dx, which the added mass's
Coriolis and centripetal forces already apply (:mod:`.added_mass`), and its force is zero
unless the flow leaves the hull before a22 returns to zero: at a transom, a skeg or any
trailing edge with draft the flow separates (the Kutta condition of Jones's slender-wing
theory, 1946), and the momentum a22(x_t) V(x_t) of the trailing section goes into the wake
every second. That is the force::

    Y = -|U| a22(x_t) (v + x_t r),  acting at x_t,

x_t the trailing end (the stern going ahead, the bow going astern). With the Munk moment it
makes the hull's linear manoeuvring derivatives; for a prismatic hull (a22 = A22 / L, x_t =
-L/2): Y_v = -U A22 / L, N_v = -U A22 / 2 (half the Munk moment), Y_r = U A22 / 2,
N_r = -U A22 L / 4, the leading terms of Clarke, Gedling & Hine's (1983) regression of
towing-tank derivatives (Y'_v = -pi (T/L)^2, N'_v = -pi (T/L)^2 / 2, Y'_r = pi (T/L)^2 / 2,
N'_r = -pi (T/L)^2 / 4, with a22 = rho pi T^2 / 2). It is what keeps a hull without a rudder
from turning broadside, which the Munk moment alone does. It is a scenario's choice
(``hydrodynamics.hull_lift``), off by default: for hulls as wide as the shipped boxes (L/B 2,
B/T 4) Clarke's regression gives about half this yaw damping (docs/DESIGN.md).

a22(x) is taken proportional to the square of the section's draft (a flat plate's sway added
mass, rho pi T^2 / 2 with its image in the free surface) and scaled so that it integrates to
the potential-flow A22 of the hull's coefficients (:func:`trailing_sections`); the demihulls of
a catamaran are taken alike. Left out, stated: the vertical analogue (heave and pitch at a
transom), and the viscous cross-flow (the damping's quadratic terms).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.body.clip import clip_parts
from boat_dynamics.physics.body.hull import HullMesh
from boat_dynamics.physics.body.wrench import Wrench, cross

__all__ = ["HULL_LIFT_MODELS", "STATIONS", "HullLift", "HullLiftModel", "draft_profile",
           "hull_lift", "trailing_sections"]

#: ``trailing_edge``: the trailing section's lift (module docstring); ``none``: the Munk
#: moment alone (a hull whose flow leaves no trailing edge).
HullLiftModel = Literal["trailing_edge", "none"]
HULL_LIFT_MODELS: tuple[HullLiftModel, ...] = get_args(HullLiftModel)

#: Stations along the wetted length on which the draft profile is taken.
STATIONS = 20


@dataclass(frozen=True)
class HullLift:
    """The hull's two trailing sections (the stern's going ahead, the bow's going astern).

    Attributes:
        added_mass: (2,) kg/m, a22 of the aft and the fore end section.
        position: (2, 3) m, body frame from the hull reference point: where each end's force
            acts (the end of the wetted length, on the centre line, at half the section's
            draft).
    """

    added_mass: np.ndarray
    position: np.ndarray


def draft_profile(mesh: HullMesh, height: float, stations: int = STATIONS
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The wetted hull's lateral profile, station by station.

    Args:
        mesh: the hull, body frame (outward triangles).
        height: m, the hull reference point's height above the calm water, upright.
        stations: how many equal stations between the wetted hull's ends.

    Returns:
        (stations + 1,) m, the stations' edges along x; (stations,) m, the mean projected
        side area (the +y facing surface) per metre of each station: the draft for one hull,
        the sum of the drafts for alike demihulls; (2,) m, the draft of the aft and the fore
        end station (from the waterline to its deepest wetted point).
    """
    xyz = np.transpose(mesh.vertices[mesh.faces], (2, 1, 0))  # (3 coord, 3 corner, F)
    wet, _, _, _ = clip_parts(xyz, -(xyz[2] + height))
    if wet.shape[2] == 0:
        raise ValueError(f"the hull is out of the water at height {height} m")
    edges = np.linspace(wet[0].min(), wet[0].max(), stations + 1)
    aft_of = np.array([_side_area(wet, x - wet[0]) for x in edges])
    aft, _, _, _ = clip_parts(wet, edges[1] - wet[0])
    fore, _, _, _ = clip_parts(wet, wet[0] - edges[-2])
    ends = np.array([-height - aft[2].min(), -height - fore[2].min()])
    return edges, np.diff(aft_of) / np.diff(edges), ends


def _side_area(wet: np.ndarray, inside: np.ndarray) -> float:
    """m^2, the +y facing projected area of the parts of ``wet`` where ``inside`` > 0."""
    parts, _, _, _ = clip_parts(wet, inside)
    a, b, c = parts[:, 0], parts[:, 1], parts[:, 2]
    return float(np.maximum(0.5 * np.cross(b - a, c - a, axis=0)[1], 0.0).sum())


def trailing_sections(mesh: HullMesh, height: float, sway_added_mass: float) -> HullLift:
    """The end sections' a22 (module docstring) of a hull whose potential-flow A22 is given.

    Args:
        mesh: the hull, body frame.
        height: m, the hull reference point's height above the calm water, upright.
        sway_added_mass: A22, kg (infinite frequency).
    """
    edges, side, ends = draft_profile(mesh, height)
    weight = side * side
    a22 = sway_added_mass * weight / float(np.sum(weight * np.diff(edges)))
    position = np.array([[edges[0], 0.0, -height - ends[0] / 2.0],
                         [edges[-1], 0.0, -height - ends[1] / 2.0]])
    return HullLift(a22[[0, -1]], position)


def hull_lift(added_mass: np.ndarray, position: np.ndarray, velocity: np.ndarray,
              angular_velocity: np.ndarray, center_of_mass: np.ndarray) -> Wrench:
    """The lift of B hulls' trailing sections, about their centres of mass (module docstring).

    Args:
        added_mass: (B, 2) kg/m, a22 of the aft and fore end sections (zero: no lift).
        position: (B, 2, 3) m, body frame from the hull reference point: the end sections.
        velocity: (B, 3) m/s, body frame, through the water (the current taken off).
        angular_velocity: (B, 3) rad/s, body frame.
        center_of_mass: (B, 3) m, body frame from the hull reference point.

    Returns:
        (B, 3) N and (B, 3) N m, body frame: a side force at the trailing end.
    """
    u = velocity[:, 0]
    end = (u < 0.0).astype(np.intp)  # going astern the bow trails
    rows = np.arange(u.shape[0])
    at = position[rows, end] - center_of_mass
    w = angular_velocity
    cross_flow = velocity[:, 1] + w[:, 2] * at[:, 0] - w[:, 0] * at[:, 2]  # (v + w x p)_y
    force = np.zeros_like(velocity)
    force[:, 1] = -np.abs(u) * added_mass[rows, end] * cross_flow
    return Wrench(force, cross(at, force))
