"""Linear potential-flow coefficients of a hull: added mass, radiation damping, excitation.

A boundary-element solution (Capytaine; the ``hydro`` reference script) of one hull floating
at rest: per wave frequency omega, the 6 x 6 added mass A(omega) and radiation damping
B(omega) about the centre of mass, and per frequency and wave direction the complex
excitation forces per metre of wave amplitude, Froude-Krylov and diffraction apart. Stored as
a NumPy ``.npz`` of plain arrays (no pickled objects); read with :func:`load_coefficients`.

Conventions (those of Capytaine 3.0.0, kept so that a solver's file is read unchanged): dof
order surge, sway, heave, roll, pitch, yaw (body axes, FLU); forces in N/m and moments in
N m/m of wave amplitude; a wave travelling toward ``direction`` (rad, counter-clockwise from
+x) with elevation Re[a e^{-i omega t}] at the origin gives the force Re[a X e^{-i omega t}].

Sources: Newman, "Marine Hydrodynamics" (1977), ch. 6; Falnes, "Ocean Waves and Oscillating
Systems" (2002), ch. 5; the Capytaine documentation (Ancellin & Dias 2019).
"""

from __future__ import annotations

import hashlib
import zipfile
from dataclasses import dataclass, replace
from functools import cached_property
from pathlib import Path

import numpy as np

__all__ = ["DOFS", "ESTIMATE_REFERENCE", "KOCHIN_HARMONICS", "SHIPPED_COEFFICIENTS", "GapMode",
           "HydroCoefficients", "HydroFileError", "NarrowPeak", "coefficient_directories",
           "estimate", "find_coefficients", "froude_scaled", "harmonic_curvature", "hydro_key",
           "load_coefficients", "moved", "narrow_peaks"]

#: The coefficient files shipped with boatsim (its scenarios' hulls), named ``*_<key>.npz``.
SHIPPED_COEFFICIENTS = Path(__file__).resolve().parents[2] / "data" / "hydro"

#: The file :func:`estimate` scales: the default 4 x 2 x 1 m box, 4100 kg, CoM 0.2 m below
#: its reference point, deep water.
ESTIMATE_REFERENCE = SHIPPED_COEFFICIENTS / "box_4x2x1_d0.500_2b2dd4941ae3d992.npz"

#: The rigid-body degrees of freedom, in the order of every 6-vector and 6 x 6 matrix.
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


#: The highest frequency a coefficient file may hold, rad/s: its radiation memory is sampled at
#: pi / (8 omega_max), so 1e7 rad/s asked 11.4 GiB (a 0.3 m model needs about 50).
MAX_OMEGA = 200.0
#: The most a coefficient file may hold uncompressed, bytes: a 2 MB .npz zip bomb once held
#: 2.4 GB for a minute (the shipped files hold under 1 MB).
MAX_FILE_BYTES = 256 * 2**20


class HydroFileError(ValueError):
    """A coefficient file that cannot be used: unreadable, or an array missing or malformed."""


@dataclass(frozen=True)
class GapMode:
    """One lightly damped resonance of a multihull's file (the sloshing between its hulls).

    Its share of the radiation kernel K(s) = B + i omega (A - A_inf), s = i omega, is the pole
    pair K_m = rho c / (s - p) + conj(rho c) / (s - conj p), p = -zeta omega0 +
    i omega0 sqrt(1 - zeta^2), c = 2 zeta omega0 p / (p - conj p) (for a real residue
    rho h(s), h = 2 zeta omega0 s / (s^2 + 2 zeta omega0 s + omega0^2), B_m(omega0) = rho);
    its share of the diffraction force is excitation conj(h) (Capytaine's e^(-i omega t)).
    :mod:`boat_dynamics.physics.potential_flow.gap_modes` computes with them.

    Attributes:
        omega0: rad/s, the undamped natural frequency.
        zeta: the damping ratio, in (0, 1) (B's peak is 2 zeta omega0 wide at half height).
        residue: (6, 6) complex, symmetric, N s/m, N s, N m s (as B).
        excitation: (D, 6) complex, N/m and N m/m, on the file's directions.
    """

    omega0: float
    zeta: float
    residue: np.ndarray
    excitation: np.ndarray


