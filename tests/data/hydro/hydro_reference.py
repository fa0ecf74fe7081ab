#!/usr/bin/env python3
"""Potential-flow (BEM) reference data for a floating rigid box, computed with Capytaine 3.0.0.

Case
----
Rigid box hull, body frame FLU (x forward, y left, z up), origin at the centre of
the box's bounding box:

* length L = 4.0 m (x), beam B = 2.0 m (y), height H = 1.0 m (z);
* floating upright with the origin at the calm-water plane (z = 0), so the
  draft is 0.5 m (bottom at z = -0.5 m);
* mass 4100 kg (= rho * displaced volume, so the box is in equilibrium),
  centre of mass (0, 0, -0.2) m, solid-box moments of inertia about the CoM
  Ixx = m (B^2 + H^2)/12, Iyy = m (L^2 + H^2)/12, Izz = m (L^2 + B^2)/12;
* rho = 1025 kg/m^3, g = 9.81 m/s^2, infinite water depth, no forward speed.

What is computed (all six rigid-body dofs, rotations about the centre of mass)
-----------------------------------------------------------------------------
* added mass A(omega) and radiation damping B(omega), 6x6, on a frequency grid,
  plus the zero- and infinite-frequency added mass;
* Froude-Krylov and diffraction forces (complex) for several wave directions;
* hydrostatic stiffness (Capytaine, Gauss-Legendre-2 quadrature) and the
  rigid-body inertia matrix;
* RAOs (capytaine.post_pro.rao);
* natural periods and radiation damping ratios in heave, roll and pitch.

Everything is written to one ``.npz`` file (``np.savez_compressed``, plain
numeric / unicode arrays only, readable with ``allow_pickle=False``).  The
array ``conventions`` in that file documents the sign, phase and unit
conventions; read it before using the data.

Mesh
----
Only the immersed part of the box is meshed, with quadrilateral panels:
``n`` panels per metre horizontally (``--panels-per-metre``, default 12) and
``n`` panels over the 0.5 m draft (i.e. 2n per metre vertically).  Both
reflection symmetries (xOz and yOz) are declared, which makes Capytaine about
an order of magnitude faster and is exact for this symmetric body (the centre
of mass lies on the symmetry axis).

Irregular frequencies are removed with an interior "lid": a horizontal panel
mesh closing the hull at z_lid = -draft/n, i.e. exactly on the first row of
panel edges of the side walls.  Reasons (measured while setting this up):

* without a lid the box shows irregular-frequency spikes from about 4.9 rad/s
  upward (first interior sloshing mode of a 4 x 2 x 0.5 m box);
* a lid at z = 0 (on the free surface) gave spurious positive heave damping
  of 100 to 300 kg/s at 7 to 9 rad/s, where the true value is about 10 kg/s;
* a lid whose edge cuts through the middle of a row of wall panels (e.g. at
  ``mesh.lowest_lid_position(12)`` = -0.0616 m with 0.125 m wall panels,
  whose collocation points are at -0.0625 m) gave grossly wrong results
  (A33 8 % off even at 3 rad/s, negative damping);
* the lid must be shallower than ``mesh.lowest_lid_position(omega_max)`` for
  its own irregular frequencies to stay above omega_max (checked below).

Memory
------
Capytaine 3.0.0 keeps every doubly-symmetric influence matrix alive in an
``functools.lru_cache`` on ``NestedBlockCirculantMatrix.to_BlockCirculantMatrix``.
This script solves one frequency at a time and calls that method's
``cache_clear()`` after each frequency, which keeps memory flat.

Usage
-----
    python hydro_reference.py                      # reference data -> box_4x2x1_d0.5.npz
    python hydro_reference.py --convergence        # mesh-convergence study (3 meshes)

Requires capytaine==3.0.0 (and its dependencies numpy, scipy, xarray).
"""

from __future__ import annotations

import argparse
import time
from dataclasses import dataclass, field
from pathlib import Path

import capytaine as cpt
import numpy as np
import xarray as xr
from capytaine.meshes.symmetric_meshes import ReflectionSymmetricMesh
from capytaine.post_pro import rao as cpt_rao
from capytaine.tools.block_circulant_matrices import NestedBlockCirculantMatrix

DOF_NAMES = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")

