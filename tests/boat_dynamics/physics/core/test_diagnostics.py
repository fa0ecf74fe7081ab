import pytest
from ready_scenarios import ready

from boat_dynamics.physics.core.boat import BoatInputs, initial_state
from boat_dynamics.physics.core.diagnostics import boat_report
from ocean_sim.physics.waves import WaveField


def test_report_of_a_floating_box_is_its_hydrostatics():
    sc = ready({"boats": [{"mass": 3280.0, "center_of_mass": [0, 0, -0.1]}]})
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
    sc = ready({"boats": [{"buoyancy": {"model": "sample_points"}}]})
    params = sc.boats[0].params
    deep = boat_report(params, initial_state(params, [0, 0, -3.0]), WaveField())
    assert deep.level == 1 and deep.message == "fully submerged"
    assert "depth clamp at 1 m" in dict(deep.values)["remedies"]
    high = boat_report(params, initial_state(params, [0, 0, 3.0]), WaveField())
    assert high.level == 1 and high.message == "out of the water"


def test_fleet_reports_equal_each_boats_report():
    from boat_dynamics.physics.core.contact import contact
    from boat_dynamics.physics.core.diagnostics import fleet_reports
    from boat_dynamics.physics.core.system import FleetState, System
    from ocean_sim.physics.waves import WaveComponent

    sc = ready({"boats": [
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
    system, state = System.build(params), FleetState.stack(states)
    together = fleet_reports(system, state, contact(system, state, sea), substeps=1)
    alone = [boat_report(p, s, sea) for p, s in zip(params, states, strict=True)]
    assert together == alone
    assert [r.level for r in together] == [0, 0, 0, 1]
    assert dict(together[1].values)["waterplane_area_m2"] != dict(
        together[0].values)["waterplane_area_m2"]


def test_reports_read_the_contact_they_are_given_and_refuse_another_states():
    from boat_dynamics.physics.core import pipeline
    from boat_dynamics.physics.core.contact import contact
    from boat_dynamics.physics.core.diagnostics import fleet_reports
    from boat_dynamics.physics.core.system import FleetInputs, FleetState, System
    from ocean_sim.physics.waves import WaveComponent

    sc = ready({"boats": [
        {"name": "a", "initial_pose": {"position": [0, 0, 0.3], "roll_deg": 5.0}},
        {"name": "b", "buoyancy": {"model": "sample_points"},
         "initial_pose": {"position": [10, 0, 0.2]}}]})
    sea = WaveField((WaveComponent(0.3, 15.0, 0.4, 0.7, 0.2),))
    system = System.build([b.params for b in sc.boats])
    before = FleetState.stack([b.initial for b in sc.boats])
    done = pipeline.step(system, before, FleetInputs.stack([BoatInputs()] * 2), sea, 0.05)
    # the contact the step returns is that of `before`: its reports are before's
    reused = fleet_reports(system, before, done.contact)
    assert reused == fleet_reports(system, before, contact(system, before, sea))
    after = done.state
    moved = fleet_reports(system, after, contact(system, after, sea))
    assert moved != reused  # the boats moved in 0.05 s: their drafts changed
    with pytest.raises(ValueError, match="another system or state"):
        fleet_reports(system, after, done.contact)
