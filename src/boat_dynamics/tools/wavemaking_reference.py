"""Potential-flow reference data for boats that make waves (issue 31), with Capytaine 3.0.0.

Writes the three files of ``tests/data/wavemaking/`` (their README states every array, unit
and convention): the far field of the default 4 x 2 x 1 m box (Kochin functions of its 6
radiation and 4 diffraction problems, and the free-surface elevation they make along three
rays 5-60 m out), the same for a truncated vertical cylinder heaving, and two default boxes
side by side in waves (their 12-dof RAOs against one box's). A wave-making model built on
the Kochin functions is checked against these full (near- and far-field) solutions.

Capytaine is imported only inside the functions that solve (the ``bem`` extra: ``make bem``).
Time dependence e^{-i omega t}; the far field of a problem's potential is, in deep water
(within 0.7 % of Capytaine's own elevations at 100 m; Newman 1977, ch. 6),

    eta(r, theta) ~ (omega / g) sqrt(8 pi k / r) H(theta) exp(i (k r - pi / 4)),

with H Capytaine's Kochin function (capytaine/post_pro/kochin.py: the sources times
e^{k z} e^{-i k (x cos theta + y sin theta)}, integrated and divided by 4 pi).

Usage::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 nice .venv/bin/python -m \
        boat_dynamics.tools.wavemaking_reference [--out DIR] [--only box,cylinder,pair]

Sources: Ancellin & Dias, "Capytaine: a Python-based linear potential flow solver", JOSS
2019; Newman, "Marine Hydrodynamics" (1977), ch. 6 (far field, Haskind, energy).
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from boat_dynamics.tools.bem import DOF_NAMES, _capytaine_mesh, _rao, plan_hull, write

__all__ = ["CYLINDER", "DISTANCES", "HEADINGS_DEG", "OMEGA_INDICES", "PAIR_HEADINGS_DEG",
           "PAIR_Y", "RAYS_DEG", "THETA_DEG", "box_pair", "cylinder", "main",
           "reference_omegas", "single_box"]

#: Indices into the shipped coefficient files' grid linspace(0.5, 12, 40) rad/s: periods
#: 7.9, 5.8, 4.5, 3.7, 2.8, 2.2, 1.8 and 1.45 s (wavelengths 98 m to 3.3 m).
OMEGA_INDICES = (1, 2, 3, 4, 6, 8, 10, 13)

#: Kochin angles, deg (0 = toward +x, 90 = toward +y).
THETA_DEG = np.arange(0.0, 360.0, 5.0)

#: Incident wave directions of the single box, deg (travelling toward; 180 = head seas).
HEADINGS_DEG = (0.0, 45.0, 90.0, 180.0)

#: Rays of the field points, deg, and their distances from the origin, m.
RAYS_DEG = (0.0, 45.0, 90.0)
DISTANCES = np.arange(5.0, 60.01, 2.5)

#: The pair: box centres at y = -PAIR_Y (named starboard) and +PAIR_Y (port), m.
PAIR_Y = 3.0
PAIR_HEADINGS_DEG = (90.0, 180.0)

#: The cylinder: radius, draft (m), water density (kg/m^3); floating: mass rho pi a^2 T.
CYLINDER = dict(radius=1.0, draft=1.0, rho=1025.0)

_ENV = dict(rho=1025.0, g=9.81, water_depth=math.inf)
_SCENARIO = Path(__file__).resolve().parents[3] / "scenarios" / "default.yaml"


def reference_omegas() -> np.ndarray:
    """(8,) rad/s: the shipped grid's frequencies at :data:`OMEGA_INDICES`."""
    return np.linspace(0.5, 12.0, 40)[list(OMEGA_INDICES)]


def _default_boat():
    """(params, z_eq, shipped coefficients) of the default scenario's box."""
    from boat_dynamics.physics.core.model import coefficients_key
    from boat_dynamics.physics.core.tuning import equilibrium_height
    from boat_dynamics.physics.potential_flow.hydro import (
        SHIPPED_COEFFICIENTS,
        find_coefficients,
        load_coefficients,
    )
    from boat_dynamics.physics.scenario import load_scenario

    scenario = load_scenario(_SCENARIO)
    params = scenario.boats[0].params
    key = coefficients_key(params, scenario.sea.depth)
    shipped = load_coefficients(find_coefficients(key, (SHIPPED_COEFFICIENTS,)))
    return params, equilibrium_height(params), shipped