CONVENTIONS = """\
Conventions of this file (Capytaine 3.0.0; file:line refer to the installed package capytaine/).

Frames and dofs
- Body frame FLU: x forward (bow at x = +2 m), y to port (left), z up. Origin = centre of the
  box's bounding box = on the calm-water plane (z = 0) at the centre of the waterplane.
- Dof order: Surge, Sway, Heave, Roll, Pitch, Yaw (array index 0..5). Translations are
  along x, y, z; rotations are right-handed about x, y, z (roll positive = port side up, starboard
  down; pitch positive = bow down; yaw positive = bow to port).
- Rotation centre of all rotational dofs = centre of mass (0, 0, -0.2) m. Hence moments
  (rows 3..5 of forces, coefficients) are about the CoM, and the translational RAOs are the
  motions of the CoM (heave of the CoM equals heave at the origin to first order; surge at
  the origin = surge_CoM + 0.2 * pitch, sway at the origin = sway_CoM - 0.2 * roll).
- added_mass[w, i, j], radiation_damping[w, i, j]: force/moment on dof i (influenced dof)
  due to a unit motion of dof j (radiating dof). Same for hydrostatic_stiffness and
  inertia_matrix.

Time convention
- Complex amplitudes X represent the real signal x(t) = Re[X exp(-i omega t)].
  Evidence: free-surface elevation eta = -(1/g) dPhi/dt is coded with d/dt -> -i omega
  (bem/solver.py:559); the dynamic pressure p = -rho dPhi/dt is coded as
  p = 1j * omega * rho * Phi (bem/airy_waves.py:98); the RAO impedance is
  H = -omega^2 (M + A) - i omega B + C (post_pro/impedance.py:55-57); the animation uses
  Re[X exp(-1j omega t)] (ui/vedo_animations.py:98); the radiation body condition is the
  normal velocity -i omega (dof . n) of a unit-amplitude motion (bem/problems_and_results.py:449).
- With this convention, the radiation force on dof i for a motion Re[xi_j exp(-i omega t)]
  is F_i = (omega^2 A_ij + i omega B_ij) xi_j (bem/problems_and_results.py:585 and :592
  extract A = Re(F)/omega^2 and B = Im(F)/omega from the force of a unit-amplitude motion),
  i.e. in the time domain F = -A x'' - B x'.

Incident wave, direction and phase reference
- Incident potential (deep water): Phi_0 = -i g/omega exp(k z) exp(i k (x cos beta + y sin beta))
  (bem/airy_waves.py:43 and :52), beta = wave direction in radians.
- Hence the incident elevation is eta_0 = (i omega/g) Phi_0 at z = 0 (bem/airy_waves.py:122)
  = exp(i k (x cos beta + y sin beta)), i.e. in real form
  eta_0(x, y, t) = a cos(k (x cos beta + y sin beta) - omega t) per unit amplitude a = 1 m.
  Phase reference: a wave crest is at the origin at t = 0 (eta_0 = a cos(omega t) at the
  origin).
- beta is the direction the waves PROPAGATE TOWARD, measured from +x toward +y:
  beta = 0: waves travel toward +x (following seas for a boat whose bow points to +x);
  beta = pi (180 deg): waves travel toward -x, coming from ahead = HEAD seas;
  beta = pi/2 (90 deg): waves travel toward +y (toward port), i.e. coming from starboard
  = beam seas. The orbital velocity under a crest points along (cos beta, sin beta)
  (bem/airy_waves.py:89-91), confirming propagation toward beta.
- Forces are the force of the fluid on the body: F_i = -integral p n . dof_i dS
  (bodies/bodies.py:246-247), n pointing out of the body into the fluid.
  excitation = froude_krylov + diffraction.

Units (per unit wave amplitude, a = 1 m)
- omega in rad/s; directions in rad.
- added_mass: kg (translation-translation), kg m (coupling), kg m^2 (rotation-rotation).
- radiation_damping: kg/s, kg m/s, kg m^2/s. hydrostatic_stiffness: N/m, N, N m/rad.
- froude_krylov, diffraction: N/m (forces, rows 0-2) and N m/m (moments about the CoM,
  rows 3-5), complex, with the phase relative to eta_0 at the origin as above.
- rao: m/m (surge, sway, heave of the CoM) and rad/m (roll, pitch, yaw), complex, same phase
  reference. No viscous damping, no mooring: surge, sway and yaw have no restoring force.
- natural_period_dry, natural_period_wet and damping_ratio are for [heave, roll, pitch] (uncoupled,
  diagonal terms only).
"""


