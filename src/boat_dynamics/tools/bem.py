"""Linear potential-flow (BEM) coefficients of any closed hull mesh, with Capytaine 3.0.0.

``boatsim hydro`` (optional extra ``boatsim[bem]``; Capytaine is imported only inside the
functions that solve). Generalizes ``tests/data/hydro/hydro_reference.py`` (a box only): the
panels of :mod:`boat_dynamics.tools.bem_mesh`; radiation (6 dofs about the centre of mass) and
diffraction problems, one frequency at a time (clearing Capytaine 3.0.0's influence-matrix
lru_cache after each), plus the zero- and infinite-frequency added mass; hydrostatics with
Gauss-Legendre-2 quadrature. The result holds the arrays that
:func:`boat_dynamics.physics.potential_flow.hydro.load_coefficients` reads, plus RAOs, metadata,
the key of
the inputs (:func:`boat_dynamics.physics.potential_flow.hydro.hydro_key`) and the conventions text;
:func:`write` saves it.

Only a translation along z separates Capytaine's frame from the body frame, so moments about
the centre of mass, wave phases (referred to x = y = 0) and directions need no conversion.

Measured on the 4 x 2 x 1 m box (draft 0.5 m, CoM (0, 0, -0.2)) against the reference file
(2880 + 1152 lid panels): the default mesh (2120 + 800 lid panels, 48 s on one core) is
within 1 % of it for A, B, A_inf and the excitation (max error relative to each quantity's
maximum), within 1.1 % of a 1.2 times finer mesh; without symmetry the same numbers in 136 s.
Sources: Ancellin & Dias, "Capytaine: a Python-based linear potential flow solver", JOSS 2019;
Newman, "Marine Hydrodynamics" (1977), ch. 6.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from boat_dynamics.physics.potential_flow.hydro import hydro_key
from boat_dynamics.tools.bem_mesh import (
    REL_TOL,
    VERTICAL_STRETCH,
    default_directions,
    default_omegas,
    immersed_panels,
    indexed,
    mirror_symmetric,
)

__all__ = ["CAPYTAINE_VERSION", "DOF_NAMES", "KOCHIN_ANGLES", "MAX_PANELS", "SolvePlan",
           "conventions_text", "plan_hull", "solve_hull", "write"]

LOG = logging.getLogger(__name__)

#: The solver version the files are made and checked with (the ``bem`` extra pins it).
CAPYTAINE_VERSION = "3.0.0"

#: CPU seconds per (panel x block panel) and per block panel^3 of one frequency's 6 radiation
#: and 5 diffraction problems (blocks: the symmetry's copies): fitted to five Capytaine 3.0.0
#: solves on one thread (the 4 x 2 x 1 m box and a 3 m Wigley hull, 760-5,780 panels) within
#: 21 %, measured with the machine's other core busy (docs/DESIGN.md, "boatsim hydro").
ASSEMBLY_SECONDS, FACTOR_SECONDS = 1.07e-6, 2.55e-10

#: The most hull + lid panels :func:`solve_hull` takes by default (memory ~ 0.3 kB x panels^2).
MAX_PANELS = 8000

#: Capytaine's rigid-body dof names, in the order of every 6-vector and 6 x 6 matrix.
DOF_NAMES = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")

#: rad, the angles of the files' Kochin functions (the direction the outgoing wave travels
#: toward, body frame): 0, 5, ..., 355 deg.
KOCHIN_ANGLES = np.radians(np.arange(0.0, 360.0, 5.0))


def _capytaine_mesh(panels: np.ndarray, sym_x: bool, sym_y: bool, name: str):
    """A Capytaine mesh of the panels, wrapped in its reflection symmetries.

    Nested quarter -> yOz -> xOz, as ``mesh_parallelepiped(reflection_symmetry=True)`` does.
    """
    import capytaine as cpt
    from capytaine.meshes.symmetric_meshes import ReflectionSymmetricMesh

    tol = REL_TOL * float(np.ptp(panels.reshape(-1, 3), axis=0).max())
    vertices, faces = indexed(panels, tol)
    faces = [list(q[:3]) if q[3] == q[2] else list(q) for q in faces]
    mesh = cpt.Mesh(vertices, faces, name=name, auto_check=False)
    if sym_x:
        mesh = ReflectionSymmetricMesh(mesh, plane="yOz", name=name)
    if sym_y:
        mesh = ReflectionSymmetricMesh(mesh, plane="xOz", name=name)
    return mesh


# --------------------------------------------------------------------------------------
# Capytaine solve
# --------------------------------------------------------------------------------------
def _solve_frequencies(body, omegas, directions, env: dict) -> list:
    """Capytaine results of radiation (6 dofs) and diffraction problems.

    One frequency at a time (diffraction only for 0 < omega < inf), clearing Capytaine
    3.0.0's cache of doubly-symmetric matrices after each (it otherwise keeps them all).
    """
    import capytaine as cpt
    from capytaine.tools.block_circulant_matrices import NestedBlockCirculantMatrix

    solver = cpt.BEMSolver()
    results, t0 = [], time.perf_counter()
    for i, w in enumerate(omegas):
        w = float(w)
        problems = [cpt.RadiationProblem(body=body, radiating_dof=d, omega=w, **env)
                    for d in DOF_NAMES]
        if 0.0 < w < math.inf:
            problems += [cpt.DiffractionProblem(body=body, wave_direction=float(b), omega=w,
                                                **env) for b in directions]
        results += solver.solve_all(problems, progress_bar=False, _check_wavelength=False)
        NestedBlockCirculantMatrix.to_BlockCirculantMatrix.cache_clear()
        LOG.info("omega %d/%d = %.4f rad/s, %.1f s", i + 1, len(omegas), w,
                 time.perf_counter() - t0)
    return results


def _kochin(results, omegas, directions) -> dict:
    """(W, 6, T) radiation and (W, D, T) diffraction Kochin functions at :data:`KOCHIN_ANGLES`.

    Capytaine's ``compute_kochin`` (post_pro/kochin.py: the panel sources, hull and lid,
    times e^{k z} e^{-i k (x cos theta + y sin theta)} dS / 4 pi about x = y = 0; the indirect
    method's sources, which ``solve_all`` keeps): m^2/s per unit motion amplitude (1 m,
    1 rad) of each dof, and per metre of incident amplitude for the scattered potential.
    """
    from capytaine.post_pro.kochin import compute_kochin

    w_index = {float(w): i for i, w in enumerate(omegas)}
    b_index = {float(b): i for i, b in enumerate(directions)}
    radiation = np.full((len(omegas), 6, len(KOCHIN_ANGLES)), np.nan, dtype=complex)
    diffraction = np.full((len(omegas), len(directions), len(KOCHIN_ANGLES)), np.nan,
                          dtype=complex)
    for r in results:
        i = w_index[float(r.omega)]
        kind = type(r).__name__  # a failed solve stays NaN (as its forces do)
        if kind == "RadiationResult":
            radiation[i, DOF_NAMES.index(r.radiating_dof)] = compute_kochin(r, KOCHIN_ANGLES)
        elif kind == "DiffractionResult":
            diffraction[i, b_index[float(r.wave_direction)]] = compute_kochin(r, KOCHIN_ANGLES)
    return dict(kochin_angles=KOCHIN_ANGLES, kochin_radiation=radiation,
                kochin_diffraction=diffraction)


def _tables(results, omegas, directions) -> dict:
    """(W, 6, 6) added mass and damping, (W, D, 6) Froude-Krylov and diffraction forces.

    And the Kochin functions of every problem (:func:`_kochin`).
    """
    import capytaine as cpt

    ds = cpt.assemble_dataset(results)
    dofs2 = dict(influenced_dof=list(DOF_NAMES), radiating_dof=list(DOF_NAMES))
    sel = dict(omega=omegas, wave_direction=directions, influenced_dof=list(DOF_NAMES))

    def mat(name):
        return (ds[name].sel(omega=omegas, **dofs2)
                .transpose("omega", "influenced_dof", "radiating_dof").values)

    def exc(name):
        return ds[name].sel(**sel).transpose("omega", "wave_direction", "influenced_dof").values

    return dict(added_mass=mat("added_mass"), radiation_damping=mat("radiation_damping"),
                froude_krylov=exc("Froude_Krylov_force"), diffraction=exc("diffraction_force"),
                **_kochin(results, omegas, directions))


def _limit_added_mass(results, omega_value: float) -> np.ndarray:
    """(6, 6) added mass from the radiation results at omega = 0 or inf."""
    A = np.full((6, 6), np.nan)
    for r in results:
        if float(r.omega) == omega_value and type(r).__name__ == "RadiationResult":
            j = DOF_NAMES.index(r.radiating_dof)
            A[:, j] = [r.added_mass[d] for d in DOF_NAMES]
    return A


def _hydrostatic_stiffness(hull_mesh, cog: np.ndarray, mass: float, rho: float,
                           g: float) -> np.ndarray:
    """Capytaine's (6, 6) hydrostatic stiffness about ``cog``.

    Gauss-Legendre-2 quadrature: exact for the second moments of planar panels (the default
    one-point rule is ~0.3 % off).
    """
    import capytaine as cpt

    mesh = hull_mesh.merged().with_quadrature("Gauss-Legendre 2")
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=cog),
                            center_of_mass=cog, mass=mass)
    K = body.compute_hydrostatic_stiffness(rho=rho, g=g)
    return K.sel(influenced_dof=list(DOF_NAMES), radiating_dof=list(DOF_NAMES)).values


def _rao(omegas, M, A, B, C, F) -> np.ndarray:
    """(W, D, 6) RAOs: (-omega^2 (M + A) - i omega B + C) X = F, per frequency."""
    out = np.empty(F.shape, dtype=complex)
    for k, w in enumerate(omegas):
        H = -w**2 * (M + A[k]) - 1j * w * B[k] + C
        out[k] = np.linalg.solve(H, F[k].T).T
    return out


@dataclass(frozen=True)
class SolvePlan:
    """What a solve will do, known before Capytaine is imported.

    Attributes:
        panels: hull panels, whole hull.
        lid_panels: interior-lid panels, whole lid.
        copies: 1, 2 or 4: the reflection symmetries' copies (each block is 1 / copies).
        panel_size: m, the largest panel edge.
        frequencies: solved, the two limits (0, infinity) included.
        directions: wave directions of the diffraction problems.
    """

    panels: int
    lid_panels: int
    copies: int
    panel_size: float
    frequencies: int
    directions: int

    @property
    def cpu_seconds(self) -> float:
        """CPU seconds on one thread, estimated (:data:`ASSEMBLY_SECONDS`)."""
        total = self.panels + self.lid_panels
        block = total / self.copies
        return self.frequencies * (ASSEMBLY_SECONDS * total * block
                                   + FACTOR_SECONDS * self.copies * block**3)

    def describe(self) -> str:
        """One line: panels, frequencies, directions and the estimated CPU time."""
        symmetry = {1: "", 2: ", one symmetry", 4: ", two symmetries"}[self.copies]
        line = (f"{self.panels} hull + {self.lid_panels} lid panels of {self.panel_size:.3g} m"
                f"{symmetry}, {self.frequencies} frequencies x {6 + self.directions} problems: "
                f"about {_duration(self.cpu_seconds)} of CPU")
        if self.panels + self.lid_panels > MAX_PANELS:
            line += (f"; over the {MAX_PANELS}-panel limit (a hull mesh coarser than the "
                     f"panels, or a larger panel size)")
        return line


def _duration(seconds: float) -> str:
    return f"{seconds:.0f} s" if seconds < 90 else f"{seconds / 60:.0f} min"


def plan_hull(vertices, faces, *, draft_offset, gravity=9.81, omegas=None, directions=None,
              panel_size=None, lid_panel_size=None, vertical_stretch=VERTICAL_STRETCH,
              lid=True, symmetry=True, shortest_wavelength=math.inf
              ) -> tuple[SolvePlan, dict, np.ndarray, np.ndarray]:
    """The panels and the plan of :func:`solve_hull` (same arguments), without solving.

    Returns:
        The plan, the panels (:func:`immersed_panels`), the frequencies (rad/s) and the
        directions (rad).
    """
    v, f = np.asarray(vertices, dtype=float), np.asarray(faces, dtype=np.int64)
    omegas = (default_omegas(float(np.ptp(v[:, 0]))) if omegas is None
              else np.asarray(omegas, dtype=float))
    if directions is None:
        directions = default_directions(mirror_symmetric(v, f, 1))
    directions = np.asarray(directions, dtype=float)
    mesh = immersed_panels(v, f, draft_offset=draft_offset, omega_max=float(omegas[-1]),
                           panel_size=panel_size, lid_panel_size=lid_panel_size,
                           vertical_stretch=vertical_stretch, gravity=gravity, lid=lid,
                           symmetry=symmetry, shortest_wavelength=shortest_wavelength)
    copies = (2 if mesh["sym_x"] else 1) * (2 if mesh["sym_y"] else 1)
    plan = SolvePlan(copies * len(mesh["hull"]), copies * len(mesh["lid"]), copies,
                     float(mesh["panel_size"]), len(omegas) + 2, len(directions))
    return plan, mesh, omegas, directions


def solve_hull(vertices, faces, *, draft_offset, mass, center_of_mass, inertia_matrix,
               water_density=1025.0, gravity=9.81, depth=float("inf"), omegas=None,
               directions=None, panel_size=None, lid_panel_size=None,
               vertical_stretch=VERTICAL_STRETCH, lid=True, symmetry=True,
               max_panels=MAX_PANELS, description="", shortest_wavelength=math.inf
               ) -> dict[str, np.ndarray]:
    """Potential-flow coefficients of a hull floating upright at rest.

    Args:
        vertices: (V, 3) m, body frame (FLU, origin at the hull reference point).
        faces: (F, 3) vertex indices, outward normals, closed mesh.
        draft_offset: body-frame z of the calm-water plane (= -z_eq).
        mass: kg.
        center_of_mass: (3,) m, body frame (the rotation centre of the dofs).
        inertia_matrix: (6, 6) rigid-body mass matrix about the centre of mass.
        water_density: rho, kg/m^3.
        gravity: g, m/s^2.
        depth: water depth, m (inf: deep water).
        omegas: (W,) rad/s increasing; default :func:`default_omegas`.
        directions: (D,) rad; default :func:`default_directions`.
        panel_size: largest hull panel edge, m (:func:`immersed_panels`).
        lid_panel_size: largest lid panel edge, m (:func:`immersed_panels`).
        vertical_stretch: panel rows this many times shorter (:func:`immersed_panels`).
        lid: remove irregular frequencies with an interior lid.
        symmetry: exploit the mesh's exact reflection symmetries.
        max_panels: refuse meshes of more hull + lid panels (memory ~ 0.3 kB x panels^2).
        description: free text stored as ``hull``.
        shortest_wavelength: m, the default panel size resolves it
            (:func:`.bem_mesh.default_panel_size`).

    Returns:
        dict of NumPy arrays: those
        :func:`boat_dynamics.physics.potential_flow.hydro.load_coefficients`
        reads, plus ``rao``, ``added_mass_zero``, ``conventions``, ``key`` and metadata.

    Raises:
        ValueError: a hull above the water, or more than ``max_panels`` panels.
    """
    t0 = time.perf_counter()
    v, f = np.asarray(vertices, dtype=float), np.asarray(faces, dtype=np.int64)
    com = np.asarray(center_of_mass, dtype=float)
    M = np.asarray(inertia_matrix, dtype=float)
    plan, mesh, omegas, directions = plan_hull(
        v, f, draft_offset=draft_offset, gravity=gravity, omegas=omegas, directions=directions,
        panel_size=panel_size, lid_panel_size=lid_panel_size,
        vertical_stretch=vertical_stretch, lid=lid, symmetry=symmetry,
        shortest_wavelength=shortest_wavelength)
    if plan.panels + plan.lid_panels > max_panels:
        raise ValueError(f"{plan.panels + plan.lid_panels} panels exceed "
                         f"max_panels = {max_panels}: raise panel_size or max_panels")
    cog = com - np.array([0.0, 0.0, draft_offset])  # calm-water frame
    out = _coefficients(mesh, cog, mass, M, omegas, directions,
                        dict(rho=water_density, g=gravity, water_depth=depth))
    out.update(center_of_mass=com, key=np.array(hydro_key(v, f, mass, com, M, water_density,
                                                           gravity, depth)),
               conventions=np.array(conventions_text(com, draft_offset,
                                                     str(out["capytaine_version"]))),
               hull=np.array(description), waterline_z=np.array(float(draft_offset)),
               lid_z=np.array(mesh["z_lid"] + draft_offset), mass=np.array(float(mass)),
               rho=np.array(float(water_density)), g=np.array(float(gravity)),
               water_depth=np.array(float(depth)),
               solve_seconds=np.array(time.perf_counter() - t0))
    return out


def _coefficients(mesh: dict, cog: np.ndarray, mass: float, M: np.ndarray, omegas,
                  directions, env: dict) -> dict:
    """The BEM solution for the panels of :func:`immersed_panels`.

    Rotations about ``cog`` (calm-water frame); returns the coefficient arrays, RAOs and
    mesh metadata.
    """
    import capytaine as cpt

    hull = _capytaine_mesh(mesh["hull"], mesh["sym_x"], mesh["sym_y"], "hull")
    lid_mesh = (_capytaine_mesh(mesh["lid"], mesh["sym_x"], mesh["sym_y"], "lid")
                if len(mesh["lid"]) else None)
    body = cpt.FloatingBody(mesh=hull, lid_mesh=lid_mesh,
                            dofs=cpt.rigid_body_dofs(rotation_center=cog),
                            center_of_mass=cog, mass=mass, name="hull")
    limits = _solve_frequencies(body, [0.0, math.inf], directions, env)
    out = _tables(_solve_frequencies(body, omegas, directions, env), omegas, directions)
    C = _hydrostatic_stiffness(hull, cog, mass, env["rho"], env["g"])
    out.update(
        omega=omegas, directions=directions, added_mass_inf=_limit_added_mass(limits, math.inf),
        added_mass_zero=_limit_added_mass(limits, 0.0), hydrostatic_stiffness=C,
        inertia_matrix=M,
        rao=_rao(omegas, M, out["added_mass"], out["radiation_damping"], C,
                 out["froude_krylov"] + out["diffraction"]))
    out.update(_metadata(mesh, hull, lid_mesh, env["g"], cpt.__version__))
    return out


def _metadata(mesh: dict, hull, lid_mesh, gravity: float, version: str) -> dict:
    """Plain-array metadata: panel counts, panel size, symmetry, resolution limit."""
    radius = float(hull.faces_radiuses.max())
    if lid_mesh is not None:
        radius = max(radius, float(lid_mesh.faces_radiuses.max()))
    return dict(
        dof_names=np.array(DOF_NAMES), panels=np.array(hull.nb_faces),
        lid_panels=np.array(lid_mesh.nb_faces if lid_mesh is not None else 0),
        panel_size=np.array(mesh["panel_size"]),
        symmetry_planes=np.array([p for p, on in (("yOz", mesh["sym_x"]),
                                                  ("xOz", mesh["sym_y"])) if on] or [""]),
        # Capytaine's criterion: largest panel radius <= wavelength / 8.
        omega_resolved=np.array(math.sqrt(gravity * 2 * math.pi / (8 * radius))),
        capytaine_version=np.array(str(version)))


def write(path, arrays: dict) -> Path:
    """Save ``arrays`` with ``np.savez_compressed`` (plain arrays, no pickles).

    Returns:
        The path written (``.npz`` appended by NumPy if missing).

    Raises:
        ValueError: an array of dtype object (it would need pickling).
    """
    data = {k: np.asarray(v) for k, v in arrays.items()}
    bad = [k for k, v in data.items() if v.dtype == object]
    if bad:
        raise ValueError(f"arrays of dtype object cannot be saved without pickle: {bad}")
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(p, **data)
    return p if p.suffix == ".npz" else p.with_name(p.name + ".npz")


# --------------------------------------------------------------------------------------
# Conventions
# --------------------------------------------------------------------------------------
_CONVENTIONS = """\
Conventions of this file (Capytaine {version}; file:line refer to the installed package capytaine/).