def _box_body(panel_size: float | None, name: str = "hull", y: float = 0.0,
              symmetry: bool = True):
    """A Capytaine body of the default box at rest, centred at (0, y), rotations about its CoM.

    The panels of :func:`boat_dynamics.tools.bem_mesh.immersed_panels` (as ``boatsim hydro``
    makes the shipped file: the same lid, placed for its 12 rad/s).
    """
    import capytaine as cpt

    params, z_eq, _ = _default_boat()
    from boat_dynamics.physics.core.model import hull_mesh

    mesh = hull_mesh(params)
    _, panels, _, _ = plan_hull(mesh.vertices, mesh.faces, draft_offset=-z_eq,
                                omegas=np.linspace(0.5, 12.0, 40), panel_size=panel_size,
                                symmetry=symmetry)
    shift = np.array([0.0, y, 0.0])
    hull = _capytaine_mesh(panels["hull"] + shift, panels["sym_x"], panels["sym_y"], name)
    lid = _capytaine_mesh(panels["lid"] + shift, panels["sym_x"], panels["sym_y"], name + "_lid")
    cog = np.asarray(params.center_of_mass) + np.array([0.0, y, z_eq])
    return cpt.FloatingBody(mesh=hull, lid_mesh=lid, name=name, center_of_mass=cog,
                            mass=params.mass, dofs=cpt.rigid_body_dofs(rotation_center=cog))


def _solve(body, omega: float, dofs, headings_deg) -> list:
    """Radiation (``dofs``) and diffraction (``headings_deg``) results at ``omega``.

    The indirect method, sources kept (Kochin functions and field points need them);
    Capytaine 3.0.0's cache of doubly-symmetric matrices cleared afterwards (as bem.py).
    """
    import capytaine as cpt
    from capytaine.tools.block_circulant_matrices import NestedBlockCirculantMatrix

    problems = [cpt.RadiationProblem(body=body, radiating_dof=d, omega=omega, **_ENV)
                for d in dofs]
    problems += [cpt.DiffractionProblem(body=body, wave_direction=math.radians(b),
                                        omega=omega, **_ENV) for b in headings_deg]
    results = cpt.BEMSolver(method="indirect").solve_all(
        problems, keep_details=True, progress_bar=False, _check_wavelength=False)
    NestedBlockCirculantMatrix.to_BlockCirculantMatrix.cache_clear()
    return results


def _field_points() -> np.ndarray:
    """(rays, distances, 2) m: the points of :data:`RAYS_DEG` x :data:`DISTANCES`."""
    t = np.radians(RAYS_DEG)[:, None]
    return np.stack([DISTANCES * np.cos(t), DISTANCES * np.sin(t)], axis=-1)


