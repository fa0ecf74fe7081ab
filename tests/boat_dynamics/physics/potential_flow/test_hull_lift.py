"""The hull's lift at speed: the trailing section's shed momentum (slender-body theory)."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.hull import BoxHull, box_mesh, load_mesh
from boat_dynamics.physics.core.pipeline import init_scenario
from boat_dynamics.physics.experiments.trials import Order, sea_trials
from boat_dynamics.physics.potential_flow.added_mass import added_mass_coriolis
from boat_dynamics.physics.potential_flow.hull_lift import (
    draft_profile,
    hull_lift,
    trailing_sections,
)
from boat_dynamics.physics.scenario import ScenarioError, load_scenario, parse_scenario
from ocean_sim.physics.waves import WaveField

SCENARIOS = Path(__file__).resolve().parents[4] / "scenarios"
DATA = Path(__file__).resolve().parents[3] / "data" / "hydro"
RHO = 1025.0


def _derivatives(added: np.ndarray, lift, speed: float) -> dict[str, float]:
    """Y_v, N_v, Y_r, N_r of the added mass at speed plus the hull lift, by central differences.

    The hull reference point is the centre of mass (a box with its centroid there).
    """
    def wrench(v: float, r: float) -> np.ndarray:
        velocity, rate = np.array([[speed, v, 0.0]]), np.array([[0.0, 0.0, r]])
        munk = added_mass_coriolis(added[None], velocity, rate)
        shed = hull_lift(lift.added_mass[None], lift.position[None], velocity, rate,
                         np.zeros((1, 3)))
        return np.array([munk.force[0, 1] + shed.force[0, 1],
                         munk.torque[0, 2] + shed.torque[0, 2]])
    h = 1e-4
    dv = (wrench(h, 0.0) - wrench(-h, 0.0)) / (2 * h)
    dr = (wrench(0.0, h) - wrench(0.0, -h)) / (2 * h)
    return {"Y_v": dv[0], "N_v": dv[1], "Y_r": dr[0], "N_r": dr[1]}


def test_a_prismatic_hulls_derivatives_are_clarkes_leading_terms():
    """Clarke, Gedling & Hine (1983): Y'_v = -pi (T/L)^2, N'_v = -pi (T/L)^2 / 2,
    Y'_r = pi (T/L)^2 / 2, N'_r = -pi (T/L)^2 / 4 (their regression's terms free of B), which
    are slender-body theory's for a flat plate of draft T: a22 = rho pi T^2 / 2, A11 = 0;
    non-dimensional with 1/2 rho U L^2 (v) and 1/2 rho U L^3 (r, and N_v)."""
    length, draft, speed = 12.0, 0.8, 3.0
    hull = BoxHull(length=length, beam=0.01, height=2 * draft)  # a flat plate, half immersed
    a22 = RHO * math.pi * draft**2 / 2
    lift = trailing_sections(box_mesh(hull), 0.0, a22 * length)
    assert lift.added_mass == pytest.approx([a22, a22], rel=1e-12)
    assert lift.position == pytest.approx(np.array([[-6.0, 0.0, -0.4], [6.0, 0.0, -0.4]]))
    added = np.zeros((6, 6))
    added[1, 1] = a22 * length
    d = _derivatives(added, lift, speed)
    q, k = 0.5 * RHO * speed, math.pi * (draft / length) ** 2
    assert d["Y_v"] / (q * length**2) == pytest.approx(-k, rel=1e-6)
    assert d["N_v"] / (q * length**3) == pytest.approx(-k / 2, rel=1e-6)  # half the Munk moment
    assert d["Y_r"] / (q * length**3) == pytest.approx(k / 2, rel=1e-6)
    assert d["N_r"] / (q * length**4) == pytest.approx(-k / 4, rel=1e-6)
    # without the lift, the Munk moment alone: N_v twice as large, no sway force, no N_r
    none = replace(lift, added_mass=np.zeros(2))
    alone = _derivatives(added, none, speed)
    assert alone["N_v"] == pytest.approx(2 * d["N_v"], rel=1e-6)
    assert alone["Y_v"] == 0.0 and alone["N_r"] == 0.0


def test_going_astern_the_bow_trails():
    lift = trailing_sections(box_mesh(BoxHull(length=4.0, beam=2.0, height=1.0)), 0.0, 800.0)
    velocity, rate = np.array([[-2.0, 0.5, 0.0]]), np.zeros((1, 3))
    w = hull_lift(lift.added_mass[None], lift.position[None], velocity, rate, np.zeros((1, 3)))
    assert w.force[0].tolist() == pytest.approx([0.0, -2.0 * 200.0 * 0.5, 0.0])
    assert w.torque[0, 2] == pytest.approx(2.0 * w.force[0, 1])  # at the bow, x = +2 m
    assert w.torque[0, 0] == pytest.approx(0.25 * w.force[0, 1])  # at half the draft
    still = hull_lift(lift.added_mass[None], lift.position[None], np.array([[0.0, 0.5, 0.0]]),
                      rate, np.zeros((1, 3)))
    assert not still.force.any()  # no speed, no lift


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(-5.0, 5.0), min_size=6, max_size=6),
       st.lists(st.floats(-1.0, 1.0), min_size=3, max_size=3))
def test_the_lift_never_feeds_the_cross_flow(velocity, com):
    """Its power at the trailing section, F . (v + w x p), is -|u| a22 V^2 <= 0."""
    lift = trailing_sections(box_mesh(BoxHull(length=6.0, beam=2.5, height=1.2)), 0.1, 900.0)
    v, w = np.array([velocity[:3]]), np.array([velocity[3:]])
    c = np.array([com])
    wrench = hull_lift(lift.added_mass[None], lift.position[None], v, w, c)
    end = lift.position[1 if v[0, 0] < 0.0 else 0] - c[0]
    power = wrench.force[0] @ (v[0] + np.cross(w[0], end))
    assert power <= 1e-9
    assert wrench.torque[0] == pytest.approx(np.cross(end, wrench.force[0]), abs=1e-9)


def test_a_catamarans_sections_hold_its_potential_flow_added_mass():
    mesh = load_mesh(str(SCENARIOS / "otter.stl"))
    edges, side, ends = draft_profile(mesh, 0.0233)
    # two prismatic V pontoons 2 m long drawing 0.1767 m: side area 2 x 0.1767 m per metre
    assert side == pytest.approx(np.full(side.shape, 0.3534), rel=1e-6)  # float32 STL
    assert ends == pytest.approx([0.1767, 0.1767], rel=1e-6)
    lift = trailing_sections(mesh, 0.0233, 86.5)
    assert np.sum(lift.added_mass[0] * np.ones_like(side) * np.diff(edges)) == pytest.approx(86.5)
    with pytest.raises(ValueError, match="out of the water"):
        draft_profile(mesh, 1.0)


def _wigley(lift: str):
    """Journee's Wigley III model (3 m) with a thruster and no rudder, in fresh water."""
    mass, com_z = 77.82646417457902, -0.02645135914839236  # test_towing_tank.HULLS["III"]
    return init_scenario(parse_scenario({"simulation": {"water_density": 1000.0}, "boats": [{
        "hull": {"type": "mesh", "path": str(DATA / "journee_wigley_III_24x4.stl")},
        "mass": mass, "center_of_mass": [0.0, 0.0, com_z],
        "inertia": [mass * 0.105**2, mass * 0.75**2, mass * 0.75**2],
        "inertia_products": [0.0, 0.0, 0.0],
        "propulsion": {"max_thrust": 20.0, "position": [-1.5, 0.0, com_z]},
        "rudder": {"model": "none"},
        "hydrodynamics": {"coefficients": str(DATA / "journee_wigley_III.npz"),
                          "hull_lift": lift}}]}))


def test_a_slender_hull_without_a_rudder_stops_turning_only_with_the_lift():
    """The Wigley III at 1.2 m/s (Fn 0.22), started yawing at 0.1 rad/s, no rudder.

    Its A22 (63.5 kg) is 0.81 of m + A11 (78.3 kg): slender-body theory puts it just short of
    course stability (a prismatic hull is stable when A22 > m + A11), so with the lift its
    yaw rate decays slowly; the Munk moment alone spins it. Measured over 60 s:
    with the lift 5.73 -> 1.02 deg/s at 5 s and 0.60 at 60 s, 49 deg turned; without it
    13.6 deg/s, 733 deg turned.
    """
    with_lift, without = _wigley("trailing_edge"), _wigley("none")
    assert with_lift.boats[0].params.hull_lift is not None
    assert without.boats[0].params.hull_lift is None
    boats = [replace(sc.boats[0], initial=replace(sc.boats[0].initial,
                                                  angular_velocity=np.array([0.0, 0.0, 0.1])))
             for sc in (with_lift, without)]
    calm = WaveField(gravity=with_lift.sea.gravity, depth=with_lift.sea.depth)
    track = sea_trials(boats, calm, [Order("ahead", 0.0, 1.0, 0.0)] * 2, 40.0,
                       1.0 / with_lift.simulation.rate_hz)
    rate = np.degrees(np.abs(track.angular_velocity[:, :, 2]))
    late = track.t >= 20.0
    assert rate[0, late].max() < 1.0 and rate[0, -1] <= rate[0, track.t >= 10.0][0], rate[0]
    assert rate[1, late].min() > 10.0, rate[1]


@pytest.mark.parametrize(("hydro", "match"), [
    ("{coefficients: none, hull_lift: none}", "needs hydrodynamics.coefficients"),
    ("{coefficients: auto, radiation: resonance, hull_lift: trailing_edge}",
     "needs hydrodynamics.radiation cummins"),
    ("{coefficients: auto, hull_lift: wing}", "must be one of: trailing_edge, none"),
    ("{coefficients: auto, radiation: resonance, hull_lift: none}", None),
    ("{coefficients: auto}", None),
])
def test_a_hull_lift_it_cannot_have_is_refused_and_none_is_the_default(tmp_path, hydro, match):
    text = (SCENARIOS / "otter.yaml").read_text()
    shipped = "hydrodynamics: {coefficients: auto, hull_lift: trailing_edge}"
    assert text.count(shipped) == 1
    text = text.replace(shipped, f"hydrodynamics: {hydro}")
    (tmp_path / "otter.stl").write_bytes((SCENARIOS / "otter.stl").read_bytes())
    (tmp_path / "s.yaml").write_text(text)
    if match is None:  # none is always allowed
        assert load_scenario(tmp_path / "s.yaml").boats[0].params.hull_lift is None
        return
    with pytest.raises(ScenarioError, match=match) as info:
        load_scenario(tmp_path / "s.yaml")
    assert "hydrodynamics" in str(info.value)