Frames and dofs
- Body frame FLU of boatsim: x forward, y to port (left), z up; origin = the hull reference
  point (centre of the hull mesh's bounding box). The calm-water plane is at body z = {wl:.6g} m
  (the hull floating upright at rest: boatsim's equilibrium height z_eq = {zeq:.6g} m).
- Dof order: Surge, Sway, Heave, Roll, Pitch, Yaw (array index 0..5). Translations are
  along x, y, z; rotations are right-handed about x, y, z (roll positive = port side up,
  starboard down; pitch positive = bow down; yaw positive = bow to port).
- Rotation centre of all rotational dofs = centre of mass ({cx:.6g}, {cy:.6g}, {cz:.6g}) m,
  body frame.
  Hence moments (rows 3..5 of forces, coefficients) are about the CoM, and the translational
  RAOs are the motions of the CoM.
- added_mass[w, i, j], radiation_damping[w, i, j]: force/moment on dof i (influenced dof)
  due to a unit motion of dof j (radiating dof). Same for hydrostatic_stiffness and
  inertia_matrix.

Time convention
- Complex amplitudes X represent the real signal x(t) = Re[X exp(-i omega t)].
  Evidence: free-surface elevation eta = -(1/g) dPhi/dt is coded with d/dt -> -i omega
  (bem/solver.py:559); the dynamic pressure p = -rho dPhi/dt is coded as
  p = 1j * omega * rho * Phi (bem/airy_waves.py:98); the RAO impedance is
  H = -omega^2 (M + A) - i omega B + C (post_pro/impedance.py:55-57); the radiation body
  condition is the normal velocity -i omega (dof . n) of a unit-amplitude motion
  (bem/problems_and_results.py:449).
- With this convention, the radiation force on dof i for a motion Re[xi_j exp(-i omega t)]
  is F_i = (omega^2 A_ij + i omega B_ij) xi_j (bem/problems_and_results.py:585 and :592),
  i.e. in the time domain F = -A x'' - B x'.

Incident wave, direction and phase reference
- Incident potential (deep water): Phi_0 = -i g/omega exp(k z') exp(i k (x cos beta + y sin beta))
  (bem/airy_waves.py:43 and :52), z' = height above the calm water, beta = wave direction (rad).
- Hence the incident elevation is eta_0 = exp(i k (x cos beta + y sin beta)), i.e.
  eta_0(x, y, t) = a cos(k (x cos beta + y sin beta) - omega t) per unit amplitude a = 1 m,
  with x, y body-frame coordinates. Phase reference: a wave crest is at x = y = 0 (above or
  below the hull reference point) at t = 0.
- beta is the direction the waves PROPAGATE TOWARD, measured from +x toward +y:
  beta = 0: following seas; beta = pi (180 deg): head seas; beta = pi/2 (90 deg): waves
  travelling toward port, i.e. coming from starboard = beam seas.
- Forces are the force of the fluid on the body: F_i = -integral p n . dof_i dS
  (bodies/bodies.py:246-247), n pointing out of the body into the fluid.
  excitation = froude_krylov + diffraction.

Units (per unit wave amplitude, a = 1 m)
- omega in rad/s; directions in rad.
- added_mass: kg (translation-translation), kg m (coupling), kg m^2 (rotation-rotation).
- radiation_damping: kg/s, kg m/s, kg m^2/s. hydrostatic_stiffness: N/m, N, N m/rad.
- froude_krylov, diffraction: N/m (forces, rows 0-2) and N m/m (moments about the CoM,
  rows 3-5), complex, with the phase relative to eta_0 at x = y = 0 as above.
- rao: m/m (surge, sway, heave of the CoM) and rad/m (roll, pitch, yaw), complex, same phase
  reference. No viscous damping, no mooring: surge, sway and yaw have no restoring force.

Mesh and accuracy
- Hull panels: `panels` (whole hull, symmetric halves included), largest edge `panel_size`;
  interior lid of `lid_panels` panels at body z = `lid_z` against irregular frequencies.
- Capytaine's wavelength / 8 panel criterion holds for omega <= `omega_resolved`; above it
  the coefficients are less accurate (they are small there).
- The omega grid does not resolve lightly damped resonances in `rao`: interpolate
  added_mass, radiation_damping and the excitation and solve the 6 x 6 system instead.
"""


def conventions_text(center_of_mass, draft_offset: float, version: str = "3.0.0") -> str:
    """The ``conventions`` string of a coefficient file (frames, time, phase, units)."""
    cx, cy, cz = (float(c) for c in center_of_mass)
    return _CONVENTIONS.format(version=version, wl=float(draft_offset),
                               zeq=-float(draft_offset) + 0.0, cx=cx, cy=cy, cz=cz)