def _far_field(results, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(P, theta) Kochin functions and (P, *points.shape[:-1]) elevations of P results."""
    import capytaine as cpt
    from capytaine.post_pro.kochin import compute_kochin

    solver = cpt.BEMSolver(method="indirect")
    theta = np.radians(THETA_DEG)
    flat = points.reshape(-1, 2)
    kochin = np.array([compute_kochin(r, theta) for r in results])
    eta = np.array([solver.compute_free_surface_elevation(flat, r) for r in results])
    return kochin, eta.reshape(len(results), *points.shape[:-1])


def _tables(results, dofs, headings_deg) -> dict:
    """(n, n) added mass and damping, (D, n) excitation (Froude-Krylov + diffraction)."""
    import capytaine as cpt

    ds = cpt.assemble_dataset(results)
    sel = dict(influenced_dof=list(dofs))
    mat = dict(sel, radiating_dof=list(dofs))
    beta = np.radians(headings_deg)
    exc = (ds["Froude_Krylov_force"] + ds["diffraction_force"]).sel(wave_direction=beta, **sel)
    return dict(
        added_mass=ds["added_mass"].sel(**mat).transpose(..., "influenced_dof",
                                                         "radiating_dof").values[0],
        radiation_damping=ds["radiation_damping"].sel(**mat).transpose(
            ..., "influenced_dof", "radiating_dof").values[0],
        excitation=exc.transpose(..., "wave_direction", "influenced_dof").values[0])


def _stack(rows: list[dict]) -> dict:
    """One dict of arrays stacked along a new first axis (frequency)."""
    return {k: np.stack([r[k] for r in rows]) for k in rows[0]}


def single_box(panel_size: float | None = None, log=print) -> dict:
    """The default box's far field, coefficients and RAOs at :func:`reference_omegas`.

    Args:
        panel_size: m; None: ``boatsim hydro``'s default (0.1 m, the shipped file's mesh).
        log: called with a progress line per frequency.

    Returns:
        dict of arrays (tests/data/wavemaking/README.md, ``box_far_field.npz``).
    """
    _, _, shipped = _default_boat()
    body = _box_body(panel_size)
    omegas, rows, t0 = reference_omegas(), [], time.perf_counter()
    for w in omegas:
        res = _solve(body, float(w), DOF_NAMES, HEADINGS_DEG)
        kochin, eta = _far_field(res, _field_points())
        row = _tables(res, DOF_NAMES, HEADINGS_DEG)
        row.update(kochin_radiation=kochin[:6], kochin_diffraction=kochin[6:],
                   eta_radiation=eta[:6], eta_diffraction=eta[6:],
                   wavenumber=np.array(res[0].wavenumber))
        rows.append(row)
        log(f"box: omega {w:.3f} rad/s done, {time.perf_counter() - t0:.0f} s")
    out = _stack(rows)
    M, C = shipped.inertia_matrix, shipped.hydrostatic_stiffness
    out["rao"] = _rao(omegas, M, out["added_mass"], out["radiation_damping"], C,
                      out["excitation"])
    out.update(_common(omegas), inertia_matrix=M, hydrostatic_stiffness=C,
               headings_deg=np.array(HEADINGS_DEG), dof_names=np.array(DOF_NAMES),
               center_of_mass=np.asarray(body.center_of_mass),
               panels=np.array(body.mesh.nb_faces), lid_panels=np.array(body.lid_mesh.nb_faces),
               solve_seconds=np.array(time.perf_counter() - t0))
    return out


def _common(omegas) -> dict:
    """The arrays every file has: frequencies, angles, field points, environment."""
    return dict(omega=np.asarray(omegas), theta_deg=THETA_DEG, rays_deg=np.array(RAYS_DEG),
                distances=DISTANCES, rho=np.array(_ENV["rho"]), g=np.array(_ENV["g"]),
                water_depth=np.array(_ENV["water_depth"]), capytaine_version=np.array("3.0.0"))


def _cylinder_body(panel_size: float):
    """The floating truncated cylinder of :data:`CYLINDER`, heave only, with a lid."""
    import capytaine as cpt

    a, T = CYLINDER["radius"], CYLINDER["draft"]
    n_theta = 4 * math.ceil(2 * math.pi * a / panel_size / 4)
    full = cpt.mesh_vertical_cylinder(
        length=2 * T, radius=a, center=(0.0, 0.0, 0.0),
        resolution=(math.ceil(a / panel_size), n_theta, math.ceil(2 * T / panel_size)))
    hull = full.immersed_part()
    lid = hull.generate_lid(z=-0.05 * T)
    return cpt.FloatingBody(mesh=hull, lid_mesh=lid, name="cylinder",
                            dofs=cpt.rigid_body_dofs(only=["Heave"]),
                            center_of_mass=(0.0, 0.0, -T / 2), mass=CYLINDER["rho"] * math.pi
                            * a * a * T)


def cylinder(panel_size: float = 0.1, log=print) -> dict:
    """The heaving cylinder's Kochin function, elevations, A33, B33 and heave RAO (beta 0).

    Returns:
        dict of arrays (tests/data/wavemaking/README.md, ``cylinder_heave.npz``).
    """
    body = _cylinder_body(panel_size)
    omegas, rows, t0 = reference_omegas(), [], time.perf_counter()
    for w in omegas:
        res = _solve(body, float(w), ["Heave"], [0.0])
        kochin, eta = _far_field(res[:1], _field_points())
        row = _tables(res, ["Heave"], [0.0])
        rows.append(dict(kochin_heave=kochin[0], eta_heave=eta[0],
                         added_mass=row["added_mass"][0, 0],
                         radiation_damping=row["radiation_damping"][0, 0],
                         excitation=row["excitation"][0, 0],
                         wavenumber=np.array(res[0].wavenumber)))
        log(f"cylinder: omega {w:.3f} rad/s done, {time.perf_counter() - t0:.0f} s")
    out = _stack(rows)
    a, T, rho = CYLINDER["radius"], CYLINDER["draft"], CYLINDER["rho"]
    mass, c33 = rho * math.pi * a * a * T, rho * _ENV["g"] * math.pi * a * a
    out["rao_heave"] = out["excitation"] / (-omegas**2 * (mass + out["added_mass"])
                                            - 1j * omegas * out["radiation_damping"] + c33)
    out.update(_common(omegas), radius=np.array(a), draft=np.array(T), mass=np.array(mass),
               hydrostatic_stiffness=np.array(c33), panels=np.array(body.mesh.nb_faces),
               lid_panels=np.array(body.lid_mesh.nb_faces),
               solve_seconds=np.array(time.perf_counter() - t0))
    return out


def _pair_rao(omegas, k, tables: dict, M, C) -> np.ndarray:
    """(W, D, 2, 6) RAOs of the pair, each body's phase referred to its own centre."""
    M12 = np.kron(np.eye(2), M)
    C12 = np.kron(np.eye(2), C)
    rao = _rao(omegas, M12, tables["added_mass"], tables["radiation_damping"], C12,
               tables["excitation"]).reshape(len(omegas), -1, 2, 6)
    beta = np.radians(PAIR_HEADINGS_DEG)
    y = np.array([-PAIR_Y, PAIR_Y])
    phase = np.exp(1j * k[:, None, None] * np.sin(beta)[None, :, None] * y[None, None, :])
    return rao / phase[..., None]


