"""Rigid-body kinematics and integration: unit quaternions and a semi-implicit Euler step.

Quaternions are (x, y, z, w) arrays, as in ROS messages; they rotate body (FLU) vectors into
the world (ENU) frame. Linear and angular velocity in the state are body-frame quantities
(Fossen's nu), so the equations of motion about the centre of mass are::

    m (dv/dt + w x v) = F_body
    I dw/dt + w x (I w) = tau_body

Source: Fossen, "Handbook of Marine Craft Hydrodynamics and Motion Control" (2011),
eqs. 3.47-3.48 with the origin at the centre of mass; quaternion kinematics eq. 2.54.
"""

from __future__ import annotations

import numpy as np

from boat_dynamics.wrench import cross

__all__ = [
    "inertia_tensor",
    "integrate",
    "quat_from_euler",
    "quat_multiply",
    "quat_to_euler",
    "rotation_matrix",
]


def quat_multiply(q: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Hamilton product q * r of (..., 4) (x, y, z, w) quaternions (broadcasting)."""
    x1, y1, z1, w1 = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    x2, y2, z2, w2 = r[..., 0], r[..., 1], r[..., 2], r[..., 3]
    out = np.empty(np.broadcast_shapes(q.shape, r.shape))
    out[..., 0] = w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2
    out[..., 1] = w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2
    out[..., 2] = w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2
    out[..., 3] = w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2
    return out


def rotation_matrix(q: np.ndarray) -> np.ndarray:
    """(..., 3, 3) matrices R rotating body vectors into the world, from unit (x, y, z, w)."""
    x, y, z, w = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    xx, yy, zz = x * x, y * y, z * z
    xy, xz, yz, xw, yw, zw = x * y, x * z, y * z, x * w, y * w, z * w
    r = np.empty((*q.shape[:-1], 3, 3))  # filled in place: half the time of np.stack
    r[..., 0, 0], r[..., 0, 1], r[..., 0, 2] = 1 - 2 * (yy + zz), 2 * (xy - zw), 2 * (xz + yw)
    r[..., 1, 0], r[..., 1, 1], r[..., 1, 2] = 2 * (xy + zw), 1 - 2 * (xx + zz), 2 * (yz - xw)
    r[..., 2, 0], r[..., 2, 1], r[..., 2, 2] = 2 * (xz - yw), 2 * (yz + xw), 1 - 2 * (xx + yy)
    return r


def quat_from_euler(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Unit (x, y, z, w) quaternion from roll, pitch, yaw (rad), ZYX (yaw applied last).

    Source: REP-103 fixed-axis roll-pitch-yaw; Fossen (2011) eq. 2.18.
    """
    cr, sr = np.cos(roll / 2), np.sin(roll / 2)
    cp, sp = np.cos(pitch / 2), np.sin(pitch / 2)
    cy, sy = np.cos(yaw / 2), np.sin(yaw / 2)
    return np.array(
        [
            sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy,
        ]
    )


def quat_to_euler(q: np.ndarray) -> tuple[float, float, float]:
    """Roll, pitch, yaw (rad) of a unit (x, y, z, w) quaternion; inverse of quat_from_euler."""
    x, y, z, w = q
    roll = np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = np.arcsin(np.clip(2 * (w * y - z * x), -1.0, 1.0))
    yaw = np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return float(roll), float(pitch), float(yaw)


def inertia_tensor(moments: np.ndarray, products: np.ndarray) -> np.ndarray:
    """(..., 3, 3) kg m^2 inertia tensor from moments and products of inertia.

    Args:
        moments: (..., 3) [Ixx, Iyy, Izz].
        products: (..., 3) [Ixy, Ixz, Iyz], integral(x y dm), ...; negated off the diagonal
            (Fossen 2011, eq. 3.28).
    """
    ixx, iyy, izz = moments[..., 0], moments[..., 1], moments[..., 2]
    ixy, ixz, iyz = -products[..., 0], -products[..., 1], -products[..., 2]
    return np.stack([ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz], axis=-1).reshape(
        (*np.shape(ixx), 3, 3))


def _quat_exp(rotation_vector: np.ndarray) -> np.ndarray:
    """Unit (..., 4) quaternions of rotations by |v| rad about v/|v|, from (..., 3) v.

    Below 1e-12 rad the first-order form (v/2, 1), normalized, avoids dividing by |v|.
    """
    angle = np.sqrt(np.einsum("...i,...i->...", rotation_vector, rotation_vector))
    small = angle < 1e-12
    half = 0.5 * angle
    # sin(|v|/2)/|v|, with its limit 1/2 at 0 (then renormalized with cos -> 1)
    scale = np.where(small, 0.5 / np.sqrt(1.0 + half * half),
                     np.sin(half) / np.where(small, 1.0, angle))
    cos = np.where(small, 1.0 / np.sqrt(1.0 + half * half), np.cos(half))
    return np.concatenate([rotation_vector * scale[..., None], cos[..., None]], axis=-1)


def integrate(
    position: np.ndarray,
    orientation: np.ndarray,
    velocity: np.ndarray,
    angular_velocity: np.ndarray,
    force: np.ndarray,
    torque: np.ndarray,
    mass: np.ndarray,
    inertia: np.ndarray,
    dt: float,
    inertia_products: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """One semi-implicit (symplectic) Euler step of the body.

    Velocities are updated first from the forces, then the pose from the new velocities.

    Args:
        position: (..., 3) m, centre of mass, world frame.
        orientation: (..., 4) unit quaternion (x, y, z, w), body to world.
        velocity: (..., 3) m/s, body frame.
        angular_velocity: (..., 3) rad/s, body frame.
        force: (..., 3) N, total, body frame.
        torque: (..., 3) N m, total about the centre of mass, body frame.
        mass: (..., 3) kg, effective mass per body axis (rigid-body mass plus added mass).
        inertia: (..., 3) kg m^2, principal moments about the centre of mass (plus added
            inertia).
        dt: s.
        inertia_products: (..., 3) kg m^2 [Ixy, Ixz, Iyz] (integral(x y dm), ...), or None
            for principal body axes. With them the full tensor
            I = [[Ixx, -Ixy, -Ixz], [-Ixy, Iyy, -Iyz], [-Ixz, -Iyz, Izz]] is used
            (Fossen 2011, eq. 3.28).

    The leading axes (``...``) are boats: a whole fleet integrates in one call.

    Returns:
        New (position, orientation, velocity, angular_velocity).
    """
    v_dot = force / mass - cross(angular_velocity, velocity)
    if inertia_products is None:
        w_dot = (torque - cross(angular_velocity, inertia * angular_velocity)) / inertia
    else:
        tensor = inertia_tensor(inertia, inertia_products)
        spin = np.einsum("...ij,...j->...i", tensor, angular_velocity)
        w_dot = np.linalg.solve(tensor, (torque - cross(angular_velocity, spin))[..., None])[
            ..., 0]
    v = velocity + dt * v_dot
    w = angular_velocity + dt * w_dot
    q = quat_multiply(orientation, _quat_exp(w * dt))
    q = q / np.sqrt(np.einsum("...i,...i->...", q, q))[..., None]
    p = position + dt * np.einsum("...ij,...j->...i", rotation_matrix(q), v)
    return p, q, v, w
