"""Hydrostatic equilibrium, stiffness and the critical-damping helper.

Stiffnesses are measured from the boat's own buoyancy model in flat water (central differences
about the equilibrium), so they hold for any hull and either buoyancy model: for a box they
are rho g A_wp in heave and m g GM in roll and pitch. The critical damping of a DOF is
b_c = 2 sqrt(k m) (Source: the seed notes, "Damping"; Fossen (2011), sec. 4.3), with the mass
or moment of inertia of that DOF (rigid body plus added mass).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from boat_dynamics.physics.body.hull import HullMesh, box_mesh
from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.core.contact import contact
from boat_dynamics.physics.core.forces import forces
from boat_dynamics.physics.core.model import BoatInputs, BoatParams, initial_state
from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy
from boat_dynamics.physics.force_models.mooring import soft_mooring
from boat_dynamics.physics.force_models.wind import Windage, windage_of_hull
from boat_dynamics.physics.potential_flow.gap_modes import memory_of
from boat_dynamics.physics.potential_flow.hull_lift import trailing_sections
from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients, estimate
from boat_dynamics.physics.wave_making.kelvin_wake import thin_ship
from ocean_sim.physics.waves import WaveField

__all__ = [
    "DEFAULT_DRAG_COEFFICIENTS",
    "critical_damping",
    "default_drag",
    "derive",
    "equilibrium_height",
    "horizontal_mass",
    "hydrostatic_stiffness",
    "potential_flow_at_resonance",
]

#: Drag coefficients [surge, sway, heave] of the default quadratic damping 1/2 rho C_d A.
DEFAULT_DRAG_COEFFICIENTS = (0.5, 1.0, 1.0)

_FLAT = WaveField()


_AT_REST = FleetInputs.stack([BoatInputs()])


def _vertical_buoyancy(system: System, z: float, roll: float = 0.0,
                       pitch: float = 0.0) -> tuple[float, np.ndarray]:
    """World-vertical buoyancy force (N) and body torque (N m) in flat water.

    Of the one boat of ``system``, its hull reference point at height z (m).
    """
    state = FleetState.stack([initial_state(system.params[0], [0.0, 0.0, z], roll=roll,
                                            pitch=pitch)])
    acting, _ = forces(system, state, _AT_REST, contact(system, state, _FLAT))
    f = acting.boat(0).buoyancy
    return float((rotation_matrix(state.orientation[0]) @ f.force)[2]), f.torque


def equilibrium_height(params: BoatParams) -> float:
    """Height z (m) of the hull reference point where buoyancy carries the weight, upright.

    Regula falsi (Illinois variant) over the hull's height in flat water, to 1e-10 of the
    weight: buoyancy is piecewise linear in z for wall-sided hulls, so a few evaluations
    suffice. Raises ValueError for a hull that sinks.
    """
    weight = params.mass * params.gravity
    half = params.hull.height / 2
    system = System.build([params])

    def excess(z: float) -> float:
        return _vertical_buoyancy(system, z)[0] - weight

    low, high = -half, half  # fully submerged (excess > 0) .. just touching (excess < 0)
    f_low, f_high = excess(low), excess(high)
    if f_low < 0.0:
        raise ValueError(f"the hull sinks: fully submerged buoyancy is less than its weight "
                         f"{weight:.4g} N (density above the water's?)")
    side = 0
    z = 0.5 * (low + high)
    for _ in range(100):
        if f_high == f_low:  # no slope to follow (a centre of mass lost in rounding)
            raise ValueError("no equilibrium draft: the buoyancy does not change with the "
                             "draft in double precision (a centre of mass far from the hull?)")
        z = (low * f_high - high * f_low) / (f_high - f_low)
        f = excess(z)
        if abs(f) <= 1e-10 * weight or high - low <= 1e-12 * params.hull.height:
            break
        if f > 0.0:
            low, f_low = z, f
            if side == 1:
                f_high *= 0.5
            side = 1
        else:
            high, f_high = z, f
            if side == -1:
                f_low *= 0.5
            side = -1
    return z


def hydrostatic_stiffness(params: BoatParams, z0: float | None = None) -> np.ndarray:
    """(3,) heave N/m, roll and pitch N m/rad restoring stiffness at the upright equilibrium.

    ``z0``: the equilibrium height if already known (:func:`equilibrium_height`).
    """
    z0 = equilibrium_height(params) if z0 is None else z0
    dz = 1e-3 * params.hull.height
    da = 1e-3
    system = System.build([params])
    k_heave = -(_vertical_buoyancy(system, z0 + dz)[0]
                - _vertical_buoyancy(system, z0 - dz)[0]) / (2 * dz)
    k_roll = -(_vertical_buoyancy(system, z0, roll=da)[1][0]
               - _vertical_buoyancy(system, z0, roll=-da)[1][0]) / (2 * da)
    k_pitch = -(_vertical_buoyancy(system, z0, pitch=da)[1][1]
                - _vertical_buoyancy(system, z0, pitch=-da)[1][1]) / (2 * da)
    return np.array([k_heave, k_roll, k_pitch])


def critical_damping(params: BoatParams, ratios: np.ndarray, z0: float | None = None
                     ) -> np.ndarray:
    """Linear damping (6,) giving damping ratios zeta = [heave, roll, pitch] (surge/sway/yaw 0).

    b = zeta * 2 sqrt(k m) per DOF, k from :func:`hydrostatic_stiffness`, m the rigid-body
    mass or inertia plus added mass (the diagonal ``added_mass``, or of the 6 x 6
    ``added_mass_matrix`` when there is one: potential flow's A_inf). A DOF with no restoring
    stiffness (k <= 0: unstable in roll, say) gets no damping from here. ``z0``: the
    equilibrium height, if known.
    """
    k = hydrostatic_stiffness(replace(params, damping_linear=np.zeros(6)), z0)
    added = (params.added_mass if params.added_mass_matrix is None
             else np.diag(params.added_mass_matrix))
    m = np.array([params.mass + added[2], params.inertia[0] + added[3],
                  params.inertia[1] + added[4]])
    b = np.asarray(ratios, dtype=float) * 2.0 * np.sqrt(np.maximum(k, 0.0) * m)
    out = np.zeros(6)
    out[[2, 3, 4]] = b
    return out


def default_drag(params: BoatParams, z_eq: float) -> np.ndarray:
    """(6,) the default quadratic damping of a hull floating upright at height ``z_eq`` (m).

    1/2 rho C_d A on the projected areas at the equilibrium draft d (surge B d, sway L d,
    heave L B) and, by strip theory of the sway drag along the hull, yaw rho C_d,y d L^4 / 64;
    roll and pitch none. C_d: :data:`DEFAULT_DRAG_COEFFICIENTS`. Units N/(m/s)^2 and
    N m/(rad/s)^2.
    """
    hull = params.hull
    bottom = float(np.min(params.buoyancy.mesh.vertices[:, 2])
                   if isinstance(params.buoyancy, MeshBuoyancy) else -hull.height / 2)
    draft = min(max(-(z_eq + bottom), 0.0), hull.height)
    cx, cy, cz = DEFAULT_DRAG_COEFFICIENTS
    half_rho = 0.5 * params.water_density
    return np.array([half_rho * cx * hull.beam * draft,
                     half_rho * cy * hull.length * draft,
                     half_rho * cz * hull.length * hull.beam,
                     0.0, 0.0,
                     params.water_density * cy * draft * hull.length**4 / 64.0])


def derive(params: BoatParams) -> BoatParams:
    """``params`` with what its :class:`~.model.Derivation` asks for, computed once.

    The equilibrium height (flat water, upright) becomes ``control.height_offset``; with
    potential-flow coefficients, the 6 x 6 infinite-frequency added mass and the fitted
    radiation memory of the Cummins equation (:func:`.gap_modes.memory_of`) and the hull's
    trailing sections (:func:`.hull_lift.trailing_sections`), or the added
    mass and radiation damping of :func:`potential_flow_at_resonance`; then
    ``damping_linear`` += :func:`critical_damping` of ``critical_ratio``, with
    ``quadratic``, ``damping_quadratic`` = :func:`default_drag`, and the windage the wind
    acts on (:func:`.wind.windage_of_hull` where the scenario gave none). Parameters with nothing to
    derive (``derive`` None) are returned as they are.

    Raises:
        ValueError: the hull sinks (its fully submerged buoyancy is less than its weight).
    """
    wanted = params.derive
    if wanted is None:
        return params
    z_eq = equilibrium_height(params)
    if wanted.estimate is not None:
        params = replace(params, hydro=estimate(params.mass, params.center_of_mass,
                                                params.water_density, z_eq, wanted.estimate))
    linear, quadratic = params.damping_linear, params.damping_quadratic
    if params.hydro is not None and wanted.memory:
        params = replace(params, added_mass_matrix=params.hydro.added_mass_inf.copy(),
                         radiation_memory=memory_of(params.hydro))
        if wanted.hull_lift:
            params = replace(params, hull_lift=trailing_sections(
                _mesh(params), z_eq, float(params.hydro.added_mass_inf[1, 1])))
    if params.hydro is not None and (wanted.added_mass or wanted.radiation_damping):
        added, radiation = potential_flow_at_resonance(params, params.hydro, z_eq)
        if wanted.added_mass:
            params = replace(params, added_mass=added)
        if wanted.radiation_damping:
            params = replace(params, radiation_damping=radiation)
    if wanted.critical_ratio is not None:
        linear = linear + critical_damping(params, wanted.critical_ratio, z_eq)
    if wanted.quadratic:
        quadratic = default_drag(params, z_eq)
    if wanted.windage is not None:
        params = replace(params, windage=_windage(params, wanted.windage, z_eq))
    if wanted.thin_ship:
        params = replace(params, thin_ship=thin_ship(_mesh(params), z_eq))
    if wanted.mooring_period is not None:  # anchored where it starts: pipeline.init
        params = replace(params, mooring=soft_mooring(np.full(3, np.nan), horizontal_mass(params),
                                                      wanted.mooring_period))
    return replace(params, damping_linear=linear, damping_quadratic=quadratic,
                   control=replace(params.control, height_offset=z_eq), derive=None)


def horizontal_mass(params: BoatParams) -> np.ndarray:
    """(3,) kg, kg, kg m^2: surge, sway mass and yaw inertia with their added mass.

    The infinite-frequency added mass of the coefficients where the boat has them, else its
    ``added_mass``: what a soft mooring's period is set with (:func:`.mooring.soft_mooring`).
    """
    rigid = np.array([params.mass, params.mass, params.inertia[2]], dtype=float)
    if params.hydro is not None:
        return rigid + np.diag(params.hydro.added_mass_inf)[[0, 1, 5]]
    return rigid + np.asarray(params.added_mass, dtype=float)[[0, 1, 5]]


def _windage(params: BoatParams, given: Windage, z_eq: float) -> Windage:
    """``given`` with its NaN fields from the hull above its equilibrium waterline."""
    hull = windage_of_hull(_mesh(params), z_eq, params.hull.length)
    return Windage(
        frontal_area=hull.frontal_area if np.isnan(given.frontal_area) else given.frontal_area,
        lateral_area=hull.lateral_area if np.isnan(given.lateral_area) else given.lateral_area,
        length=params.hull.length,
        centre=np.where(np.isnan(given.centre), hull.centre, given.centre),
        coefficients=np.asarray(given.coefficients, dtype=float))


def potential_flow_at_resonance(params: BoatParams, coefficients: HydroCoefficients,
                                z_eq: float) -> tuple[np.ndarray, np.ndarray]:
    """(6,) added mass and (6,) linear radiation damping, constant, from a BEM solution.

    Heave, roll and pitch take A_ii and B_ii at their own natural frequency, where
    omega^2 (M_ii + A_ii(omega)) = C_ii with the boat's own stiffness
    (:func:`hydrostatic_stiffness`) and rigid-body mass or moment: the frequency-domain
    constant-coefficient model, exact at resonance (periods and decay rates of free
    oscillations; Newman 1977, sec. 6.19). Surge, sway and yaw take the infinite-frequency
    added mass and no radiation damping (no restoring force, no natural frequency). A dof
    without positive stiffness is treated like those.
    """
    k = hydrostatic_stiffness(replace(params, damping_linear=np.zeros(6)), z_eq)
    rigid = np.array([params.mass, params.inertia[0], params.inertia[1]])
    added = np.diag(coefficients.added_mass_inf).astype(float).copy()
    damping = np.zeros(6)
    for dof, stiffness, inertia in zip((2, 3, 4), k, rigid, strict=True):
        if stiffness <= 0.0:
            continue
        omega, a, _ = coefficients.natural(dof, float(stiffness), float(inertia))
        added[dof] = a
        damping[dof] = coefficients.damping_at(omega)[dof, dof]
    return added, damping


def _mesh(params: BoatParams) -> HullMesh:
    """The hull's mesh: the mesh model's own, or the box's."""
    if isinstance(params.buoyancy, MeshBuoyancy):
        return params.buoyancy.mesh
    return box_mesh(params.hull)
