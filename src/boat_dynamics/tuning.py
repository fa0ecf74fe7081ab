"""Hydrostatic equilibrium, stiffness and the critical-damping helper.

Stiffnesses are measured from the boat's own buoyancy model in flat water (central differences
about the equilibrium), so they hold for any hull and either buoyancy model: for a box they
are rho g A_wp in heave and m g GM in roll and pitch. The critical damping of a DOF is
b_c = 2 sqrt(k m) (Source: the seed notes, "Damping"; Fossen (2011), sec. 4.3), with the mass
or moment of inertia of that DOF (rigid body plus added mass).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from boat_dynamics.boat import BoatInputs, BoatParams, evaluate_forces, initial_state
from boat_dynamics.rigid_body import rotation_matrix
from ocean_sim.waves import WaveField

__all__ = ["critical_damping", "equilibrium_height", "hydrostatic_stiffness"]

_FLAT = WaveField()


def _vertical_buoyancy(params: BoatParams, z: float, roll: float = 0.0,
                       pitch: float = 0.0) -> tuple[float, np.ndarray]:
    """World-vertical buoyancy force (N) and body torque (N m) with the reference point at z."""
    state = initial_state(params, [0.0, 0.0, z], roll=roll, pitch=pitch)
    f = evaluate_forces(params, state, BoatInputs(), _FLAT).buoyancy
    return float((rotation_matrix(state.orientation) @ f.force)[2]), f.torque


def equilibrium_height(params: BoatParams) -> float:
    """Height z (m) of the hull reference point where buoyancy carries the weight, upright.

    Bisection over the hull's height in flat water. Raises ValueError for a hull that sinks.
    """
    weight = params.mass * params.gravity
    half = params.hull.height / 2
    low, high = -half, half  # fully submerged .. just touching
    if _vertical_buoyancy(params, low)[0] < weight:
        raise ValueError(f"the hull sinks: fully submerged buoyancy is less than its weight "
                         f"{weight:.4g} N (density above the water's?)")
    for _ in range(60):
        mid = 0.5 * (low + high)
        if _vertical_buoyancy(params, mid)[0] > weight:
            low = mid
        else:
            high = mid
    return 0.5 * (low + high)


def hydrostatic_stiffness(params: BoatParams) -> np.ndarray:
    """(3,) heave N/m, roll and pitch N m/rad restoring stiffness at the upright equilibrium."""
    z0 = equilibrium_height(params)
    dz = 1e-3 * params.hull.height
    da = 1e-3
    k_heave = -(_vertical_buoyancy(params, z0 + dz)[0]
                - _vertical_buoyancy(params, z0 - dz)[0]) / (2 * dz)
    k_roll = -(_vertical_buoyancy(params, z0, roll=da)[1][0]
               - _vertical_buoyancy(params, z0, roll=-da)[1][0]) / (2 * da)
    k_pitch = -(_vertical_buoyancy(params, z0, pitch=da)[1][1]
                - _vertical_buoyancy(params, z0, pitch=-da)[1][1]) / (2 * da)
    return np.array([k_heave, k_roll, k_pitch])


def critical_damping(params: BoatParams, ratios: np.ndarray) -> np.ndarray:
    """Linear damping (6,) giving damping ratios zeta = [heave, roll, pitch] (surge/sway/yaw 0).

    b = zeta * 2 sqrt(k m) per DOF, k from :func:`hydrostatic_stiffness`, m the rigid-body
    mass or inertia plus added mass. A DOF with no restoring stiffness (k <= 0: unstable in
    roll, say) gets no damping from here.
    """
    k = hydrostatic_stiffness(replace(params, damping_linear=np.zeros(6)))
    m = np.array([params.mass + params.added_mass[2], params.inertia[0] + params.added_mass[3],
                  params.inertia[1] + params.added_mass[4]])
    b = np.asarray(ratios, dtype=float) * 2.0 * np.sqrt(np.maximum(k, 0.0) * m)
    out = np.zeros(6)
    out[[2, 3, 4]] = b
    return out