NOTES = """\
Accuracy notes (measured with this script, `--convergence`, meshes of 8 / 12 / 18 panels per metre;
this file uses 12 panels per metre).
- Mesh convergence near the resonances (2.0-4.7 rad/s), change from 12/m to 18/m:
  A33, A44, A55 within 0.3 %; B33 within 0.6 %, B44 within 1.4 %, B55 within 0.9 %;
  heave excitation (head seas) and roll excitation (beam seas) within 0.9 %.
  The convergence is roughly first order in the panel size, so the 12/m values are
  estimated to be within about 1 % (added mass) and 2-4 % (damping, B44 worst, too low)
  of the converged values.
- Coupling terms A15/A51, A24/A42 (and B) should be symmetric; the computed matrices are
  not exactly: up to 2.4 % (A) and 4.8 % (B) of sqrt(X_ii X_jj) at 12/m, decreasing
  slowly with refinement. Symmetrise if needed.
- Capytaine's wavelength/8 panel-size criterion holds up to omega = 11.4 rad/s on this mesh.
- The omega grid (step 0.295 rad/s) does not resolve the lightly damped roll resonance
  (half-width about 0.12 rad/s): linear interpolation of `rao` near 3.1 rad/s can be off by
  tens of percent. Interpolate added_mass, radiation_damping and the excitation (smooth) and
  solve (-omega^2 (M + A) - i omega B + C) x = F instead (within ~1-2 % of direct solves).
- Irregular frequencies are removed by an interior lid at z = lid_z (see hydro_reference.py).
- Natural periods are uncoupled (diagonal) estimates; sway-roll and surge-pitch coupling
  are ignored there (they are included in `rao`).
"""

# --------------------------------------------------------------------------------------
# Case definition
# --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class BoxCase:
    length: float = 4.0          # m, along x
    beam: float = 2.0            # m, along y
    height: float = 1.0          # m, along z
    draft: float = 0.5           # m (reference point = box centre at z = 0)
    mass: float = 4100.0         # kg
    center_of_mass: tuple = (0.0, 0.0, -0.2)  # m, body frame
    rho: float = 1025.0          # kg/m^3
    g: float = 9.81              # m/s^2
    water_depth: float = np.inf  # deep water

    def inertia_matrix(self) -> np.ndarray:
        """6x6 rigid-body inertia matrix about the centre of mass (solid box, principal)."""
        m, L, B, H = self.mass, self.length, self.beam, self.height
        ixx = m * (B**2 + H**2) / 12.0
        iyy = m * (L**2 + H**2) / 12.0
        izz = m * (L**2 + B**2) / 12.0
        return np.diag([m, m, m, ixx, iyy, izz])

    def analytic_hydrostatic_stiffness(self) -> np.ndarray:
        """Exact hydrostatic stiffness of the box about the CoM (for checking Capytaine)."""
        L, B, T = self.length, self.beam, self.draft
        rg = self.rho * self.g
        V = L * B * T
        zb, zg = -T / 2.0, self.center_of_mass[2]
        C = np.zeros((6, 6))
        C[2, 2] = rg * L * B
        # Capytaine's rigid-body formula with rotation centre z_c:
        # rho g (I_wp + V (zb - z_c)) - m g (zg - z_c); here z_c = zg.
        C[3, 3] = rg * (L * B**3 / 12.0 + V * (zb - zg))
        C[4, 4] = rg * (B * L**3 / 12.0 + V * (zb - zg))
        return C


@dataclass
class Mesher:
    """Panel mesh of the immersed box and its interior lid.

    n_per_metre: panels per metre horizontally; the draft gets the same number of panels
    as one metre of length (n_per_metre rows over 0.5 m), and the lid lies on the first
    row of wall-panel edges, z_lid = -draft / nz.
    """
    case: BoxCase
    n_per_metre: int = 12
    nx: int = field(init=False)
    ny: int = field(init=False)
    nz: int = field(init=False)
    z_lid: float = field(init=False)

    def __post_init__(self):
        c = self.case
        self.nx = round(c.length * self.n_per_metre)
        self.ny = round(c.beam * self.n_per_metre)
        self.nz = round(2.0 * c.draft * self.n_per_metre)
        for n in (self.nx, self.ny):
            if n % 2:
                raise ValueError("the symmetric mesh needs an even number of panels in x and y")
        self.z_lid = -c.draft / self.nz

    def hull(self):
        c = self.case
        return cpt.mesh_parallelepiped(
            size=(c.length, c.beam, c.draft), center=(0.0, 0.0, -c.draft / 2.0),
            resolution=(self.nx, self.ny, self.nz), missing_sides={"top"},
            reflection_symmetry=True, name="box_hull")

    def lid(self):
        """Full rectangular lid at z_lid, with the same symmetry structure as the hull.

        Built as one quarter (x < 0, y < 0) mirrored about yOz then xOz, exactly like
        mesh_parallelepiped(reflection_symmetry=True), so that the joined hull+lid mesh
        keeps both symmetries.  mesh_rectangle's `size` is (extent in y, extent in x)
        for a horizontal rectangle.
        """
        c = self.case
        quarter = cpt.mesh_rectangle(
            size=(c.beam / 2.0, c.length / 2.0), resolution=(self.ny // 2, self.nx // 2),
            center=(-c.length / 4.0, -c.beam / 4.0, self.z_lid), normal=(0.0, 0.0, -1.0),
            name="quarter_of_lid")
        half = ReflectionSymmetricMesh(quarter, plane="yOz", name="half_of_lid")
        return ReflectionSymmetricMesh(half, plane="xOz", name="box_lid")


def make_body(case: BoxCase, mesher: Mesher, *, with_lid: bool = True) -> cpt.FloatingBody:
    cog = np.asarray(case.center_of_mass, dtype=float)
    body = cpt.FloatingBody(
        mesh=mesher.hull(), lid_mesh=mesher.lid() if with_lid else None,
        dofs=cpt.rigid_body_dofs(rotation_center=cog),
        center_of_mass=cog, mass=case.mass, name="box_4x2x1")
    assert tuple(body.dofs) == DOF_NAMES, tuple(body.dofs)
    return body


def hydrostatic_stiffness(case: BoxCase, mesher: Mesher) -> np.ndarray:
    """Capytaine's 6x6 hydrostatic stiffness, with Gauss-Legendre-2 surface quadrature.

    The default one-point (centroid) quadrature is ~0.3 % off for the second moments of
    the waterplane; Gauss-Legendre 2 is exact for this box.  A separate non-symmetric
    copy of the hull is used (the quadrature only matters here, not in the BEM solve).
    """
    mesh = mesher.hull().merged().with_quadrature("Gauss-Legendre 2")
    cog = np.asarray(case.center_of_mass, dtype=float)
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=cog),
                            center_of_mass=cog, mass=case.mass)
    K = body.compute_hydrostatic_stiffness(rho=case.rho, g=case.g)
    return K.sel(influenced_dof=list(DOF_NAMES), radiating_dof=list(DOF_NAMES)).values


