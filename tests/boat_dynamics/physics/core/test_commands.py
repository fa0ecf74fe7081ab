import math

import pytest

from boat_dynamics.physics.core.commands import CommandScript, check_command
from boat_dynamics.physics.force_models.propulsion import MAX_THRUSTERS


def test_in_range_passes_unchanged():
    c = check_command(0.25, -1.0, 1.0)
    assert (c.value, c.problem) == (0.25, None)


@pytest.mark.parametrize(("raw", "clamped"), [(1.5, 1.0), (-7.0, -1.0)])
def test_out_of_range_is_clamped_with_the_reason(raw, clamped):
    c = check_command(raw, -1.0, 1.0)
    assert c.value == clamped
    assert "clamped" in c.problem and "[-1, 1]" in c.problem


@pytest.mark.parametrize("raw", [math.nan, math.inf, -math.inf])
def test_non_finite_is_refused(raw):
    c = check_command(raw, -0.6, 0.6, "rad")
    assert c.value is None
    assert "finite" in c.problem and "rad" in c.problem


def test_script_is_piecewise_constant():
    s = CommandScript((0.0, 10.0, 20.0), (1.0, 0.5, 0.0), (0.0, 0.3, -0.3))
    assert s.at(-1.0) == (0.0, 0.0)
    assert s.at(0.0) == (1.0, 0.0)
    assert s.at(9.999) == (1.0, 0.0)
    assert s.at(10.0) == (0.5, 0.3)
    assert s.at(1e6) == (0.0, -0.3)


# ---- the fleet's command intake (what the dynamics node hands each received command)

def _intake(tmp_path):
    """Two boats: one with a fixed and a steerable named thruster (20 deg), one scripted."""
    from boat_dynamics.physics.core.commands import Commanded, CommandIntake
    from boat_dynamics.physics.scenario import load_scenario

    path = tmp_path / "s.yaml"
    path.write_text("""
boats:
  - name: a
    propulsion:
      - {name: left, max_thrust: 100.0, position: [-1.0, 0.5, -0.2]}
      - {name: jet, max_thrust: 100.0, position: [-1.0, -0.5, -0.2], steerable: true,
         max_angle_deg: 20}
  - name: b
    commands: [{t: 0, thrust: 0.5, rudder: 0.1}, {t: 2, thrust: -0.5, rudder: 0.0}]
""")
    sc = load_scenario(path)
    return CommandIntake([Commanded(b.params, b.commands, len(b.thrusters)) for b in sc.boats])


def test_the_intake_keeps_the_last_valid_command_and_counts_the_rest(tmp_path):
    intake = _intake(tmp_path)
    assert intake.thrust(0, 0.4, 1.0).problem is None
    assert intake.thrust(0, math.nan, 1.1).value is None  # ignored: 0.4 stays
    assert intake.thrust(0, 3.0, 1.2).value == 1.0  # clamped
    assert intake.rudder(0, -9.0).value == pytest.approx(-math.radians(35.0))
    a = intake.boats[0]
    assert (a.throttle, a.last_thrust_t, a.received, a.ignored, a.clamped) == (1.0, 1.2, 4, 1, 2)
    # cmd_thrust drives every named thruster; cmd_rudder steers the steerable one within
    # its own limit
    assert a.thrusts == [1.0, 1.0] and a.thrust_t == [1.2, 1.2]
    assert a.angles == [0.0, pytest.approx(-math.radians(20.0))]
    assert intake.thruster_angle(0, 1, 0.5).value == pytest.approx(math.radians(20.0))
    assert intake.thruster_thrust(0, 0, -0.25, 1.3).value == -0.25
    inputs, fell = intake.inputs(1.3, timeout=1.0)
    assert fell == []
    assert inputs.throttle.shape == inputs.thruster_angle.shape == (2, MAX_THRUSTERS)
    assert inputs.throttle[0, :2].tolist() == [-0.25, 1.0]
    assert inputs.thruster_angle[0, 1] == pytest.approx(math.radians(20.0))
    assert inputs.rudder[0] == pytest.approx(-math.radians(35.0))
    # the scripted boat follows its script, whatever the time-out
    assert inputs.throttle[1].tolist() == [0.5] * MAX_THRUSTERS and inputs.rudder[1] == 0.1
    assert intake.inputs(2.5, timeout=1.0)[0].throttle[1].tolist() == [-0.5] * MAX_THRUSTERS


def test_a_throttle_not_renewed_within_the_time_out_falls_to_zero_once(tmp_path):
    from boat_dynamics.physics.core.commands import TimedOut

    intake = _intake(tmp_path)
    intake.thrust(0, 0.6, 0.0)
    intake.thruster_thrust(0, 1, 0.3, 0.5)
    assert intake.inputs(1.0, timeout=1.0)[1] == []  # 1.0 s old: not yet
    inputs, fell = intake.inputs(1.25, timeout=1.0)
    assert fell == [TimedOut(0, None), TimedOut(0, 0)]  # the jet was renewed at 0.5 s
    assert inputs.throttle[0, :2].tolist() == [0.0, 0.3]
    inputs, fell = intake.inputs(1.75, timeout=1.0)
    assert fell == [TimedOut(0, 1)] and inputs.throttle[0, :2].tolist() == [0.0, 0.0]
    assert intake.inputs(5.0, timeout=1.0)[1] == []  # said once


def test_the_intake_resumes_from_its_snapshot(tmp_path):
    intake = _intake(tmp_path)
    intake.thrust(0, 0.6, 0.2)
    intake.thruster_angle(0, 1, -0.1)
    intake.rudder(0, math.inf)
    arrays = intake.snapshot()
    resumed = _intake(tmp_path)
    resumed.restore(arrays)
    assert resumed.boats == intake.boats
    a, b = intake.inputs(3.0, timeout=5.0)[0], resumed.inputs(3.0, timeout=5.0)[0]
    assert all((getattr(a, k) == getattr(b, k)).all()
               for k in ("throttle", "rudder", "thruster_angle"))