def box_pair(panel_size: float | None = None, log=print) -> dict:
    """Two default boxes at y = -/+ :data:`PAIR_Y`, both free: 12-dof RAOs, and one box's.

    The single box is solved with the same panels (so the difference is the interaction).

    Returns:
        dict of arrays (tests/data/wavemaking/README.md, ``box_pair.npz``).
    """
    _, _, shipped = _default_boat()
    pair = (_box_body(panel_size, "starboard", -PAIR_Y, symmetry=False)
            + _box_body(panel_size, "port", PAIR_Y, symmetry=False))
    dofs = [f"{b}__{d}" for b in ("starboard", "port") for d in DOF_NAMES]
    alone = _box_body(panel_size)
    omegas, rows, single, t0 = reference_omegas(), [], [], time.perf_counter()
    for w in omegas:
        res = _solve(pair, float(w), dofs, PAIR_HEADINGS_DEG)
        rows.append(dict(_tables(res, dofs, PAIR_HEADINGS_DEG),
                         wavenumber=np.array(res[0].wavenumber)))
        single.append(_tables(_solve(alone, float(w), DOF_NAMES, PAIR_HEADINGS_DEG),
                              DOF_NAMES, PAIR_HEADINGS_DEG))
        log(f"pair: omega {w:.3f} rad/s done, {time.perf_counter() - t0:.0f} s")
    out, one = _stack(rows), _stack(single)
    M, C = shipped.inertia_matrix, shipped.hydrostatic_stiffness
    out["rao_pair"] = _pair_rao(omegas, out["wavenumber"], out, M, C)
    out["rao_single"] = _rao(omegas, M, one["added_mass"], one["radiation_damping"], C,
                             one["excitation"])
    out.update({f"single_{k}": v for k, v in one.items()})
    out.update(_common(omegas), headings_deg=np.array(PAIR_HEADINGS_DEG),
               body_y=np.array([-PAIR_Y, PAIR_Y]), body_names=np.array(["starboard", "port"]),
               dof_names=np.array(DOF_NAMES), inertia_matrix=M, hydrostatic_stiffness=C,
               panels=np.array(pair.mesh.nb_faces), lid_panels=np.array(pair.lid_mesh.nb_faces),
               solve_seconds=np.array(time.perf_counter() - t0))
    return out


def main(argv=None) -> int:
    """Solve and write the files (``--only`` a comma list of box, cylinder, pair)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path(__file__).resolve().parents[3]
                    / "tests" / "data" / "wavemaking")
    ap.add_argument("--only", default="box,cylinder,pair")
    ap.add_argument("--panel-size", type=float, default=None,
                    help="m, the boxes' panels (default: the shipped file's, 0.1 m)")
    args = ap.parse_args(argv)
    jobs = dict(box=("box_far_field", lambda: single_box(args.panel_size)),
                cylinder=("cylinder_heave", cylinder),
                pair=("box_pair", lambda: box_pair(args.panel_size)))
    for name in args.only.split(","):
        stem, job = jobs[name]
        path = write(args.out / f"{stem}.npz", job())
        print(f"wrote {path} ({path.stat().st_size / 1e3:.0f} kB)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