def as_dof_matrix(M: np.ndarray, name: str) -> xr.DataArray:
    return xr.DataArray(M, dims=["influenced_dof", "radiating_dof"],
                        coords={"influenced_dof": list(DOF_NAMES),
                                "radiating_dof": list(DOF_NAMES)},
                        name=name)


# --------------------------------------------------------------------------------------
# BEM solution
# --------------------------------------------------------------------------------------
def solve_frequencies(body, case: BoxCase, omegas, directions, *, radiating_dofs=DOF_NAMES,
                      solver=None, label="", log=print):
    """Solve radiation (given dofs) and diffraction (given directions) problems.

    One frequency at a time; the lru_cache of NestedBlockCirculantMatrix is cleared after
    each frequency (memory trap of Capytaine 3.0.0).  Diffraction is skipped for
    omega = 0 and omega = inf (undefined there).  Returns the list of results.
    """
    solver = solver or cpt.BEMSolver()
    env = dict(rho=case.rho, g=case.g, water_depth=case.water_depth)
    results = []
    t0 = time.perf_counter()
    for i, w in enumerate(omegas):
        w = float(w)
        problems = [cpt.RadiationProblem(body=body, radiating_dof=d, omega=w, **env)
                    for d in radiating_dofs]
        if 0.0 < w < np.inf:
            problems += [cpt.DiffractionProblem(body=body, wave_direction=float(b), omega=w, **env)
                         for b in directions]
        # _check_wavelength=False: the resolution / irregular-frequency warnings are
        # handled explicitly in main() (Capytaine's estimate does not see that our lid
        # is fully closing).
        results += solver.solve_all(problems, progress_bar=False, _check_wavelength=False)
        NestedBlockCirculantMatrix.to_BlockCirculantMatrix.cache_clear()
        log(f"  {label}[{i + 1:2d}/{len(omegas)}] omega = {w:8.4f} rad/s, "
            f"{len(problems):2d} problems, elapsed {time.perf_counter() - t0:7.1f} s")
    return results


def added_mass_only(results, omega_value) -> np.ndarray:
    """6x6 added mass from radiation results at one (possibly 0 or inf) frequency."""
    A = np.full((6, 6), np.nan)
    for r in results:
        if r.__class__.__name__ == "RadiationResult" and float(r.omega) == omega_value:
            j = DOF_NAMES.index(r.radiating_dof)
            for i, d in enumerate(DOF_NAMES):
                A[i, j] = r.added_mass[d]
    return A


# --------------------------------------------------------------------------------------
# Post-processing
# --------------------------------------------------------------------------------------
def natural_frequency(C, M, omega_grid, A_grid, *, tol=1e-12, max_iter=200):
    """Fixed point omega = sqrt(C / (M + A(omega))), A linearly interpolated on the grid."""
    w = np.sqrt(C / M)
    for _ in range(max_iter):
        w_new = np.sqrt(C / (M + np.interp(w, omega_grid, A_grid)))
        if abs(w_new - w) < tol:
            return w_new
        w = w_new
    raise RuntimeError("natural-frequency iteration did not converge")


