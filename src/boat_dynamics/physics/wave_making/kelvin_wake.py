"""The Kelvin wake of a hull at speed: Michell's thin ship, Havelock's far field.

A hull moving ahead at U through calm deep water leaves the steady wave pattern (Havelock
1932; Newman 1977, "Marine Hydrodynamics", sec. 6.19; Wehausen 1973, Adv. Appl. Mech. 13)

    eta(x, y) = Re integral_{-pi/2}^{pi/2} A(theta) exp(i k (x cos theta + y sin theta)) dtheta,

in the hull's frame (x along its course, y to port, origin at its reference point), of free
waves k = k0 sec^2 theta, k0 = g / U^2, each travelling at angle theta to the course with the
hull (frequency omega = k U cos theta over the water). Michell's thin-ship theory (Michell
1898; Tuck 1989, J. Austral. Math. Soc. B 30, 365-377) gives the amplitude function from the
hull's half-breadths Y(x, z) below the waterline: its centre-plane sources sigma = -2 U Y_x
give, through the linearised free-surface condition U^2 phi_xx + g phi_z = 0 with the
radiation condition (waves behind),

    A(theta) = -(2 i k0^2 sec^4 theta / pi) integral Y(x, z) e^{k z} e^{-i k x cos theta} dx dz,

whose Havelock resistance R = (pi rho U^2 / 2) integral |A|^2 cos^3 theta dtheta is Michell's
integral. Far behind the hull the integral is dominated by its points of stationary phase
(Lord Kelvin 1887; Newman 1977, sec. 6.19): inside the wedge |y| <= X / sqrt(8) behind it
(X = -x, the 19.47 deg half-angle) two waves cross at each point, the transverse one and the
divergent one, each with amplitude |A| sqrt(2 pi / |Phi''|); on the wedge's edge (the cusp
line) the two merge and the amplitude is held to the Airy function's peak, outside it there is
no wave. That stationary-phase field is what this module gives, per point: as a local plane
wave of each branch (:class:`~.made_waves.LocalWaves`, what another boat feels) and as an
elevation (what the view draws).

What it leaves out, stated: the near field (the local disturbance that moves with the hull; the
wake is faded in from half a hull length to 1.5 hull lengths behind the reference point), waves
shorter than :data:`SHORTEST_WAVE`, the hull's sinkage and trim at speed, unsteady wakes (the
pattern is that of the present speed and course), viscous decay, and the Froude-number limits
of thin-ship theory (it over-predicts the waves of beamy hulls; the shipped boxes have
B / L = 0.5).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.hull import HullMesh
from boat_dynamics.physics.wave_making.made_waves import LocalWaves
from ocean_sim.physics.constants import GRAVITY

__all__ = ["SHORTEST_WAVE", "ThinShip", "amplitude", "leaves_wake", "michell_resistance",
           "pair_waves", "thin_ship", "wake_elevation", "wake_waves"]

#: m, the shortest wave of a wake kept (shorter ones, the divergent waves near the track,
#: are left out; a hull moving slower than sqrt(g SHORTEST_WAVE / 2 pi), 0.88 m/s, leaves
#: no wake).
SHORTEST_WAVE = 0.5
#: The Airy function's largest value (at -1.0188): the two branches' merged amplitude on
#: the cusp line is 2 pi Ai_max (2 / Phi''')^(1/3) |A| (Abramowitz & Stegun 10.4).
_AIRY_PEAK = 0.53566
#: Phi''' on the cusp line, per k0 X: 9 sqrt(3) / 4.
_CUSP_THIRD = 9.0 * math.sqrt(3.0) / 4.0


@dataclass(frozen=True)
class ThinShip:
    """A hull's half-breadths below its waterline on a grid: Michell's thin-ship hull.

    Attributes:
        x: (I,) m, body frame from the hull reference point: the stations' centres.
        dx: m, the stations' width.
        z_top: (J,) m, the layers' upper edges, below the calm waterline (<= 0).
        z_bottom: (J,) m, their lower edges.
        half_breadth: (I, J) m, Y: half the hull's breadth at each station and layer (the
            sum of the breadths of alike demihulls).
        length: m, the wetted length.
    """

    x: np.ndarray
    dx: float
    z_top: np.ndarray
    z_bottom: np.ndarray
    half_breadth: np.ndarray
    length: float


def thin_ship(mesh: HullMesh, height: float, stations: int = 40, layers: int = 10
              ) -> ThinShip:
    """The hull's :class:`ThinShip` floating upright with its reference point at ``height``.

    Each cell's half-breadth is that of the line across the hull (along y) through its centre:
    half the summed lengths of its runs inside the mesh.

    Args:
        mesh: the closed hull, body frame.
        height: m, the hull reference point's height above the calm water.
        stations: cells along the wetted length.
        layers: cells down the draft.

    Raises:
        ValueError: the hull is out of the water at ``height``.
    """
    v = mesh.vertices
    z_keel = v[:, 2].min() + height
    if z_keel >= 0.0:
        raise ValueError(f"the hull is out of the water at height {height} m")
    x0, x1 = v[:, 0].min(), v[:, 0].max()
    dx = (x1 - x0) / stations
    x = x0 + dx * (np.arange(stations) + 0.5)
    edges = np.linspace(0.0, z_keel, layers + 1)
    zc = 0.5 * (edges[:-1] + edges[1:])
    px, pz = np.meshgrid(x, zc - height, indexing="ij")  # body frame z
    breadth = _breadths(mesh, px.ravel(), pz.ravel()).reshape(stations, layers)
    wet = breadth.any(axis=1)
    length = dx * float(np.count_nonzero(wet))
    return ThinShip(x, float(dx), edges[:-1], edges[1:], breadth / 2.0, length)


def _breadths(mesh: HullMesh, x: np.ndarray, z: np.ndarray) -> np.ndarray:
    """(P,) m, the length inside the mesh of the lines along y through (x, z) (P points)."""
    c = mesh.corners  # (F, 3, 3)
    ax, az = c[:, 0, 0], c[:, 0, 2]
    e1x, e1z = c[:, 1, 0] - ax, c[:, 1, 2] - az
    e2x, e2z = c[:, 2, 0] - ax, c[:, 2, 2] - az
    det = e1x * e2z - e2x * e1z
    keep = np.abs(det) > 1e-12 * (np.abs(e1x * e2z) + np.abs(e2x * e1z) + 1e-300)
    out = np.zeros(x.shape[0])
    for p in range(x.shape[0]):  # once per hull, at start-up
        rx, rz = x[p] - ax[keep], z[p] - az[keep]
        u = (rx * e2z[keep] - e2x[keep] * rz) / det[keep]
        w = (e1x[keep] * rz - rx * e1z[keep]) / det[keep]
        hit = (u >= 0.0) & (w >= 0.0) & (u + w <= 1.0)
        f = np.flatnonzero(keep)[hit]
        y = np.sort(c[f, 0, 1] + u[hit] * (c[f, 1, 1] - c[f, 0, 1])
                    + w[hit] * (c[f, 2, 1] - c[f, 0, 1]))
        y = y[np.concatenate([[True], np.diff(y) > 1e-9])]  # a line through a shared edge
        if y.shape[0] >= 2:
            runs = y[: y.shape[0] // 2 * 2].reshape(-1, 2)
            out[p] = float(np.sum(runs[:, 1] - runs[:, 0]))
    return out


def _transform(ship: ThinShip, k: np.ndarray, kx: np.ndarray) -> np.ndarray:
    """(P,) complex, m^2: integral Y e^{k z} e^{-i kx x} dx dz, cell by cell exactly."""
    k = np.asarray(k, dtype=float)[:, None]
    depth = (np.exp(k * ship.z_top) - np.exp(k * ship.z_bottom)) / k  # (P, J)
    half = 0.5 * np.asarray(kx, dtype=float)[:, None] * ship.dx
    along = ship.dx * np.sinc(half / np.pi) * np.exp(-1j * kx[:, None] * ship.x)  # (P, I)
    return np.einsum("pi,ij,pj->p", along, ship.half_breadth, depth)


def amplitude(ship: ThinShip, theta: np.ndarray, speed: float | np.ndarray,
              gravity: float = GRAVITY) -> np.ndarray:
    """(T,) complex, m/rad: Michell's amplitude function A(theta) (module docstring).

    Args:
        ship: the hull.
        theta: (T,) rad, in (-pi/2, pi/2): the waves' angle to the course.
        speed: U, m/s, > 0; or (T,), one per angle.
        gravity: g, m/s^2.
    """
    theta = np.asarray(theta, dtype=float)
    k0 = gravity / np.asarray(speed, dtype=float) ** 2
    sec = 1.0 / np.cos(theta)
    k = k0 * sec**2
    return -2j * k0**2 * sec**4 / np.pi * _transform(ship, k, k * np.cos(theta))


def michell_resistance(ship: ThinShip, speed: float, density: float,
                       gravity: float = GRAVITY, nodes: int = 4000) -> float:
    """N, the wave resistance of Havelock's formula (pi rho U^2 / 2) int |A|^2 cos^3 dtheta.

    Equal to Michell's integral; the quadrature (in theta, ``nodes`` midpoints) stops where
    the waves are shorter than :data:`SHORTEST_WAVE`.
    """
    k0 = gravity / speed**2
    top = math.acos(min(1.0, math.sqrt(k0 * SHORTEST_WAVE / (2.0 * math.pi))))
    theta = (np.arange(nodes) + 0.5) / nodes * 2.0 * top - top
    a = amplitude(ship, theta, speed, gravity)
    return float(math.pi * density * speed**2 / 2.0
                 * np.sum(np.abs(a) ** 2 * np.cos(theta) ** 3) * 2.0 * top / nodes)


def _branches(x: np.ndarray, y: np.ndarray, k0: float | np.ndarray, length: float):
    """The two stationary-phase waves at P points (x, y), hull frame (x ahead, m).

    ``k0``: g / U^2, rad/m, or (P,), one per point (wakes of hulls at several speeds).

    Returns:
        theta (2, P) rad, k (2, P) rad/m, complex factor (2, P) sqrt(2 pi / |Phi''|) times
        e^{i (Phi +- pi / 4)} times the near-field fade (zero where there is no wave).
    """
    big_x = -x
    s2 = big_x**2 - 8.0 * y**2
    inside = (big_x > 0.0) & (s2 >= 0.0)
    s = np.sqrt(np.where(inside, s2, 0.0))
    small = np.where(inside, 2.0 * y / np.maximum(big_x + s, 1e-300), 0.0)  # tan, transverse
    large = np.where(inside & (small != 0.0), 0.5 / np.where(small == 0.0, 1.0, small),
                     np.inf)  # tan, divergent: t_small t_large = 1/2
    t = np.stack([small, large])
    finite = np.isfinite(t)
    t = np.where(finite, t, 0.0)
    sec = np.sqrt(1.0 + t * t)
    k = k0 * sec * sec
    phase = k0 * sec * (-big_x + y * t)
    curvature = k0 * sec**3 * s * np.array([[-1.0], [1.0]])  # Phi''
    cap = math.pi * _AIRY_PEAK * (2.0 / (_CUSP_THIRD * k0 * np.maximum(big_x, 1e-300))) ** (1 / 3)
    gain = np.minimum(np.sqrt(2.0 * math.pi / np.maximum(np.abs(curvature), 1e-300)), cap)
    fade = np.clip((big_x - 0.5 * length) / length, 0.0, 1.0)
    fade = fade * fade * (3.0 - 2.0 * fade)
    keep = inside & finite & (k <= 2.0 * math.pi / SHORTEST_WAVE)
    factor = np.where(keep, gain * fade, 0.0) * np.exp(
        1j * (phase + np.array([[-1.0], [1.0]]) * math.pi / 4.0))
    return np.arctan(t), k, factor


def _hull_frame(source_xy: np.ndarray, course: float, xy: np.ndarray) -> tuple:
    """(P,) x and (P,) y of world points ``xy`` (P, 2) in the frame of a hull at ``source_xy``."""
    d = np.asarray(xy, dtype=float).reshape(-1, 2) - np.asarray(source_xy, dtype=float)
    c, s = math.cos(course), math.sin(course)
    return d[:, 0] * c + d[:, 1] * s, -d[:, 0] * s + d[:, 1] * c


def _waves(ship: ThinShip, speed: float, source_xy, course: float, xy, gravity: float):
    """The angles (2, P) rad, k (2, P) rad/m and complex amplitudes (2, P) m at ``xy``."""
    x, y = _hull_frame(source_xy, course, xy)
    return pair_waves(ship, x, y, np.full(x.shape, float(speed)), gravity)


def pair_waves(ship: ThinShip, x: np.ndarray, y: np.ndarray, speed: np.ndarray,
               gravity: float = GRAVITY) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The wake's two waves at P points, each in the frame of a hull of this shape.

    Args:
        ship: the hull (shared by the P sources).
        x: (P,) m, each point ahead of its source along the source's course.
        y: (P,) m, to port of it.
        speed: (P,) m/s, > 0, each source's speed through the water.
        gravity: g, m/s^2.

    Returns:
        (2, P) rad, the waves' angles to the course (transverse, then divergent); (2, P)
        rad/m, their wavenumbers; (2, P) complex m, their amplitudes and phases at the
        points (zero: no wave).
    """
    k0 = gravity / speed**2
    theta, k, factor = _branches(x, y, k0, ship.length)
    a = np.zeros(theta.shape, dtype=complex)
    live = factor != 0.0
    if live.any():
        u = np.broadcast_to(speed, theta.shape)[live]
        a[live] = amplitude(ship, theta[live], u, gravity) * factor[live]
    return theta, k, a