@dataclass(frozen=True)
class HydroCoefficients:
    """One hull's potential-flow coefficients at its floating position.

    Attributes:
        omega: (W,) rad/s, increasing.
        added_mass: (W, 6, 6) kg, kg m, kg m^2.
        radiation_damping: (W, 6, 6) N s/m, N s, N m s.
        added_mass_inf: (6, 6), the infinite-frequency limit.
        directions: (D,) rad, wave directions of the excitation.
        froude_krylov: (W, D, 6) complex, N/m and N m/m.
        diffraction: (W, D, 6) complex, N/m and N m/m.
        hydrostatic_stiffness: (6, 6) N/m, N, N m (the solver's, for checks).
        inertia_matrix: (6, 6) the rigid-body mass matrix the solver was given.
        center_of_mass: (3,) m, body frame, the rotation centre of the dofs.
        source: where the coefficients come from: the file's path, or the description of an
            estimate (:func:`estimate`).
        gap_modes: the file's gap resonances, found by local solves around its narrow peaks
            (:class:`GapMode`; the ``gap_mode_*`` arrays), or none.
        kochin_angles: (T,) rad, body frame, increasing within [0, 2 pi): the directions
            the outgoing waves of the Kochin functions travel toward; None for a file
            without Kochin functions (the three ``kochin_*`` arrays: all or none).
        kochin_radiation: (W, 6, T) complex, m^2/s per unit motion amplitude (1 m, 1 rad)
            of each dof (rotations about ``center_of_mass``): the radiation problems'
            Kochin functions H_j(theta) (Capytaine's ``compute_kochin``, about x = y = 0;
            tests/data/wavemaking/README.md), or None.
        kochin_diffraction: (W, D, T) complex, m^2/s per metre of incident amplitude, at
            ``directions``: the scattered potential's H_D(theta; beta), or None.
    """

    omega: np.ndarray
    added_mass: np.ndarray
    radiation_damping: np.ndarray
    added_mass_inf: np.ndarray
    directions: np.ndarray
    froude_krylov: np.ndarray
    diffraction: np.ndarray
    hydrostatic_stiffness: np.ndarray
    inertia_matrix: np.ndarray
    center_of_mass: np.ndarray
    source: str = ""
    gap_modes: tuple[GapMode, ...] = ()
    kochin_angles: np.ndarray | None = None
    kochin_radiation: np.ndarray | None = None
    kochin_diffraction: np.ndarray | None = None

    @property
    def has_kochin(self) -> bool:
        """True when the file carries Kochin functions (the boat can make waves)."""
        return self.kochin_angles is not None

    @cached_property
    def kochin_curvature(self) -> tuple[np.ndarray, np.ndarray] | None:
        """-d^2 H / d theta^2 of the Kochin functions, harmonics |n| <= KOCHIN_HARMONICS.

        H(theta) = sum_n h_n e^{i n theta} gives sum_n n^2 h_n e^{i n theta} (FFT over the
        file's angles; the higher harmonics, noise that the near field would amplify, are
        left out: tests/data/wavemaking/README.md). Computed once, when first asked
        (:mod:`boat_dynamics.physics.wave_making.scattered_waves`' 1 / (k r) term).

        Returns:
            (W, 6, T) radiation and (W, D, T) diffraction tables, as the file's; None without
            Kochin functions or unless their angles are uniform over 2 pi.
        """
        theta = self.kochin_angles
        if theta is None or not np.allclose(np.diff(theta), 2 * np.pi / theta.shape[0],
                                            rtol=0.0, atol=1e-6):
            return None
        return (harmonic_curvature(self.kochin_radiation),
                harmonic_curvature(self.kochin_diffraction))

    def added_mass_at(self, omega: float) -> np.ndarray:
        """(6, 6) A at ``omega`` (linear in omega between grid points, clamped at the ends)."""
        return _interp(self.omega, self.added_mass, omega)

    def damping_at(self, omega: float) -> np.ndarray:
        """(6, 6) B at ``omega`` (linear in omega between grid points, clamped at the ends)."""
        return _interp(self.omega, self.radiation_damping, omega)

    def diffraction_at(self, omega: np.ndarray, direction: np.ndarray) -> np.ndarray:
        """(M, 6) complex diffraction forces per metre of amplitude for M (omega, direction).

        Bilinear in omega (clamped to the grid) and direction (modulo 2 pi; the grid's
        directions are extended by symmetry when they span only 0..pi: a hull symmetric
        about its centreplane feels a wave from -beta as one from beta, mirrored: sway, roll
        and yaw change sign).
        """
        return _bilinear(self.omega, self.directions, self.diffraction, omega, direction)

    def froude_krylov_at(self, omega: np.ndarray, direction: np.ndarray) -> np.ndarray:
        """(M, 6) complex Froude-Krylov forces per metre of amplitude, as :meth:`diffraction_at`."""
        return _bilinear(self.omega, self.directions, self.froude_krylov, omega, direction)

    def excitation_at(self, omega: np.ndarray, direction: np.ndarray) -> np.ndarray:
        """(M, 12) complex: diffraction (6) then Froude-Krylov (6), one interpolation."""
        table = np.concatenate([self.diffraction, self.froude_krylov], axis=2)
        return _bilinear(self.omega, self.directions, table, omega, direction)

    def natural(self, dof: int, stiffness: float, inertia: float) -> tuple[float, float, float]:
        """(omega_n rad/s, A_ii(omega_n), damping ratio) of one dof with its added mass.

        Solves omega = sqrt(C / (M + A(omega))) by fixed-point iteration on the grid's linear
        interpolation; the damping ratio is B / (2 sqrt(C (M + A))) there.
        """
        omega = float(np.sqrt(stiffness / inertia))
        for _ in range(200):
            added = self.added_mass_at(omega)[dof, dof]
            new = float(np.sqrt(stiffness / (inertia + added)))
            if abs(new - omega) <= 1e-12 * omega:
                break
            omega = new
        added = float(self.added_mass_at(omega)[dof, dof])
        zeta = float(self.damping_at(omega)[dof, dof]
                     / (2.0 * np.sqrt(stiffness * (inertia + added))))
        return omega, added, zeta