def resonance_table(omega, A, B, C, M):
    """Uncoupled natural periods and damping ratios for heave, roll, pitch."""
    out = {}
    for name, k in (("heave", 2), ("roll", 3), ("pitch", 4)):
        w_dry = np.sqrt(C[k, k] / M[k, k])
        w_n = natural_frequency(C[k, k], M[k, k], omega, A[:, k, k])
        a_n = np.interp(w_n, omega, A[:, k, k])
        b_n = np.interp(w_n, omega, B[:, k, k])
        zeta = b_n / (2.0 * np.sqrt(C[k, k] * (M[k, k] + a_n)))
        out[name] = dict(T_dry=2 * np.pi / w_dry, omega_n=w_n, T_wet=2 * np.pi / w_n,
                         A_n=a_n, B_n=b_n, zeta=zeta)
    return out


def interp_complex(x_new, x, y):
    """Linear interpolation of a complex array along its first axis."""
    y = np.asarray(y)
    flat = y.reshape(len(x), -1)
    re = np.array([np.interp(x_new, x, flat[:, j].real) for j in range(flat.shape[1])]).T
    im = np.array([np.interp(x_new, x, flat[:, j].imag) for j in range(flat.shape[1])]).T
    return (re + 1j * im).reshape((len(np.atleast_1d(x_new)),) + y.shape[1:])


def omega_of_wavelength(lam, g):
    """Deep-water dispersion: omega = sqrt(g k), k = 2 pi / lambda."""
    return np.sqrt(g * 2.0 * np.pi / np.asarray(lam, dtype=float))


