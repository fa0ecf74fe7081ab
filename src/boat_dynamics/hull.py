"""Hull geometry: the box hull and its sample-point layouts.

Body frame FLU (x forward, y left, z up) with the origin at the hull reference point, the
centre of the hull's bounding box (DESIGN.md, "Conventions").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["BoxHull"]


@dataclass(frozen=True)
class BoxHull:
    """A rectangular box hull.

    Attributes:
        length: along x, m, > 0.
        beam: along y, m, > 0.
        height: along z, m, > 0.

    """

    length: float
    beam: float
    height: float

    @property
    def volume(self) -> float:
        """Enclosed volume, m^3."""
        return self.length * self.beam * self.height

    @property
    def waterplane_area(self) -> float:
        """Area of the horizontal section when floating upright, m^2."""
        return self.length * self.beam

    def solid_inertia(self, mass: float) -> np.ndarray:
        """Principal moments of a solid box of ``mass`` kg about its centre, (3,) kg m^2.

        I_xx = m (B^2 + H^2) / 12, I_yy = m (L^2 + H^2) / 12, I_zz = m (L^2 + B^2) / 12.
        """
        lsq, bsq, hsq = self.length**2, self.beam**2, self.height**2
        return mass / 12.0 * np.array([bsq + hsq, lsq + hsq, lsq + bsq])

    def bottom_grid(self, nx: int, ny: int) -> np.ndarray:
        """Cell centres of an nx x ny grid on the hull bottom, (nx * ny, 3) m, body frame.

        Each point stands for an equal share of the bottom area, so columns of water above
        the points add up to the displaced volume of the box exactly in flat water.
        """
        xs = (np.arange(nx) + 0.5) / nx * self.length - self.length / 2
        ys = (np.arange(ny) + 0.5) / ny * self.beam - self.beam / 2
        gx, gy = np.meshgrid(xs, ys, indexing="ij")
        return np.stack([gx.ravel(), gy.ravel(), np.full(nx * ny, -self.height / 2)], axis=1)