#: The dofs that change sign when a wave's direction is mirrored about the x axis.
_MIRRORED = np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])


#: The Kochin functions' harmonics the far field's 1 / (k r) term keeps
#: (:attr:`HydroCoefficients.kochin_curvature`).
KOCHIN_HARMONICS = 8


def harmonic_curvature(table: np.ndarray) -> np.ndarray:
    """sum_n n^2 h_n e^{i n theta}, |n| <= :data:`KOCHIN_HARMONICS`, of (..., T) samples."""
    t = table.shape[-1]
    n = np.fft.fftfreq(t, 1.0 / t)
    weight = np.where(np.abs(n) <= KOCHIN_HARMONICS, n**2, 0.0)
    return np.fft.ifft(np.fft.fft(table, axis=-1) * weight, axis=-1)


def _bilinear(omegas: np.ndarray, directions: np.ndarray, table: np.ndarray,
              omega: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """(M, 6) of a (W, D, 6) table at M points (omega, direction), bilinear."""
    w = np.clip(np.asarray(omega, dtype=float), omegas[0], omegas[-1])
    beta = np.mod(np.asarray(direction, dtype=float), 2 * np.pi)
    sign = np.ones((beta.shape[0], 1))
    if directions[-1] <= np.pi + 1e-9:  # a half circle: mirror the other half
        mirrored = beta > np.pi
        beta = np.where(mirrored, 2 * np.pi - beta, beta)
        flip = np.tile(_MIRRORED, table.shape[-1] // 6)
        sign = np.where(mirrored[:, None], flip, 1.0)
    beta = np.clip(beta, directions[0], directions[-1])
    i = np.clip(np.searchsorted(omegas, w) - 1, 0, omegas.shape[0] - 2)
    j = np.clip(np.searchsorted(directions, beta) - 1, 0, directions.shape[0] - 2)
    u = ((w - omegas[i]) / (omegas[i + 1] - omegas[i]))[:, None]
    v = ((beta - directions[j]) / (directions[j + 1] - directions[j]))[:, None]
    value = ((1 - u) * (1 - v) * table[i, j] + u * (1 - v) * table[i + 1, j]
             + (1 - u) * v * table[i, j + 1] + u * v * table[i + 1, j + 1])
    return sign * value


def _interp(grid: np.ndarray, table: np.ndarray, x: float) -> np.ndarray:
    """table[i] linearly interpolated along its first axis at x on ``grid`` (clamped)."""
    x = float(np.clip(x, grid[0], grid[-1]))
    i = int(np.clip(np.searchsorted(grid, x) - 1, 0, grid.shape[0] - 2))
    w = (x - grid[i]) / (grid[i + 1] - grid[i])
    return (1.0 - w) * table[i] + w * table[i + 1]


_SHAPES = {
    "omega": ("W",), "added_mass": ("W", 6, 6), "radiation_damping": ("W", 6, 6),
    "added_mass_inf": (6, 6), "directions": ("D",), "froude_krylov": ("W", "D", 6),
    "diffraction": ("W", "D", 6), "hydrostatic_stiffness": (6, 6), "inertia_matrix": (6, 6),
    "center_of_mass": (3,),
}
#: The optional arrays of a file's gap modes (:class:`GapMode`): all four or none.
_MODE_SHAPES = {"gap_mode_omega": ("M",), "gap_mode_zeta": ("M",),
                "gap_mode_residue": ("M", 6, 6), "gap_mode_excitation": ("M", "D", 6)}
#: The optional Kochin functions of a file (``boatsim hydro`` writes them since issue 31):
#: all three or none.
_KOCHIN_SHAPES = {"kochin_angles": ("T",), "kochin_radiation": ("W", 6, "T"),
                  "kochin_diffraction": ("W", "D", "T")}


def load_coefficients(path: str | Path) -> HydroCoefficients:
    """Read a coefficient file (``.npz``), checking every array's shape and values.

    Raises:
        HydroFileError: naming the file, the array and what was wrong.
    """
    p = Path(path)
    try:
        _check_sizes(p)
        with np.load(p, allow_pickle=False) as data:
            arrays = {name: np.asarray(data[name])
                      for name in (*_SHAPES, *_MODE_SHAPES, *_KOCHIN_SHAPES)
                      if name in data.files}
    except (OSError, ValueError, zipfile.BadZipFile, EOFError, MemoryError) as exc:
        if isinstance(exc, HydroFileError):
            raise
        raise HydroFileError(f"{p}: not a readable .npz coefficient file ({exc})") from exc
    sizes: dict[str, int] = {}
    for name in _SHAPES:
        if name not in arrays:
            raise HydroFileError(f"{p}: array {name!r} is missing")
        _check_array(p, name, arrays[name], _SHAPES[name], sizes)
    if sizes["W"] < 2 or np.any(np.diff(arrays["omega"]) <= 0.0) or arrays["omega"][0] <= 0.0:
        raise HydroFileError(f"{p}: omega must hold at least two increasing values > 0")
    _check_physics(p, arrays)
    return HydroCoefficients(**{name: arrays[name] for name in _SHAPES}, source=str(p),
                             gap_modes=_gap_modes(p, arrays, sizes),
                             **_kochin(p, arrays, sizes))


def _check_array(p: Path, name: str, a: np.ndarray, shape: tuple, sizes: dict[str, int]) -> None:
    """HydroFileError unless ``a`` holds finite numbers of ``shape`` (named sizes agreeing)."""
    if a.dtype.kind not in "fciu":  # text, bytes, booleans, dates, structures
        raise HydroFileError(f"{p}: {name} holds {a.dtype} values; expected numbers")
    if a.ndim != len(shape):
        raise HydroFileError(f"{p}: {name} has shape {a.shape}, expected {shape}")
    for size, want in zip(a.shape, shape, strict=True):
        if isinstance(want, str):
            if sizes.setdefault(want, size) != size:
                raise HydroFileError(f"{p}: {name} has shape {a.shape}: {want} = {size}, "
                                     f"but {sizes[want]} elsewhere")
        elif size != want:
            raise HydroFileError(f"{p}: {name} has shape {a.shape}, expected {shape}")
    if not np.all(np.isfinite(a)):
        raise HydroFileError(f"{p}: {name} has non-finite values")


def _gap_modes(p: Path, arrays: dict[str, np.ndarray], sizes: dict[str, int]
               ) -> tuple[GapMode, ...]:
    """The file's gap modes (the ``gap_mode_*`` arrays: all four or none), checked."""
    present = [name for name in _MODE_SHAPES if name in arrays]
    if not present:
        return ()
    if len(present) != len(_MODE_SHAPES):
        missing = sorted(set(_MODE_SHAPES) - set(present))
        raise HydroFileError(f"{p}: gap mode arrays {missing} are missing (all four or none)")
    for name, shape in _MODE_SHAPES.items():
        _check_array(p, name, arrays[name], shape, sizes)
    omega0, zeta = arrays["gap_mode_omega"], arrays["gap_mode_zeta"]
    if np.iscomplexobj(omega0) or np.iscomplexobj(zeta):
        raise HydroFileError(f"{p}: gap_mode_omega and gap_mode_zeta must be real")
    if np.any(omega0 <= 0.0) or np.any(omega0 > MAX_OMEGA):
        raise HydroFileError(f"{p}: gap_mode_omega {omega0.tolist()} rad/s: each in "
                             f"(0, {MAX_OMEGA:g}]")
    if np.any(zeta <= 0.0) or np.any(zeta >= 1.0):
        raise HydroFileError(f"{p}: gap_mode_zeta {zeta.tolist()}: each in (0, 1)")
    residue = arrays["gap_mode_residue"].astype(complex)
    return tuple(GapMode(float(w0), float(z), r, x.astype(complex)) for w0, z, r, x in
                 zip(omega0, zeta, residue, arrays["gap_mode_excitation"], strict=True))


def _kochin(p: Path, arrays: dict[str, np.ndarray], sizes: dict[str, int]) -> dict:
    """The file's Kochin arrays (``kochin_*``: all three or none), checked; {} for none."""
    present = [name for name in _KOCHIN_SHAPES if name in arrays]
    if not present:
        return {}
    if len(present) != len(_KOCHIN_SHAPES):
        missing = sorted(set(_KOCHIN_SHAPES) - set(present))
        raise HydroFileError(f"{p}: Kochin arrays {missing} are missing (all three or none)")
    for name, shape in _KOCHIN_SHAPES.items():
        _check_array(p, name, arrays[name], shape, sizes)
    theta = arrays["kochin_angles"]
    if (np.iscomplexobj(theta) or theta.size < 8 or np.any(np.diff(theta) <= 0.0)
            or theta[0] < 0.0 or theta[-1] >= 2 * np.pi):
        raise HydroFileError(f"{p}: kochin_angles {np.degrees(np.real(theta)).round(3).tolist()}"
                             " deg: at least eight, real, increasing, within [0, 360) deg")
    return dict(kochin_angles=theta.astype(float),
                kochin_radiation=arrays["kochin_radiation"].astype(complex),
                kochin_diffraction=arrays["kochin_diffraction"].astype(complex))


def _check_sizes(p: Path) -> None:
    """HydroFileError for a file that would hold more than :data:`MAX_FILE_BYTES` once read.

    The zip's declared sizes, and each array's header (shape, dtype) against its member's
    size, are read before anything is allocated.
    """
    with zipfile.ZipFile(p) as z:
        members = z.infolist()
        total = sum(m.file_size for m in members)
        if total > MAX_FILE_BYTES:
            raise HydroFileError(f"{p}: its arrays hold {total} bytes uncompressed; a "
                                 f"coefficient file may hold at most {MAX_FILE_BYTES}")
        for m in members:
            with z.open(m) as f:
                version = np.lib.format.read_magic(f)
                read_header = (np.lib.format.read_array_header_1_0 if version == (1, 0)
                               else np.lib.format.read_array_header_2_0)
                shape, _, dtype = read_header(f)
            declared = int(np.prod(shape, dtype=float)) * dtype.itemsize
            if declared > m.file_size:
                raise HydroFileError(f"{p}: array {m.filename} declares {shape} of {dtype} "
                                     f"({declared} bytes) in {m.file_size} bytes")


def _check_physics(p: Path, arrays: dict[str, np.ndarray]) -> None:
    """HydroFileError for coefficients the physics cannot use (NaN states followed).

    At least two wave directions, increasing within [0, 2 pi); frequencies up to
    :data:`MAX_OMEGA`; an infinite-frequency added mass that is symmetric (within 5 % of its
    largest entry: a solver's discretization leaves 0.04-0.35 % in the shipped files) and
    positive semi-definite; some radiation damping.
    """
    beta = arrays["directions"]
    if beta.size < 2 or np.any(np.diff(beta) <= 0.0) or beta[0] < 0.0 or beta[-1] >= 2 * np.pi:
        raise HydroFileError(f"{p}: directions {np.degrees(beta).round(3).tolist()} deg: at "
                             "least two, increasing, within [0, 360) deg")
    if arrays["omega"][-1] > MAX_OMEGA:
        raise HydroFileError(f"{p}: omega reaches {arrays['omega'][-1]:g} rad/s; at most "
                             f"{MAX_OMEGA:g}")
    a_inf = arrays["added_mass_inf"]
    scale = max(float(np.abs(a_inf).max()), 1e-300)
    lowest = float(np.linalg.eigvalsh(0.5 * (a_inf + a_inf.T)).min())
    if np.abs(a_inf - a_inf.T).max() > 0.05 * scale or lowest < -1e-6 * scale:
        raise HydroFileError(f"{p}: added_mass_inf must be symmetric positive semi-definite "
                             f"(its lowest eigenvalue is {lowest:.4g})")
    if not np.any(np.diagonal(arrays["radiation_damping"], axis1=1, axis2=2) > 0.0):
        raise HydroFileError(f"{p}: radiation_damping is zero at every frequency: a hull "
                             "radiates; use `coefficients: none` for a hull without them")


def _canonical(name: str, value, dtype: str) -> bytes:
    """Bytes of one named array: name, dtype, shape and little-endian data."""
    a = np.asarray(value, dtype=np.float64 if dtype == "<f8" else np.int64)
    if dtype == "<f8":
        with np.errstate(over="ignore", invalid="ignore"):  # 1e308 m of depth: x 1e9 overflows
            rounded = np.round(a, 9)
        a = np.where(np.isfinite(rounded), rounded, a) + 0.0  # + 0.0 maps -0.0 to 0.0
    a = np.ascontiguousarray(a.astype(dtype))
    return f"{name}:{dtype}:{a.shape}:".encode() + a.tobytes()


def hydro_key(vertices: np.ndarray, faces: np.ndarray, mass: float,
              center_of_mass: np.ndarray, inertia_matrix: np.ndarray, water_density: float,
              gravity: float, depth: float) -> str:
    """The identity of a coefficient file's inputs: the hull mesh, its mass, the water.

    Args:
        vertices: (V, 3) m, body frame (the scenario's mesh, before any refinement).
        faces: (F, 3) vertex indices.
        mass: kg.
        center_of_mass: (3,) m, body frame.
        inertia_matrix: (6, 6) rigid-body mass matrix about the centre of mass.
        water_density: kg/m^3.
        gravity: m/s^2.
        depth: water depth, m (``inf`` for deep water).

    Returns:
        16 hex characters: the start of the sha256 of a canonical byte string of the inputs
        (a version tag, then each input's name, dtype, shape and little-endian data: floats
        rounded to 1e-9 as float64, faces as int64).
    """
    parts = [("vertices", vertices, "<f8"), ("faces", faces, "<i8"), ("mass", mass, "<f8"),
             ("center_of_mass", center_of_mass, "<f8"),
             ("inertia_matrix", inertia_matrix, "<f8"),
             ("water_density", water_density, "<f8"), ("gravity", gravity, "<f8"),
             ("depth", depth, "<f8")]
    digest = hashlib.sha256(b"boatsim-hydro-v1\n")
    for name, value, dtype in parts:
        digest.update(_canonical(name, value, dtype))
    return digest.hexdigest()[:16]


def coefficient_directories(scenario_dir: Path) -> tuple[Path, ...]:
    """Where ``coefficients: auto`` looks: the scenario's ``hydro/``, then the shipped files.

    ``boatsim hydro SCENARIO`` writes into the first; :data:`SHIPPED_COEFFICIENTS` is the
    second.
    """
    return (Path(scenario_dir) / "hydro", SHIPPED_COEFFICIENTS)


def find_coefficients(key: str, directories: tuple[Path, ...]) -> Path | None:
    """The first file named ``*_<key>.npz`` in ``directories`` (sorted by name), or None."""
    for directory in directories:
        found = sorted(Path(directory).glob(f"*_{key}.npz"))
        if found:
            return found[0]
    return None


_ROTATIONAL = np.array([0, 0, 0, 1, 1, 1])


def moved(hydro: HydroCoefficients, center: np.ndarray) -> HydroCoefficients:
    """The same coefficients with the rotations about ``center`` (m, body frame).

    A rigid motion about the old centre c is one about the new centre n plus a translation:
    with d = c - n and T = [[I, -[d]x], [0, I]], A' = T^T A T (B, A_inf, C, M alike) and
    F' = T^T F (Newman 1977, sec. 6.11; Fossen 2011, sec. 7.5); a gap mode's residue as B, its
    excitation as F; the radiation Kochin functions as F (the wave is linear in the motion,
    x_c = T x_n), the diffraction ones unchanged.
    """
    d = hydro.center_of_mass - np.asarray(center, dtype=float)
    t = np.eye(6)
    t[:3, 3:] = -np.array([[0.0, -d[2], d[1]], [d[2], 0.0, -d[0]], [-d[1], d[0], 0.0]])

    def square(m):
        return np.einsum("ki,...kl,lj->...ij", t, m, t)

    def force(f):
        return np.einsum("ki,...k->...i", t, f)

    return HydroCoefficients(
        hydro.omega, square(hydro.added_mass), square(hydro.radiation_damping),
        square(hydro.added_mass_inf), hydro.directions, force(hydro.froude_krylov),
        force(hydro.diffraction), square(hydro.hydrostatic_stiffness),
        square(hydro.inertia_matrix), np.asarray(center, dtype=float), hydro.source,
        tuple(replace(m, residue=square(m.residue), excitation=force(m.excitation))
              for m in hydro.gap_modes),
        hydro.kochin_angles,
        None if hydro.kochin_radiation is None
        else np.einsum("ki,wkt->wit", t, hydro.kochin_radiation),
        hydro.kochin_diffraction)


def froude_scaled(hydro: HydroCoefficients, scale: float) -> HydroCoefficients:
    """The coefficients of the same hull ``scale`` times larger, same water (Froude scaling).

    Lengths x s, frequencies / sqrt(s); a coefficient's powers of s follow its dofs (e = 1 for
    a rotation): A and M s^(3 + e_i + e_j), B s^(2.5 + e_i + e_j), C s^(2 + e_i + e_j), the
    excitation per metre of amplitude s^(2 + e_i) (Newman 1977, sec. 2.11; ITTC 7.5-02-07-02.1);
    a gap mode's residue as B, its excitation as the excitation; the Kochin functions (m^2/s
    per metre of motion or of wave) s^(1.5 + e_j), e_j = 0 for the diffraction ones.
    """
    e = _ROTATIONAL[:, None] + _ROTATIONAL[None, :]
    return HydroCoefficients(
        hydro.omega / np.sqrt(scale), hydro.added_mass * scale ** (3.0 + e),
        hydro.radiation_damping * scale ** (2.5 + e), hydro.added_mass_inf * scale ** (3.0 + e),
        hydro.directions, hydro.froude_krylov * scale ** (2.0 + _ROTATIONAL),
        hydro.diffraction * scale ** (2.0 + _ROTATIONAL),
        hydro.hydrostatic_stiffness * scale ** (2.0 + e), hydro.inertia_matrix * scale ** (3.0 + e),
        hydro.center_of_mass * scale, hydro.source,
        tuple(GapMode(m.omega0 / np.sqrt(scale), m.zeta, m.residue * scale ** (2.5 + e),
                      m.excitation * scale ** (2.0 + _ROTATIONAL)) for m in hydro.gap_modes),
        hydro.kochin_angles,
        None if hydro.kochin_radiation is None
        else hydro.kochin_radiation * scale ** (1.5 + _ROTATIONAL)[:, None],
        None if hydro.kochin_diffraction is None else hydro.kochin_diffraction * scale**1.5)


def estimate(mass: float, center_of_mass: np.ndarray, water_density: float, z_eq: float,
             key: str) -> HydroCoefficients:
    """Coefficients for a hull without a file: the reference box's, Froude-scaled.

    The box of :data:`ESTIMATE_REFERENCE` (its waterline at its reference point) scaled by the
    cube root of the displacement ratio and by the density ratio, placed with its waterline on
    the boat's (body z = -z_eq), its rotations moved to the boat's centre of mass. Right for a
    box of the same proportions; for others an estimate (the tests measure it on the shipped
    boxes), deep water. Its ``source`` says so.

    Args:
        mass: kg, the boat's (its displacement at rest).
        center_of_mass: (3,) m, body frame.
        water_density: kg/m^3.
        z_eq: m, the boat's equilibrium height (its waterline is at body z = -z_eq).
        key: the hull's key, for the description.
    """
    reference = load_coefficients(ESTIMATE_REFERENCE)
    rho = 1025.0  # the reference file's water
    scale = (mass / water_density / (float(reference.inertia_matrix[0, 0]) / rho)) ** (1 / 3)
    scaled = froude_scaled(reference, scale)
    ratio = water_density / rho
    scaled = replace(
        scaled, added_mass=scaled.added_mass * ratio,
        radiation_damping=scaled.radiation_damping * ratio,
        added_mass_inf=scaled.added_mass_inf * ratio, froude_krylov=scaled.froude_krylov * ratio,
        diffraction=scaled.diffraction * ratio,
        hydrostatic_stiffness=scaled.hydrostatic_stiffness * ratio,
        center_of_mass=scaled.center_of_mass - np.array([0.0, 0.0, z_eq]))
    return replace(moved(scaled, center_of_mass),
                   source=f"estimate for hull {key}: {ESTIMATE_REFERENCE.name} Froude-scaled "
                          f"by {scale:.3f}, no file of its own")


@dataclass(frozen=True)
class NarrowPeak:
    """A file's value that stands far above its neighbours on the frequency grid.

    Attributes:
        dof: one of :data:`DOFS`.
        quantity: ``damping`` (B's diagonal) or ``excitation`` (|F_FK + F_D|, any direction).
        omega: rad/s, the grid frequency.
        ratio: the value over the larger of the values two grid steps away.
    """

    dof: str
    quantity: str
    omega: float
    ratio: float


def narrow_peaks(hydro: HydroCoefficients, ratio: float = 1.5, floor: float = 0.2
                 ) -> tuple[NarrowPeak, ...]:
    """Grid points one or two wide that stand ``ratio`` times above those two steps away.

    And twice ``ratio`` times above one of the two beside it (a hump a few points wide, as
    between two interference minima, is left alone: a Wigley hull's yaw excitation in
    oblique seas has one), and by ``floor`` times the curve's 90th percentile: a sharp
    resonance narrower than the
    grid, such as the sloshing between a catamaran's hulls (omega^2 ~ g n pi / b for a gap b;
    the shipped Otter's at 8.2 and 13.2 rad/s, under 0.2 rad/s wide, measured with
    a 0.05 rad/s solve). Its height on the grid means nothing, its added mass's slow tails
    contradict the damping (Kramers-Kronig), and no radiation memory fits both
    (:func:`.radiation.fit_memory`). Broad physical humps (the heave hump between two hulls
    whose waves cancel) are not flagged; nor is anything in the shipped monohulls' files.

    Returns:
        The peaks, by frequency then dof; empty for a file without any.
    """
    w = hydro.omega
    channels = [("damping", d, np.diagonal(hydro.radiation_damping, axis1=1, axis2=2)[:, d])
                for d in range(6)]
    excitation = np.abs(hydro.froude_krylov + hydro.diffraction)  # (W, D, 6)
    channels += [("excitation", d, excitation[:, j, d]) for d in range(6)
                 for j in range(excitation.shape[1])]
    found: dict[tuple[int, str, str], float] = {}
    for quantity, d, y in channels:
        y = np.abs(y)
        if y.max() <= 1e-9 * max(float(np.abs(hydro.radiation_damping).max()), 1e-300):
            continue  # zero by symmetry
        scale = float(np.percentile(y, 90))
        for k in range(len(w)):
            around = max(y[m] for m in (k - 2, k + 2) if 0 <= m < len(w))
            beside = min(y[m] for m in (k - 1, k + 1) if 0 <= m < len(w))
            sharp = y[k] > ratio * around and y[k] > 2 * ratio * beside
            if sharp and y[k] - around > floor * scale:
                key = (k, DOFS[d], quantity)
                found[key] = max(found.get(key, 0.0), float(y[k] / max(around, 1e-300)))
    return tuple(NarrowPeak(dof, quantity, float(w[k]), r)
                 for (k, dof, quantity), r in sorted(found.items(),
                                                     key=lambda item: (item[0][0],
                                                                       DOFS.index(item[0][1]))))