# --------------------------------------------------------------------------------------
# Main computation
# --------------------------------------------------------------------------------------
def compute_reference(out_path: Path, n_per_metre: int, n_omega: int, omega_min: float,
                      omega_max: float, directions_deg, log=print):
    t_start = time.perf_counter()
    case = BoxCase()
    mesher = Mesher(case, n_per_metre)
    body = make_body(case, mesher)
    hull, lid = body.mesh, body.lid_mesh

    omega = np.linspace(omega_min, omega_max, n_omega)
    directions = np.radians(np.asarray(directions_deg, dtype=float))

    # Mesh sanity checks.
    z_lid_min = hull.lowest_lid_position(omega_max, g=case.g)
    log(f"Capytaine {cpt.__version__}")
    log(f"Hull: {mesher.nx} x {mesher.ny} panels on the bottom, {mesher.nz} over the draft: "
        f"{hull.nb_faces} panels; lid: {lid.nb_faces} panels at z = {mesher.z_lid:.4f} m "
        f"(must be above lowest_lid_position({omega_max}) = {z_lid_min:.4f} m)")
    if mesher.z_lid < z_lid_min:
        log("WARNING: lid too deep; its own irregular frequencies fall below omega_max")
    max_radius = max(hull.faces_radiuses.max(), lid.faces_radiuses.max())
    w_ok = np.sqrt(case.g * 2 * np.pi / (8 * max_radius))
    log(f"Largest panel radius {max_radius:.4f} m: Capytaine's wavelength/8 criterion is met "
        f"for omega <= {w_ok:.2f} rad/s")
    log(f"Volume {hull.volume:.6f} m^3 (exact {case.length * case.beam * case.draft}), "
        f"displaced mass {case.rho * hull.volume:.3f} kg, body mass {case.mass} kg")

    # Hydrostatics and inertia.
    C = hydrostatic_stiffness(case, mesher)
    C_exact = case.analytic_hydrostatic_stiffness()
    M = case.inertia_matrix()
    log("Hydrostatic stiffness diag (Capytaine GL2): "
        + ", ".join(f"{v:.2f}" for v in np.diag(C)))
    log("                         diag (analytic):   "
        + ", ".join(f"{v:.2f}" for v in np.diag(C_exact)))
    log(f"  max |C - C_exact| = {np.abs(C - C_exact).max():.3e}")

    # BEM: finite frequencies (radiation + diffraction), then 0 and inf (radiation only).
    solver = cpt.BEMSolver()
    n_pb = n_omega * (6 + len(directions)) + 12
    log(f"Solving {n_pb} BEM problems ({n_omega} frequencies x (6 radiation + "
        f"{len(directions)} diffraction) + 2 x 6 radiation at omega = 0 and inf)")
    t_bem = time.perf_counter()
    res = solve_frequencies(body, case, omega, directions, solver=solver, log=log)
    res_lim = solve_frequencies(body, case, [0.0, np.inf], directions, solver=solver,
                                label="limits ", log=log)
    t_bem = time.perf_counter() - t_bem
    log(f"BEM solve time: {t_bem:.1f} s")

    ds = cpt.assemble_dataset(res)
    ds["inertia_matrix"] = as_dof_matrix(M, "inertia_matrix")
    ds["hydrostatic_stiffness"] = as_dof_matrix(C, "hydrostatic_stiffness")
    sel = dict(omega=omega, wave_direction=directions)
    dofs2 = dict(influenced_dof=list(DOF_NAMES), radiating_dof=list(DOF_NAMES))

    def mat(name):
        return (ds[name].sel(omega=omega, **dofs2)
                .transpose("omega", "influenced_dof", "radiating_dof").values)

    def exc(name):
        return (ds[name].sel(**sel, influenced_dof=list(DOF_NAMES))
                .transpose("omega", "wave_direction", "influenced_dof").values)

    A, B = mat("added_mass"), mat("radiation_damping")
    FK, DF = exc("Froude_Krylov_force"), exc("diffraction_force")
    X = (cpt_rao(ds).sel(**sel, radiating_dof=list(DOF_NAMES))
         .transpose("omega", "wave_direction", "radiating_dof").values)
    A_inf = added_mass_only(res_lim, np.inf)
    A_zero = added_mass_only(res_lim, 0.0)

    reson = resonance_table(omega, A, B, C, M)
    keys = ("heave", "roll", "pitch")

    data = dict(
        omega=omega, added_mass=A, radiation_damping=B,
        added_mass_inf=A_inf, added_mass_zero=A_zero,
        directions=directions, froude_krylov=FK, diffraction=DF, rao=X,
        hydrostatic_stiffness=C, inertia_matrix=M,
        center_of_mass=np.asarray(case.center_of_mass, dtype=float),
        panels=np.array(hull.nb_faces), lid_panels=np.array(lid.nb_faces),
        capytaine_version=np.array(str(cpt.__version__)),
        conventions=np.array(CONVENTIONS),
        notes=np.array(NOTES),
        # Extra metadata (plain arrays).
        dof_names=np.array(DOF_NAMES),
        box_size=np.array([case.length, case.beam, case.height]),
        draft=np.array(case.draft), mass=np.array(case.mass),
        rho=np.array(case.rho), g=np.array(case.g), water_depth=np.array(case.water_depth),
        mesh_resolution=np.array([mesher.nx, mesher.ny, mesher.nz]),
        lid_z=np.array(mesher.z_lid),
        resonance_dofs=np.array(keys),
        natural_period_dry=np.array([reson[k]["T_dry"] for k in keys]),
        natural_period_wet=np.array([reson[k]["T_wet"] for k in keys]),
        damping_ratio=np.array([reson[k]["zeta"] for k in keys]),
    )
    for k, v in data.items():
        assert v.dtype != object, k
    out_path.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(out_path, **data)
    # Round trip check: loadable without pickle.
    with np.load(out_path, allow_pickle=False) as f:
        assert set(f.files) == set(data)

    # ---------------------------------------------------------------- summary
    log("")
    log("Natural periods (uncoupled) and radiation damping ratios:")
    for k in keys:
        r = reson[k]
        log(f"  {k:5s}: T_dry = {r['T_dry']:.4f} s, T_n = {r['T_wet']:.4f} s "
            f"(omega_n = {r['omega_n']:.4f} rad/s), A(omega_n) = {r['A_n']:.1f}, "
            f"B(omega_n) = {r['B_n']:.1f}, zeta = {r['zeta']:.4f}")
    log("A33, A44, A55 at omega = 0: " + ", ".join(f"{A_zero[i, i]:.1f}" for i in (2, 3, 4)))
    log("A33, A44, A55 at omega = inf: " + ", ".join(f"{A_inf[i, i]:.1f}" for i in (2, 3, 4)))

    wavelength_check(body, case, solver, omega, directions, A, B, C, X, FK, DF, log=log)
    log("")
    log(f"Saved {out_path}")
    log(f"Total run time: {time.perf_counter() - t_start:.1f} s")
    return data


