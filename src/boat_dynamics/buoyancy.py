"""Sample-point buoyancy, derived from density (no tuned spring).

Each of N points stands at the bottom of a vertical column of the hull and carries an equal
share V / N of the hull's volume V = mass / density. Submerged by ``d`` (surface height above
the point), it carries the weight of the water its column displaces::

    F_i = rho g (V / N) clamp(d_i / max_depth, 0, 1)   (world +z)

applied at the centre of the submerged part of the column (``d / 2`` above the point), so a box
with a grid of points has its true centre of buoyancy and metacentric height. Equilibrium:
sum F_i = m g  gives  draft / height = m / (rho V) = density / rho, whatever the mass.

Source: the seed notes (../shared/seed/boat-on-gerstner-waves.txt, "Sample-Point / Voxel
Buoyancy", "derive everything from density", "clamp submersion depth"); Archimedes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.wrench import Wrench, wrench_at

__all__ = ["SamplePointBuoyancy", "sample_point_buoyancy"]


@dataclass(frozen=True)
class SamplePointBuoyancy:
    """Parameters of the sample-point model.

    Attributes:
        points: (N, 3) m, column bottoms in the body frame (relative to the hull reference point).
        volume: V, m^3, volume displaced when every column is fully submerged (mass / density).
        max_depth: m, submersion at which a column is full (the hull height for a box).

    """

    points: np.ndarray
    volume: float
    max_depth: float


def sample_point_buoyancy(
    model: SamplePointBuoyancy,
    depths: np.ndarray,
    rotation: np.ndarray,
    center_of_mass: np.ndarray,
    water_density: float,
    gravity: float,
) -> Wrench:
    """Buoyancy wrench of the sample points.

    Args:
        model: the sample-point parameters.
        depths: (N,) m, surface height minus point height at each point (> 0 = submerged).
        rotation: (3, 3) body-to-world rotation matrix.
        center_of_mass: (3,) m, body frame, relative to the hull reference point.
        water_density: rho, kg/m^3.
        gravity: g, m/s^2.

    Returns:
        The buoyancy wrench about the centre of mass, body frame.

    """
    n = model.points.shape[0]
    submerged = np.clip(depths, 0.0, model.max_depth)
    magnitude = water_density * gravity * (model.volume / n) * (submerged / model.max_depth)
    forces = magnitude[:, None] * rotation[2, :]  # world +z expressed in the body frame
    arms = model.points - center_of_mass
    arms[:, 2] += submerged / 2.0
    return wrench_at(forces, arms)
