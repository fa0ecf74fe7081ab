"""Where the hulls meet the water: one surface query and one clip per state, as a value.

:func:`contact` is the only place the boats' geometry meets the sea. The pipeline's forces
and /diagnostics both read its result; whoever computes it for a state can hand it to
whatever else needs that state (the dynamics node hands the contact its /diagnostics computed
to the next step), instead of a cache deciding behind the caller's back.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.clip import SubmergedTriangles, clip_hulls
from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.body.wrench import sum_by_owner
from boat_dynamics.physics.core.system import FleetState, Group, System
from boat_dynamics.physics.force_models.slamming import swept_volumes, wetted_added_mass
from ocean_sim.physics.waves import (
    SurfaceSample,
    WaveField,
    orbital_velocity,
    pressure_head,
    sample_surface,
)

__all__ = ["FULL_IMMERSION", "Contact", "GroupContact", "contact", "hull_water_velocity",
           "immersion", "reference_points"]


@dataclass(frozen=True)
class GroupContact:
    """Where one group's hulls meet the water.

    Attributes:
        group: the group.
        rotation: (G, 3, 3) the group's body-to-world rotations.
        world: (E, 3) m, its hull vertices or sample points, world frame.
        depths: (E,) m, their depths below the surface (> 0 = submerged).
        surface: the surface at those points.
        at_reference: the surface at the boats' hull reference points.
        wet: the clipped hull triangles (mesh group; None for sample points).
        wet_owner: (T,) int, the boat (0..G-1) of each wet triangle (mesh group).
        water_velocity: (G, 3) m/s, world frame, the mean water velocity over each boat's
            wetted hull (:func:`hull_water_velocity`), or None for a group whose damping
            takes it at the reference point.
        waterline: (G,) kg wetted added mass of strip theory and (G, 3) m world centroid of
            the waterline (:func:`boat_dynamics.physics.force_models.slamming.wetted_added_mass`),
            for a mesh group with momentum slamming; else None.
        swept: Kerner's swept volumes of the group's triangles at the state
            (:func:`boat_dynamics.physics.force_models.slamming.swept_volumes`), for a mesh group
            with ``kerner`` slamming; else None.
    """

    group: Group
    rotation: np.ndarray
    world: np.ndarray
    depths: np.ndarray
    surface: SurfaceSample
    at_reference: SurfaceSample
    wet: SubmergedTriangles | None
    wet_owner: np.ndarray | None
    water_velocity: np.ndarray | None = None
    waterline: tuple[np.ndarray, np.ndarray] | None = None
    swept: tuple[np.ndarray, ...] | None = None


@dataclass(frozen=True)
class Contact:
    """Where every boat meets the water at one state (see :func:`contact`).

    Attributes:
        position: (B, 3) m, the state's centres of mass (the very array: a contact belongs to
            one state).
        orientation: (B, 4), the state's orientations (likewise).
        t: s, the state's time.
        sea: the sea it was sampled from.
        rotation: (B, 3, 3) body-to-world rotations.
        groups: one :class:`GroupContact` per group of the system.
        immersion: (B,) in [0, 1], how much of each hull's fluid it carries
            (:func:`immersion`): 1 afloat, 0 out of the water.
    """

    position: np.ndarray
    orientation: np.ndarray
    t: float
    sea: WaveField
    rotation: np.ndarray
    groups: tuple[GroupContact, ...]
    immersion: np.ndarray | None = None

    def belongs_to(self, system: System, state: FleetState, sea: WaveField) -> bool:
        """True if this contact was computed for ``system``, ``state`` and ``sea``.

        The state's very position and orientation arrays: states are never changed in place.
        """
        return (self.position is state.position and self.orientation is state.orientation
                and self.t == state.t and self.sea is sea
                and len(self.groups) == len(system.groups)
                and all(c.group is g for c, g in zip(self.groups, system.groups, strict=True)))


def reference_points(system: System, state: FleetState) -> tuple[np.ndarray, np.ndarray]:
    """(B, 3, 3) body-to-world rotations and (B, 3) m world hull reference points."""
    rot = rotation_matrix(state.orientation)
    return rot, state.position - np.einsum("bij,bj->bi", rot, system.center_of_mass)


def contact(system: System, state: FleetState, sea: WaveField) -> Contact:
    """Every group's surface contact at ``state``: one surface query per wave filter.

    Args:
        system: the boats.
        state: their state (positions, orientations, time).
        sea: the wave field.

    Returns:
        The contact, for the forces and /diagnostics of this state.
    """
    rot, ref = reference_points(system, state)
    queries = _world_points(system, rot, ref)
    out = []
    for (g, world), (surface, at_ref) in zip(queries, _sample(sea, state.t, queries, ref),
                                             strict=True):
        if surface is None:  # linear pressure: the hull against the calm-water plane
            surface, at_ref = _calm(world), _calm(ref[g.index])
        depths = surface.heights - world[:, 2]
        wet = wet_owner = None
        if g.mesh is not None:
            heads = None  # hydrostatic: the depths
            if g.mesh.pressure == "froude_krylov":
                heads = pressure_head(sea.filtered(g.min_wavelength), surface.rest_xy,
                                      surface.heights, world[:, 2], state.t)
            wet = clip_hulls(g.faces, world, depths, heads)
            wet_owner = g.face_owner.take(wet.faces)
        water = None
        if g.water_velocity == "hull":
            water = hull_water_velocity(sea.filtered(g.min_wavelength), state.t, g, world,
                                        surface, at_ref, wet, wet_owner)
        waterline = None
        if g.mesh is not None and g.mesh.slamming.model in ("geometric", "wagner"):
            waterline = wetted_added_mass(g.mesh.slamming, g.faces, world, depths, g.face_owner,
                                          rot[g.index], ref[g.index], g.length,
                                          system.water_density[g.index])
        swept = None
        if g.mesh is not None and g.mesh.slamming.model == "kerner":
            r = rot[g.index]
            swept = swept_volumes(g.faces, world, g.face_owner, wet.faces, wet.areas,
                                  np.einsum("gij,gj->gi", r, state.velocity[g.index]),
                                  np.einsum("gij,gj->gi", r, state.angular_velocity[g.index]),
                                  state.position[g.index])
        out.append(GroupContact(g, rot[g.index], world, depths, surface, at_ref, wet,
                                wet_owner, water, waterline, swept))
    return Contact(state.position, state.orientation, state.t, sea, rot, tuple(out),
                   immersion(system, out))


#: The submerged volume, as a share of the displacement at rest, below which a hull's added
#: mass and radiation fade (:func:`immersion`).
FULL_IMMERSION = 0.5


def immersion(system: System, groups: Sequence[GroupContact]) -> np.ndarray:
    """(B,) in [0, 1]: the share of its potential-flow fluid (added mass, radiation) a hull carries.

    min(1, V / (:data:`FULL_IMMERSION` V_0)), V the submerged volume (the divergence theorem
    over the wetted triangles: V = -integral(d n_z dA)), V_0 = m / rho the displacement at
    rest: 1 while at least half the displacement is under water, so floating and seakeeping
    are those of linear potential flow, falling to 0 as the hull leaves the water, which keeps
    its fluid (a constant A_inf in the mass matrix instead carried it along: the default box
    released 5 m deep flew 0.9 m clear of the surface, the seed notes' shooting out). 1 for
    sample points (no coefficients).
    """
    out = np.ones(system.count)
    for c in groups:
        if c.wet is None:
            continue
        g = c.group
        depth_sum = c.wet.depths[0] + c.wet.depths[1] + c.wet.depths[2]
        volume = sum_by_owner((-depth_sum / 3.0 * c.wet.vector_areas[2])[:, None],
                              c.wet_owner, g.index.shape[0])[:, 0]
        rest = system.mass[g.index] / system.water_density[g.index]
        out[g.index] = np.clip(volume / (FULL_IMMERSION * rest), 0.0, 1.0)
    return out


def hull_water_velocity(sea: WaveField, t: float, group: Group, world: np.ndarray,
                        surface: SurfaceSample, at_reference: SurfaceSample,
                        wet: SubmergedTriangles | None, wet_owner: np.ndarray | None
                        ) -> np.ndarray:
    """(G, 3) m/s, world frame: the water velocity over each boat's wetted hull.

    Linear theory's orbital velocity (:func:`ocean_sim.physics.waves.orbital_velocity`) at
    each wetted triangle's centroid, weighted by its area (mesh), or at each submerged sample
    point, equally (sample points): in waves shorter than the hull the parts move against each
    other and the mean is small, as the force they exert is (the damping of one point's
    velocity instead drove the hull at 0.5 L with 20 times the waves' true excitation). A boat
    with nothing under water takes the surface particle's velocity above its reference point.

    Args:
        sea: the waves acting on the group (filtered).
        t: s.
        group: the group.
        world: (E, 3) m, its vertices or sample points, world frame.
        surface: the surface above them.
        at_reference: the surface above the reference points.
        wet: the clipped triangles (mesh group).
        wet_owner: (T,) int, their boats (mesh group).
    """
    from boat_dynamics.physics.body.clip_kernel import wet_centroids_f64  # numba: when used
    from boat_dynamics.physics.body.owner_kernel import weighted_mean_by_owner_f64

    if wet is not None:
        where, eta, weights = wet_centroids_f64(wet.xyz, wet.depths, wet.vector_areas)
        owner = wet_owner
    else:
        under = surface.heights > world[:, 2]
        where, owner = world[under], group.owner[under]
        weights, eta = np.ones(where.shape[0]), surface.heights[under]
    u = orbital_velocity(sea, where[:, :2], eta, where[:, 2], t)
    return weighted_mean_by_owner_f64(u, weights, owner,
                                      np.ascontiguousarray(at_reference.velocities))


def _world_points(system: System, rot: np.ndarray, ref: np.ndarray) -> list:
    """(group, (E, 3) m world positions of its vertices / points) for every group."""
    from boat_dynamics.physics.body.owner_kernel import to_world_f64  # numba: when used

    return [(g, to_world_f64(rot[g.index], ref[g.index], g.owner, g.body))
            for g in system.groups]


def _sample(sea: WaveField, t: float, queries: list, ref: np.ndarray) -> list:
    """The surface at every query's points and at its boats' reference points.

    Groups sharing a wave filter and precision share one sample_surface call (its fixed cost
    is paid once). A ``linear`` group is not queried ((None, None)): its hulls meet the
    calm-water plane, and the waves act on them through their coefficients.
    """
    by_filter: dict[tuple, list[int]] = {}
    for k, (g, _) in enumerate(queries):
        by_filter.setdefault((g.min_wavelength, g.wave_precision), []).append(k)
    out: list = [(None, None)] * len(queries)
    for (min_wavelength, precision), members in by_filter.items():
        members = [k for k in members if not _linear(queries[k][0])]
        if not members:
            continue
        xy = np.concatenate([a for k in members
                             for a in (queries[k][1][:, :2], ref[queries[k][0].index, :2])])
        surface = sample_surface(sea, xy, t, min_wavelength=min_wavelength,
                                 precision=precision)
        start = 0
        for k in members:
            n, m = queries[k][1].shape[0], queries[k][0].index.shape[0]
            out[k] = (surface.rows(start, start + n), surface.rows(start + n, start + n + m))
            start += n + m
    return out


def _linear(group: Group) -> bool:
    """Whether the group's hulls meet the calm-water plane (``linear`` pressure)."""
    return group.mesh is not None and group.mesh.pressure == "linear"


def _calm(world: np.ndarray) -> SurfaceSample:
    """The calm-water plane z = 0 above ``world`` (E, 3) points: at rest, level."""
    n = world.shape[0]
    normals = np.zeros((n, 3))
    normals[:, 2] = 1.0
    return SurfaceSample(np.zeros(n), normals, np.zeros((n, 3)), np.zeros((n, 3)),
                         world[:, :2].copy())