def wavelength_check(body, case, solver, omega, directions, A, B, C, X, FK, DF,
                     lam_over_L=(0.5, 0.7, 1.0, 1.4, 2.0, 3.0, 5.0, 10.0), log=print):
    """Print RAOs and heave excitation at given wavelength / length ratios.

    A, B: (W,6,6) coefficients on the grid omega; C: (6,6) stiffness; X, FK, DF: (W,D,6).

    Three estimates: (a) linear interpolation of the stored RAO on the omega grid,
    (b) RAO rebuilt from linearly interpolated A, B, F (smooth quantities), and
    (c) a direct BEM solve at exactly those frequencies (head and beam seas only).
    Near the lightly damped roll and pitch resonances the grid under-resolves the RAO
    peak, so (a) can be tens of percent off while (b) stays close to (c).
    """
    lam_over_L = np.asarray(lam_over_L, dtype=float)
    w_lam = omega_of_wavelength(lam_over_L * case.length, case.g)
    i_head = int(np.argmin(np.abs(directions - np.pi)))
    i_beam = int(np.argmin(np.abs(directions - np.pi / 2)))
    # (a) interpolated RAO / forces
    Xa = interp_complex(w_lam, omega, X)
    Fa = interp_complex(w_lam, omega, FK + DF)
    FKa = interp_complex(w_lam, omega, FK)
    # (c) direct solve
    dirs = directions[[i_beam, i_head]]
    res = solve_frequencies(body, case, w_lam, dirs, solver=solver, label="lambda-check ",
                            log=lambda *a: None)
    ds = cpt.assemble_dataset(res)
    M = case.inertia_matrix()
    ds["inertia_matrix"] = as_dof_matrix(M, "inertia_matrix")
    ds["hydrostatic_stiffness"] = as_dof_matrix(C, "hydrostatic_stiffness")
    Xc = (cpt_rao(ds).sel(omega=w_lam, radiating_dof=list(DOF_NAMES))
          .transpose("omega", "wave_direction", "radiating_dof").values)
    Fc = (ds.excitation_force.sel(omega=w_lam, influenced_dof=list(DOF_NAMES))
          .transpose("omega", "wave_direction", "influenced_dof").values)
    FKc = (ds.Froude_Krylov_force.sel(omega=w_lam, influenced_dof=list(DOF_NAMES))
           .transpose("omega", "wave_direction", "influenced_dof").values)
    # (b) RAO from interpolated coefficients
    A_b = interp_complex(w_lam, omega, A).real
    B_b = interp_complex(w_lam, omega, B).real
    Xb = np.array([[np.linalg.solve(-w**2 * (M + A_b[j]) - 1j * w * B_b[j] + C,
                                    Fa[j, d]) for d in range(len(directions))]
                   for j, w in enumerate(w_lam)])

    def deg(z):
        return np.degrees(np.abs(z))

    log("")
    log("RAOs at wavelengths lambda/L (head seas = 180 deg, beam seas = 90 deg).")
    log("Each cell: direct solve / RAO rebuilt from interpolated A,B,F / RAO interpolated.")
    log(" lam/L  omega  | heave head (m/m)          | pitch head (deg/m)       | roll beam (deg/m)")
    for j, (r, w) in enumerate(zip(lam_over_L, w_lam, strict=False)):
        log(f" {r:5.1f} {w:6.3f} | {abs(Xc[j, 1, 2]):7.4f} {abs(Xb[j, i_head, 2]):7.4f} "
            f"{abs(Xa[j, i_head, 2]):7.4f}   | {deg(Xc[j, 1, 4]):7.2f} "
            f"{deg(Xb[j, i_head, 4]):7.2f} "
            f"{deg(Xa[j, i_head, 4]):7.2f}  | {deg(Xc[j, 0, 3]):7.2f} {deg(Xb[j, i_beam, 3]):7.2f} "
            f"{deg(Xa[j, i_beam, 3]):7.2f}")
    log("Heave excitation in head seas, N/m: direct / interpolated")
    log(" lam/L  omega  |  |FK + diffraction|   |  |FK| alone")
    for j, (r, w) in enumerate(zip(lam_over_L, w_lam, strict=False)):
        log(f" {r:5.1f} {w:6.3f} | {abs(Fc[j, 1, 2]):9.1f} {abs(Fa[j, i_head, 2]):9.1f} | "
            f"{abs(FKc[j, 1, 2]):9.1f} {abs(FKa[j, i_head, 2]):9.1f}")
    log("Phases of the direct RAOs (deg, relative to the incident crest at the origin, "
        "exp(-i omega t)):")
    for j, r in enumerate(lam_over_L):
        log(f" {r:5.1f}: heave head {np.degrees(np.angle(Xc[j, 1, 2])):7.1f}, "
            f"pitch head {np.degrees(np.angle(Xc[j, 1, 4])):7.1f}, "
            f"roll beam {np.degrees(np.angle(Xc[j, 0, 3])):7.1f}")


