"""Per-boat gathers and sums over elements (vertices, triangles, points), compiled.

A group of boats keeps the elements of all its hulls in one array, each with its boat
(``owner``). These kernels move elements to the world frame and add them up per boat in one
pass, where numpy needed a gather of (E, 3, 3) rotations and an einsum, or a 0/1 matrix
product, per call. The tests' oracles: ``_to_world_numpy`` (the einsum the step used) and
numpy's ``np.add.at``.
"""

from __future__ import annotations

import time

import numpy as np

from ocean_sim.physics.jit import kernel

__all__ = ["sum_by_owner_f64", "to_world_f64", "warm", "weighted_mean_by_owner_f64"]


@kernel
def to_world_f64(rotation, reference, owner, body):  # pragma: no cover  (compiled)
    """World positions of body-frame elements: p = r_o + R_o b.

    Args:
        rotation: (G, 3, 3) body-to-world rotations of the group's boats.
        reference: (G, 3) m, the boats' body origins (hull reference points), world frame.
        owner: (E,) int, the boat (0..G-1) of each element.
        body: (E, 3) m, the elements' positions, body frames.

    Returns:
        (E, 3) m, world frame.
    """
    out = np.empty((owner.shape[0], 3))
    for e in range(owner.shape[0]):
        o = owner[e]
        b0, b1, b2 = body[e, 0], body[e, 1], body[e, 2]
        for i in range(3):
            out[e, i] = reference[o, i] + (rotation[o, i, 0] * b0 + rotation[o, i, 1] * b1
                                           + rotation[o, i, 2] * b2)
    return out


@kernel
def sum_by_owner_f64(values, owner, count):  # pragma: no cover  (compiled)
    """(count, K) per-boat sums of (T, K) per-element rows (zero for a boat with none).

    Args:
        values: (T, K) per-element quantities.
        owner: (T,) int, the boat of each element, in [0, count).
        count: number of boats.
    """
    out = np.zeros((count, values.shape[1]))
    for t in range(owner.shape[0]):
        o = owner[t]
        for k in range(values.shape[1]):
            out[o, k] += values[t, k]
    return out


@kernel
def weighted_mean_by_owner_f64(values, weights, owner, fallback
                               ):  # pragma: no cover  (compiled)
    """(G, 3) per-boat weighted means of (T, 3) rows; ``fallback`` (G, 3) for a boat with none.

    Args:
        values: (T, 3) per-element vectors.
        weights: (T,) their weights (areas, or 1), >= 0.
        owner: (T,) int, the boat of each element, in [0, G).
        fallback: (G, 3), the value of a boat whose weights sum to 0.
    """
    count = fallback.shape[0]
    sums, total = np.zeros((count, 3)), np.zeros(count)
    for t in range(owner.shape[0]):
        o, w = owner[t], weights[t]
        for k in range(3):
            sums[o, k] += values[t, k] * w
        total[o] += w
    out = np.empty((count, 3))
    for o in range(count):
        for k in range(3):
            out[o, k] = sums[o, k] / total[o] if total[o] > 0.0 else fallback[o, k]
    return out


def _to_world_numpy(rotation: np.ndarray, reference: np.ndarray, owner: np.ndarray,
                    body: np.ndarray) -> np.ndarray:
    """:func:`to_world_f64` in numpy (the kernel's oracle)."""
    return reference[owner] + np.einsum("eij,ej->ei", rotation[owner], body)


def warm() -> float:
    """Compile (or load from the cache) this module's kernels; returns the s it took."""
    start = time.perf_counter()
    owner = np.zeros(2, dtype=np.intp)
    to_world_f64(np.eye(3)[None], np.zeros((1, 3)), owner, np.ones((2, 3)))
    sum_by_owner_f64(np.ones((2, 3)), owner, 1)
    weighted_mean_by_owner_f64(np.ones((2, 3)), np.ones(2), owner, np.zeros((1, 3)))
    return time.perf_counter() - start