def leaves_wake(speed: float | np.ndarray, gravity: float = GRAVITY) -> bool | np.ndarray:
    """Whether a hull at ``speed`` (m/s, or an array of speeds) leaves a wake.

    It does when its transverse waves, 2 pi U^2 / g long, are at least
    :data:`SHORTEST_WAVE` (U >= 0.88 m/s).
    """
    return 2.0 * math.pi * np.asarray(speed) ** 2 / gravity >= SHORTEST_WAVE


def wake_elevation(ship: ThinShip, speed: float, source_xy: np.ndarray, course: float,
                   xy: np.ndarray, gravity: float = GRAVITY) -> np.ndarray:
    """(P,) m, the wake's elevation at world points ``xy`` (P, 2) of a hull at speed.

    Args:
        ship: the hull.
        speed: U, m/s, through the water; below sqrt(g SHORTEST_WAVE / 2 pi), zeros.
        source_xy: (2,) m, world x, y of its reference point.
        course: rad, world frame, the direction it moves in through the water.
        xy: (P, 2) m, world points.
        gravity: g, m/s^2.
    """
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    if not leaves_wake(speed, gravity):
        return np.zeros(xy.shape[0])
    _, _, a = _waves(ship, speed, source_xy, course, xy, gravity)
    return a.sum(axis=0).real


def wake_waves(ship: ThinShip, speed: float, source_xy: np.ndarray, course: float,
               at: np.ndarray, t: float, gravity: float = GRAVITY) -> LocalWaves:
    """The wake at the point ``at`` as plane waves: one per branch present there.

    Each travels toward ``course`` + theta at omega = k U cos theta over the water, so that it
    keeps pace with the hull; arguments as :func:`wake_elevation` (``at``: (2,) m, world;
    ``t``: s, the time of the step).
    """
    at = np.asarray(at, dtype=float).reshape(2)
    if not leaves_wake(speed, gravity):
        return LocalWaves.none(at, t)
    theta, k, a = _waves(ship, speed, source_xy, course, at[None, :], gravity)
    theta, k, a = theta[:, 0], k[:, 0], a[:, 0]
    live = a != 0.0
    return LocalWaves(at, t, np.abs(a[live]), k[live] * speed * np.cos(theta[live]), k[live],
                      course + theta[live], np.angle(a[live]))