# --------------------------------------------------------------------------------------
# Mesh convergence
# --------------------------------------------------------------------------------------
def convergence_study(out_path: Path, levels=(8, 12, 18), omegas=None,
                      directions_deg=(90.0, 135.0, 180.0), log=print):
    """Radiation (all dofs) and diffraction (3 directions) at 10 frequencies around the
    heave / roll / pitch resonances, on meshes with n panels per metre for n in levels
    (each level 1.5x the previous per edge)."""
    t_start = time.perf_counter()
    case = BoxCase()
    omegas = np.linspace(2.0, 4.7, 10) if omegas is None else np.asarray(omegas)
    directions = np.radians(directions_deg)
    store = {"omega": omegas, "directions": directions, "levels": np.array(levels)}
    for n in levels:
        mesher = Mesher(case, n)
        body = make_body(case, mesher)
        t0 = time.perf_counter()
        res = solve_frequencies(body, case, omegas, directions, label=f"n={n} ", log=log)
        dt = time.perf_counter() - t0
        ds = cpt.assemble_dataset(res)
        dofs2 = dict(influenced_dof=list(DOF_NAMES), radiating_dof=list(DOF_NAMES))
        store[f"A_{n}"] = ds.added_mass.sel(**dofs2).transpose("omega", ...).values
        store[f"B_{n}"] = ds.radiation_damping.sel(**dofs2).transpose("omega", ...).values
        store[f"F_{n}"] = (ds.excitation_force.sel(influenced_dof=list(DOF_NAMES))
                           .transpose("omega", "wave_direction", "influenced_dof").values)
        store[f"FK_{n}"] = (ds.Froude_Krylov_force.sel(influenced_dof=list(DOF_NAMES))
                            .transpose("omega", "wave_direction", "influenced_dof").values)
        store[f"panels_{n}"] = np.array([body.mesh.nb_faces, body.lid_mesh.nb_faces])
        store[f"time_{n}"] = np.array(dt)
        log(f"n = {n}/m: {body.mesh.nb_faces} hull + {body.lid_mesh.nb_faces} lid panels, "
            f"{dt:.1f} s")
    np.savez_compressed(out_path, **store)

    ref = levels[-1]
    i_head = int(np.argmin(np.abs(directions - np.pi)))
    i_beam = int(np.argmin(np.abs(directions - np.pi / 2)))
    log("")
    log(f"Relative change vs the finest mesh (n = {ref}/m), in %, one column per coarser mesh "
        f"({', '.join(str(n) for n in levels[:-1])} panels/m); excitation: |F - F_ref|/|F_ref|:")
    hdr = " omega " + "".join(f" | {q:^{7 * (len(levels) - 1)}s}" for q in
                               ("A33", "A44", "A55", "B33", "B44", "B55", "F3 head", "F4 beam"))
    log(hdr)
    for i, w in enumerate(omegas):
        row = f" {w:5.2f} "
        for key, (a, b) in (("A", (2, 2)), ("A", (3, 3)), ("A", (4, 4)),
                            ("B", (2, 2)), ("B", (3, 3)), ("B", (4, 4))):
            r = store[f"{key}_{ref}"][i, a, b]
            row += " | " + "".join(f"{100 * (store[f'{key}_{n}'][i, a, b] - r) / r:+6.2f} "
                                   for n in levels[:-1])
        for d, k in ((i_head, 2), (i_beam, 3)):
            r = store[f"F_{ref}"][i, d, k]
            row += " | " + "".join(f"{100 * abs(store[f'F_{n}'][i, d, k] - r) / abs(r):6.2f} "
                                   for n in levels[:-1])
        log(row)
    log("")
    log("Asymmetry of the coupling terms (exactly symmetric in theory), max over omega of "
        "|X_ij - X_ji| / sqrt(X_ii X_jj), per mesh:")
    for n in levels:
        parts = []
        for key in ("A", "B"):
            X = store[f"{key}_{n}"]
            for i, j in ((0, 4), (1, 3)):
                e = np.abs(X[:, i, j] - X[:, j, i]) / np.sqrt(np.abs(X[:, i, i] * X[:, j, j]))
                parts.append(f"{key}{i + 1}{j + 1}: {100 * e.max():.2f} %")
        log(f"  n = {n:2d}/m: " + ", ".join(parts))
    log(f"Saved {out_path}")
    log(f"Total run time: {time.perf_counter() - t_start:.1f} s")
    return store


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", type=Path, default=Path(__file__).with_name("box_4x2x1_d0.5.npz"))
    p.add_argument("--panels-per-metre", type=int, default=12)
    p.add_argument("--n-omega", type=int, default=40)
    p.add_argument("--omega-min", type=float, default=0.5)
    p.add_argument("--omega-max", type=float, default=12.0)
    p.add_argument("--directions-deg", type=float, nargs="+", default=[0, 45, 90, 135, 180])
    p.add_argument("--convergence", action="store_true",
                   help="run the mesh-convergence study instead (8, 12, 18 panels per metre)")
    p.add_argument("--convergence-out", type=Path,
                   default=Path(__file__).with_name("convergence_box_4x2x1_d0.5.npz"))
    args = p.parse_args()
    if args.convergence:
        convergence_study(args.convergence_out)
    else:
        compute_reference(args.out, args.panels_per_metre, args.n_omega, args.omega_min,
                          args.omega_max, args.directions_deg)


if __name__ == "__main__":
    main()
