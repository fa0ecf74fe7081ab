import numpy as np
import pytest

from boat_dynamics.boat import BoatInputs, initial_state
from boat_dynamics.diagnostics import boat_report
from boat_dynamics.scenario import parse_scenario
from ocean_sim.waves import WaveField


def test_report_of_a_floating_box_is_its_hydrostatics():
    sc = parse_scenario({"boats": [{"mass": 3280.0, "center_of_mass": [0, 0, -0.1]}]})
    params = sc.boats[0].params
    d = 3280.0 / (1025 * 8.0)  # draft 0.4 m
    state = initial_state(params, [0.0, 0.0, 0.5 - d])
    r = boat_report(params, state, WaveField(), substeps=2)
    values = dict(r.values)
    assert r.level == 0 and r.message == "floating, 40 % submerged"
    assert float(values["draft_m"]) == pytest.approx(d, abs=1e-4)
    assert float(values["submerged_volume_m3"]) == pytest.approx(8.0 * d, abs=1e-4)
    assert float(values["waterplane_area_m2"]) == pytest.approx(8.0, abs=1e-4)
    gm = d / 2 + 4.0 / (12 * d) - 0.4
    assert float(values["metacentric_height_m"]) == pytest.approx(gm, abs=1e-4)
    assert values["control_mode"] == "dynamic" and values["buoyancy_model"] == "mesh"
    assert "2 substeps" in values["remedies"] and "quadratic heave drag" in values["remedies"]


def test_report_warns_when_submerged_or_airborne():
    sc = parse_scenario({"boats": [{"buoyancy": {"model": "sample_points"}}]})
    params = sc.boats[0].params
    deep = boat_report(params, initial_state(params, [0, 0, -3.0]), WaveField())
    assert deep.level == 1 and deep.message == "fully submerged"
    assert "depth clamp at 1 m" in dict(deep.values)["remedies"]
    high = boat_report(params, initial_state(params, [0, 0, 3.0]), WaveField())
    assert high.level == 1 and high.message == "out of the water"


def test_fleet_reports_equal_each_boats_report():
    from boat_dynamics.diagnostics import fleet_reports
    from boat_dynamics.fleet import Fleet, FleetState
    from ocean_sim.waves import WaveComponent

    sc = parse_scenario({"boats": [
        {"name": "a", "mass": 3280.0, "initial_pose": {"position": [0, 0, 0.1]}},
        {"name": "b", "mass": 2000.0, "hull": {"type": "box", "length": 3.0, "beam": 1.5,
                                                "height": 1.0},
         "initial_pose": {"position": [10, 0, 0.0], "roll_deg": 10.0}},
        {"name": "c", "buoyancy": {"model": "sample_points"},
         "initial_pose": {"position": [20, 0, 0.0]}},
        {"name": "d", "buoyancy": {"model": "sample_points", "max_depth": 0.5},
         "initial_pose": {"position": [30, 0, 3.0]}},
    ]})
    sea = WaveField((WaveComponent(0.3, 15.0, 0.4, 0.7, 0.2),))
    params = [b.params for b in sc.boats]
    states = [b.initial for b in sc.boats]
    together = fleet_reports(Fleet(params), FleetState.stack(states), sea, substeps=1)
    alone = [boat_report(p, s, sea) for p, s in zip(params, states, strict=True)]
    assert together == alone
    assert [r.level for r in together] == [0, 0, 0, 1]
    assert dict(together[1].values)["waterplane_area_m2"] != dict(
        together[0].values)["waterplane_area_m2"]


def test_reports_reuse_the_steps_contacts_only_for_the_same_state():
    from boat_dynamics.diagnostics import fleet_reports
    from boat_dynamics.fleet import Fleet, FleetInputs, FleetState, fleet_step
    from ocean_sim.waves import WaveComponent

    sc = parse_scenario({"boats": [
        {"name": "a", "initial_pose": {"position": [0, 0, 0.3], "roll_deg": 5.0}},
        {"name": "b", "buoyancy": {"model": "sample_points"},
         "initial_pose": {"position": [10, 0, 0.2]}}]})
    sea = WaveField((WaveComponent(0.3, 15.0, 0.4, 0.7, 0.2),))
    params = [b.params for b in sc.boats]
    fleet = Fleet(params)
    before = FleetState.stack([b.initial for b in sc.boats])
    after, _ = fleet_step(fleet, before, FleetInputs.stack([BoatInputs()] * 2), sea, 0.05)
    # the fleet now holds the contacts of `before` (where the step evaluated its forces)
    assert fleet.memo is not None and fleet.memo[0][0] is before.position
    reused = fleet_reports(fleet, before, sea)
    fresh = fleet_reports(Fleet(params), before, sea)
    assert reused == fresh
    moved = fleet_reports(fleet, after, sea)  # another state: computed anew
    assert moved == fleet_reports(Fleet(params), after, sea)
    assert moved != reused  # the boats moved in 0.05 s: their drafts changed
    # and the next step reuses the contacts the reports computed: bit-identical to a fresh fleet
    assert fleet.memo[0][0] is after.position
    inputs = FleetInputs.stack([BoatInputs(0.5, 0.1)] * 2)
    reusing, _ = fleet_step(fleet, after, inputs, sea, 0.05)
    fresh_step, _ = fleet_step(Fleet(params), after, inputs, sea, 0.05)
    assert np.array_equal(reusing.position, fresh_step.position)
    assert np.array_equal(reusing.orientation, fresh_step.orientation)
