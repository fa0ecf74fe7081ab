"""Force + torque pairs, the common currency of the force models.

Every force model returns a :class:`Wrench`: force and torque about the centre of mass, both in
the body frame (FLU), which is what the ``wrench/<source>`` topics publish.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ZERO_WRENCH", "Real", "Wrench", "cross", "per_element", "sum_by_owner", "wrench_at"]

#: A numeric parameter of a force model: a float for one boat, or a (G,) array when the
#: parameters of a group of G boats are stacked (:class:`boat_dynamics.physics.core.system.Group`).
#: The force models broadcast over both.
Real = float | np.ndarray


def _levi_civita() -> np.ndarray:
    """(3, 3, 3) eps with (a x b)_i = sum_jk eps[i, j, k] a_j b_k."""
    eps = np.zeros((3, 3, 3))
    for i, j, k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        eps[i, j, k], eps[i, k, j] = 1.0, -1.0
    return eps


_LEVI_CIVITA = _levi_civita()


def cross(a: np.ndarray, b: np.ndarray, axis: int = -1) -> np.ndarray:
    """Cross product of (..., 3) arrays (broadcasting), without numpy.cross's axis handling.

    numpy.cross costs about 10 us per call in its argument handling, more than the arithmetic
    on the few vectors of a boat step. Up to 50 vectors, one einsum with the Levi-Civita
    tensor (5 us for 10, measured); beyond, six products written out (13 us for 240, where
    the einsum takes 35 us). Both round the same way: the results are identical.

    Args:
        a: vectors along ``axis``.
        b: vectors along ``axis`` (broadcast against ``a``).
        axis: -1 for (..., 3) arrays, 0 for coordinate-major (3, ...) arrays (the mesh
            model's layout; the result keeps it).
    """
    if axis == -1 and max(a.size, b.size) <= 150:
        return np.einsum("ijk,...j,...k->...i", _LEVI_CIVITA, a, b)
    if axis == 0:
        def part(x, i):
            return x[i]
    elif axis == -1:
        def part(x, i):
            return x[..., i]
    else:
        raise ValueError(f"axis {axis} is not allowed: -1 or 0")
    a0, a1, a2 = part(a, 0), part(a, 1), part(a, 2)
    b0, b1, b2 = part(b, 0), part(b, 1), part(b, 2)
    out = np.empty(np.broadcast_shapes(np.shape(a), np.shape(b)))
    part(out, 0)[...] = a1 * b2 - a2 * b1
    part(out, 1)[...] = a2 * b0 - a0 * b2
    part(out, 2)[...] = a0 * b1 - a1 * b0
    return out


@dataclass(frozen=True)
class Wrench:
    """Force (N) and torque (N m) about the centre of mass, body frame.

    Attributes:
        force: (3,) N.
        torque: (3,) N m.
    """

    force: np.ndarray
    torque: np.ndarray

    def __add__(self, other: Wrench) -> Wrench:
        return Wrench(self.force + other.force, self.torque + other.torque)


ZERO_WRENCH = Wrench(np.zeros(3), np.zeros(3))


def wrench_at(forces: np.ndarray, points: np.ndarray) -> Wrench:
    """Sum of forces applied at points, as a wrench about the centre of mass.

    Args:
        forces: (N, 3) or (3,) N, body frame.
        points: (N, 3) or (3,) m, application points relative to the centre of mass, body frame.

    Returns:
        The wrench: sum of forces, and sum of r x F.
    """
    f = np.atleast_2d(forces)
    r = np.atleast_2d(points)
    return Wrench(f.sum(axis=0), cross(r, f).sum(axis=0))


def per_element(value, owner: np.ndarray):
    """A per-boat parameter ((B,) array) for each element via ``owner`` (T,), or a scalar.

    A scalar (shared by all boats) is returned as it is.
    """
    return np.asarray(value)[owner] if np.ndim(value) else value


def sum_by_owner(values: np.ndarray, owner: np.ndarray, count: int) -> np.ndarray:
    """Per-boat sums of per-element rows: out[b] = sum of values[i] with owner[i] == b.

    Args:
        values: (T, K) per-element quantities (triangles, sample points).
        owner: (T,) int, the boat of each element, in [0, count).
        count: number of boats.

    Returns:
        (count, K) sums (zero for a boat with no element); one compiled pass
        (:func:`boat_dynamics.physics.body.owner_kernel.sum_by_owner_f64`).
    """
    from boat_dynamics.physics.body.owner_kernel import sum_by_owner_f64  # numba: when used

    return sum_by_owner_f64(np.ascontiguousarray(values, dtype=float), owner, count)
