"""What /diagnostics reports about a boat: hydrostatics, mode, the remedies in force.

Pure core: returns plain values; the node turns them into diagnostic_msgs.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from boat_dynamics.physics.body.clip import clip_hulls
from boat_dynamics.physics.core.contact import Contact, GroupContact, contact
from boat_dynamics.physics.core.model import BoatParams, BoatState
from boat_dynamics.physics.core.system import FleetState, System
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy, hydrostatics_of
from ocean_sim.physics.waves import WaveField, sample_surface

__all__ = ["BoatReport", "active_remedies", "boat_report", "fleet_reports"]


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
    if np.any(params.damping_decay > 0):
        out.append("velocity decay (seed notes)")
    if np.any(params.added_mass > 0):
        out.append("added mass")
    if np.any(params.radiation_damping > 0):
        out.append("radiation damping (potential flow)")
    if substeps > 1:
        out.append(f"{substeps} substeps")
    if params.control.mode == "constrained":
        out.append("safety net (depth band, angular clamp, rescue)")
    return out


def boat_report(params: BoatParams, state: BoatState, sea: WaveField,
                substeps: int = 1) -> BoatReport:
    """Draft, submerged volume, waterplane area, GM, mode and remedies of a boat now."""
    system, fleet_state = System.build([params]), FleetState.stack([state])
    return fleet_reports(system, fleet_state, contact(system, fleet_state, sea), substeps)[0]


def fleet_reports(system: System, state: FleetState, touching: Contact, substeps: int = 1,
                  remedies: list[str] | None = None) -> list[BoatReport]:
    """:func:`boat_report` of every boat of a system, from its surface contact at ``state``.

    Args:
        system: the boats.
        state: their state.
        touching: the surface contact at ``state`` (:func:`.contact.contact`), which the next
            pipeline step from ``state`` can reuse.
        substeps: physics substeps per step (a remedy).
        remedies: each boat's remedies line ("; "-joined :func:`active_remedies`), if known
            (they depend on the parameters only).

    Raises:
        ValueError: ``touching`` belongs to another state.
    """
    if not touching.belongs_to(system, state, touching.sea):
        raise ValueError("touching: the contact of another system or state than the one "
                         "reported")
    volumes = np.zeros(system.count)
    values: list[list] = [[] for _ in range(system.count)]
    for c in touching.groups:
        _group_values(_against_the_waves(c, touching.sea, state.t), state, volumes, values)
    out = []
    for k, params in enumerate(system.params):
        line = (remedies[k] if remedies is not None
                else "; ".join(active_remedies(params, substeps)))
        entries = (values[k][0], ("control_mode", params.control.mode), *values[k][1:],
                   ("remedies", line))
        out.append(_verdict(volumes[k] / _hull_volume(params), entries))
    return out


def _hull_volume(params: BoatParams) -> float:
    """m^3, the volume the boat's buoyancy model displaces fully submerged."""
    model = params.buoyancy
    return model.mesh.volume if isinstance(model, MeshBuoyancy) else model.volume


def _verdict(ratio: float, entries: tuple) -> BoatReport:
    """The report of a boat ``ratio`` (submerged / hull volume) under water."""
    if ratio >= 0.999:
        return BoatReport(1, "fully submerged", entries)
    if ratio <= 0.0:
        return BoatReport(1, "out of the water", entries)
    return BoatReport(0, f"floating, {100 * ratio:.0f} % submerged", entries)


def _against_the_waves(c: GroupContact, sea: WaveField, t: float) -> GroupContact:
    """``c``, or a ``linear`` group's contact with its hulls clipped at the wave surface.

    A ``linear`` group meets the calm-water plane; what is under water is reported against
    the water that is there. One surface query at the hull's vertices, at the diagnostics
    rate only.
    """
    g = c.group
    if g.mesh is None or g.mesh.pressure != "linear":
        return c
    surface = sample_surface(sea, c.world[:, :2], t, min_wavelength=g.min_wavelength,
                             precision=g.wave_precision)
    depths = surface.heights - c.world[:, 2]
    wet = clip_hulls(g.faces, c.world, depths)
    return replace(c, depths=depths, surface=surface, wet=wet,
                   wet_owner=g.face_owner.take(wet.faces))


def _group_values(c: GroupContact, state: FleetState, volumes: np.ndarray,
                  values: list[list]) -> None:
    """Fill the submerged volumes (m^3) and report values of one group's boats."""
    g, depths = c.group, c.depths
    i = g.index
    count = i.shape[0]
    draft = np.full(count, -np.inf)
    np.maximum.at(draft, g.owner, depths)
    if g.mesh is not None:
        reports = hydrostatics_of(c.wet, c.wet_owner, count, c.rotation, state.position[i],
                                  draft)
        for k, hs in zip(i, reports, strict=True):
            volumes[k] = hs.submerged_volume
            values[k] = [("buoyancy_model", "mesh"),
                         ("draft_m", f"{hs.draft:.4f}"),
                         ("submerged_volume_m3", f"{hs.submerged_volume:.4f}"),
                         ("waterplane_area_m2", f"{hs.waterplane_area:.4f}"),
                         ("metacentric_height_m", f"{hs.metacentric_height:.4f}")]
        return
    model = g.points  # numeric fields stacked: (G,) per boat of the group
    max_depth = model.max_depth[g.owner]
    fraction = np.clip(depths, 0.0, max_depth) / max_depth
    mean = (np.bincount(g.owner, weights=fraction, minlength=count)
            / np.bincount(g.owner, minlength=count))
    for j, k in enumerate(i):
        volumes[k] = float(mean[j] * model.volume[j])
        values[k] = [("buoyancy_model", "sample_points"),
                     ("draft_m", f"{max(float(draft[j]), 0.0):.4f}"),
                     ("submerged_volume_m3", f"{volumes[k]:.4f}")]
