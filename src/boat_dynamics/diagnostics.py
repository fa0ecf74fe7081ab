"""What /diagnostics reports about a boat: hydrostatics, mode, the remedies in force.

Pure core: returns plain values; the node turns them into diagnostic_msgs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from boat_dynamics.boat import BoatParams, BoatState, reference_pose
from boat_dynamics.mesh_buoyancy import MeshBuoyancy, hydrostatics
from boat_dynamics.rigid_body import rotation_matrix
from ocean_sim.waves import WaveField, sample_surface

__all__ = ["BoatReport", "active_remedies", "boat_report"]


@dataclass(frozen=True)
class BoatReport:
    """One boat's diagnostic summary.

    Attributes:
        level: 0 OK, 1 WARN (fully submerged or out of the water).
        message: one line for humans.
        values: (key, value) pairs, units in the keys.
    """

    level: int
    message: str
    values: tuple[tuple[str, str], ...]


def active_remedies(params: BoatParams, substeps: int) -> list[str]:
    """The shooting-out remedies (seed notes, section 4) this boat runs with."""
    out = []
    if isinstance(params.buoyancy, MeshBuoyancy):
        out.append("exact hydrostatics (mesh: force bounded by rho g V)")
    else:
        out.append(f"depth clamp at {params.buoyancy.max_depth:g} m")
    if params.damping_linear[2] > 0:
        out.append("linear heave damping")
    if params.damping_quadratic[2] > 0:
        out.append("quadratic heave drag")
    if np.any(params.added_mass > 0):
        out.append("added mass")
    if substeps > 1:
        out.append(f"{substeps} substeps")
    if params.control.mode == "constrained":
        out.append("safety net (depth band, angular clamp, rescue)")
    return out


def boat_report(params: BoatParams, state: BoatState, sea: WaveField,
                substeps: int = 1) -> BoatReport:
    """Draft, submerged volume, waterplane area, GM, mode and remedies of a boat now."""
    rot = rotation_matrix(state.orientation)
    ref, _ = reference_pose(params, state)
    model = params.buoyancy
    body_points = model.mesh.vertices if isinstance(model, MeshBuoyancy) else model.points
    pts = ref + body_points @ rot.T
    depths = sample_surface(sea, pts[:, :2], state.t,
                            min_wavelength=params.min_wavelength).heights - pts[:, 2]
    values = [("buoyancy_model", "mesh" if isinstance(model, MeshBuoyancy) else "sample_points"),
              ("control_mode", params.control.mode)]
    hull_volume = model.mesh.volume if isinstance(model, MeshBuoyancy) else model.volume
    if isinstance(model, MeshBuoyancy):
        hs = hydrostatics(model, pts, depths, rot, state.position)
        volume = hs.submerged_volume
        values += [("draft_m", f"{hs.draft:.4f}"), ("submerged_volume_m3", f"{volume:.4f}"),
                   ("waterplane_area_m2", f"{hs.waterplane_area:.4f}"),
                   ("metacentric_height_m", f"{hs.metacentric_height:.4f}")]
    else:
        fraction = np.clip(depths, 0.0, model.max_depth) / model.max_depth
        volume = float(fraction.mean() * model.volume)
        values += [("draft_m", f"{max(float(depths.max()), 0.0):.4f}"),
                   ("submerged_volume_m3", f"{volume:.4f}")]
    values.append(("remedies", "; ".join(active_remedies(params, substeps))))
    ratio = volume / hull_volume
    if ratio >= 0.999:
        return BoatReport(1, "fully submerged", tuple(values))
    if ratio <= 0.0:
        return BoatReport(1, "out of the water", tuple(values))
    return BoatReport(0, f"floating, {100 * ratio:.0f} % submerged", tuple(values))
