"""`boatsim hydro SCENARIO`: the potential-flow coefficient files of a scenario's hulls.

Each boat's file is keyed by its hull mesh, mass properties and water
(:func:`boat_dynamics.physics.core.model.coefficients_key`); a hull whose file already exists where
``coefficients: auto`` looks
(:func:`boat_dynamics.physics.potential_flow.hydro.coefficient_directories`) is
not solved again. New files are solved with Capytaine (:mod:`boat_dynamics.tools.bem`, the
``bem`` extra) for the hull floating upright at rest at its own equilibrium. Before a solve
starts, its plan is reported: panels (fitted to the hull and to the shortest wavelength asked
for, :func:`boat_dynamics.tools.bem_mesh.default_panel_size`), frequencies, problems and the
estimated CPU time (:class:`boat_dynamics.tools.bem.SolvePlan`); ``dry_run`` stops there.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from boat_dynamics.physics.body.rigid_body import mass_matrix
from boat_dynamics.physics.core.model import BoatParams, coefficients_key, hull_mesh
from boat_dynamics.physics.core.tuning import equilibrium_height
from boat_dynamics.physics.potential_flow.gap_modes import memory_of
from boat_dynamics.physics.potential_flow.hydro import (
    coefficient_directories,
    find_coefficients,
    load_coefficients,
    narrow_peaks,
)
from boat_dynamics.physics.potential_flow.radiation import POOR_FIT
from boat_dynamics.physics.scenario import BoatSpec, Scenario
from boat_dynamics.tools.bem import MAX_PANELS, SolvePlan, plan_hull

__all__ = ["HullFile", "HydroError", "coefficient_files", "describe", "file_warnings"]


class HydroError(ValueError):
    """A request ``boatsim hydro`` cannot serve: what, which value, what would do."""


@dataclass(frozen=True)
class HullFile:
    """One boat's coefficient file.

    Attributes:
        boat: the boat's name.
        key: the hull's key.
        path: the file.
        seconds: wall time of the solve; None when the file was already there or the run
            was dry.
        plan: the solve's plan; None when the file was already there.
    """

    boat: str
    key: str
    path: Path
    seconds: float | None
    plan: SolvePlan | None = None


def describe(params: BoatParams, z_eq: float) -> str:
    """A file-name stem for the hull: its kind, size and draft, e.g. ``box_4x2x1_d0.500``."""
    mesh = hull_mesh(params)
    draft = -z_eq - float(mesh.vertices[:, 2].min())
    size = "x".join(f"{float(e):g}" for e in np.ptp(mesh.vertices, axis=0))
    boxy = np.all(np.isclose(np.abs(mesh.face_normals).max(axis=1), 1.0))
    return f"{'box' if boxy else 'hull'}_{size}_d{draft:.3f}"


def _selected(scenario: Scenario, names: Sequence[str] | None) -> list[BoatSpec]:
    if not names:  # the boats; not world.buoys (no coefficients: small against the waves)
        return [b for b in scenario.boats if b.kind == "boat"]
    known = {b.name: b for b in scenario.boats}
    for name in names:
        if name not in known:
            raise HydroError(f"--boat: {name!r} is not a boat of the scenario (its boats: "
                             f"{', '.join(repr(n) for n in known)})")
    return [known[n] for n in names]


def _solver():
    """The solving module, or HydroError saying how to install it."""
    try:
        import capytaine  # noqa: F401
    except ImportError as exc:
        raise HydroError("solving needs Capytaine, the optional extra: pip install "
                         "'boatsim[bem]' (or make bem)") from exc
    from boat_dynamics.tools import bem

    return bem


def coefficient_files(scenario: Scenario, scenario_dir: Path,
                      boats: Sequence[str] | None = None, out_dir: Path | None = None,
                      force: bool = False, panel_size: float | None = None,
                      report=lambda line: None, shortest_wavelength: float | None = None,
                      dry_run: bool = False) -> list[HullFile]:
    """Find or make the coefficient file of each boat (or of the boats named).

    Args:
        scenario: as read (boats not initialized).
        scenario_dir: the scenario file's directory (``coefficients: auto`` looks in its
            ``hydro/`` first).
        boats: names of the boats; None or empty = every boat.
        out_dir: where new files go; default ``scenario_dir / "hydro"``.
        force: solve even if a file of the key exists.
        panel_size: m, the largest panel edge (default :func:`bem_mesh.default_panel_size`).
        report: called with a progress line before each solve.
        shortest_wavelength: in boat lengths, the shortest wave the default panels resolve
            (None: only the hull sets them).
        dry_run: plan the solves (HullFile.plan, its path the one it would have) but run
            none: Capytaine is not needed.

    Raises:
        HydroError: an unknown boat, or a solve needed without Capytaine installed.
    """
    out_dir = Path(out_dir) if out_dir is not None else Path(scenario_dir) / "hydro"
    if panel_size is not None and not (math.isfinite(panel_size) and panel_size > 0.0):
        raise HydroError(f"--panel-size: {panel_size!r} is not allowed: metres, > 0")
    if shortest_wavelength is not None and not (math.isfinite(shortest_wavelength)
                                                and 0.01 <= shortest_wavelength <= 100.0):
        raise HydroError(f"--shortest-wavelength: {shortest_wavelength!r} is not allowed: "
                         f"boat lengths, from 0.01 to 100")
    files: list[HullFile] = []
    for spec in _selected(scenario, boats):
        params = spec.params
        key = coefficients_key(params, scenario.sea.depth)
        done = next((f for f in files if f.key == key), None)
        found = None if force else find_coefficients(key, coefficient_directories(scenario_dir))
        if done is not None or found is not None:
            files.append(HullFile(spec.name, key, done.path if done else found, None))
            continue
        shortest = (math.inf if shortest_wavelength is None
                    else shortest_wavelength * spec.params.hull.length)
        files.append(_solve(spec, key, scenario.sea.depth, out_dir,
                            dict(panel_size=panel_size, shortest_wavelength=shortest),
                            report, dry_run))
    return files


def _solve(spec: BoatSpec, key: str, depth: float, out_dir: Path, panels: dict, report,
           dry_run: bool) -> HullFile:
    """Plan, report, and (unless ``dry_run``) solve one boat's hull at its equilibrium.

    ``panels``: :func:`.bem.solve_hull`'s ``panel_size`` and ``shortest_wavelength``.
    """
    params = spec.params
    z_eq = equilibrium_height(params)
    stem = describe(params, z_eq)
    mesh = hull_mesh(params)
    plan = plan_hull(mesh.vertices, mesh.faces, draft_offset=-z_eq, gravity=params.gravity,
                     **panels)[0]
    name, path = spec.name or "(root)", out_dir / f"{stem}_{key}.npz"
    if not dry_run and plan.panels + plan.lid_panels > MAX_PANELS:
        raise HydroError(f"boat {name}: {plan.panels + plan.lid_panels} panels are over the "
                         f"{MAX_PANELS}-panel limit: give --panel-size more than "
                         f"{plan.panel_size:.3g} m, or a hull mesh with fewer triangles "
                         f"({len(mesh.faces)} now; each wetted one is a panel at least)")
    report(f"boat {name}: {'would solve' if dry_run else 'solving'} {stem} (key {key}): "
           f"{plan.describe()}")
    if dry_run:
        return HullFile(spec.name, key, path, None, plan)
    bem = _solver()
    t0 = time.perf_counter()
    arrays = bem.solve_hull(
        mesh.vertices, mesh.faces, draft_offset=-z_eq, mass=params.mass,
        center_of_mass=params.center_of_mass,
        inertia_matrix=mass_matrix(params.mass, params.inertia, params.inertia_products),
        water_density=params.water_density, gravity=params.gravity, depth=depth,
        description=stem, **panels)
    if str(arrays["key"]) != key:
        raise AssertionError(f"the solver keyed the file {arrays['key']}, expected {key}")
    path = bem.write(path, arrays)
    return HullFile(spec.name, key, path, time.perf_counter() - t0, plan)


def file_warnings(path: Path) -> list[str]:
    """What a user should know of a coefficient file before running with it (empty: nothing).

    Its narrow peaks (:func:`boat_dynamics.physics.potential_flow.hydro.narrow_peaks`: resonances
    such as a catamaran's gap sloshing) when it carries no gap modes that explain them, and how well
    the radiation memory fits it (:func:`boat_dynamics.physics.potential_flow.gap_modes.memory_of`;
    over
    :data:`POOR_FIT` the boat's radiation may be wrong).
    """
    try:
        hydro = load_coefficients(path)
    except ValueError as exc:  # HydroFileError: unreadable, an array missing or malformed
        return [f"{path.name}: not checked: {exc}"]
    peaks = () if hydro.gap_modes else narrow_peaks(hydro)
    error = memory_of(hydro).error
    lines = []
    if peaks:
        where = {}
        for p in peaks:
            where.setdefault(round(p.omega, 2), []).append(f"{p.dof} {p.quantity}")
        listed = "; ".join(f"{w:g} rad/s ({', '.join(what)})" for w, what in where.items())
        lines.append(f"{path.name}: narrow peaks narrower than its frequency grid at {listed}: "
                     f"sharp resonances, such as the sloshing between a catamaran's hulls, "
                     f"whose heights on the grid mean nothing")
    if error > POOR_FIT:
        lines.append(f"{path.name}: its radiation memory fits it only within "
                     f"{100 * error:.0f} % (accepted: {100 * POOR_FIT:.0f} %): a boat using it "
                     f"may radiate wrongly; `hydrodynamics: {{radiation: resonance}}` or "
                     f"`coefficients: none` avoid it")
    return lines
