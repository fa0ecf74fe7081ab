"""`boatsim rao`: the table, the PNG, potential flow beside the simulation, and bad requests."""

import math
from pathlib import Path

import numpy as np
import pytest

from boat_dynamics.cli import main

ROOT = Path(__file__).resolve().parents[3]
BOX = ROOT / "tests" / "data" / "hydro" / "box_4x2x1_d0.5.npz"


def _box(tmp_path: Path, extra: str = "") -> Path:
    """A scenario of the 4 x 2 x 1 m box with its Capytaine file (``extra``: more keys)."""
    scenario = tmp_path / "box.yaml"
    scenario.write_text(
        "boats:\n  - {name: box, center_of_mass: [0, 0, -0.2],\n"
        f"     buoyancy: {{pressure: froude_krylov}},{extra}\n"
        f"     hydrodynamics: {{coefficients: {BOX}}}}}\n")
    return scenario


def _rows(out: str) -> list[list[str]]:
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("direction_deg"))
    return [line.replace("(", " ").replace(")", " ").split()
            for line in lines[start + 1:] if line.strip() and line.strip()[0].isdigit()]


def test_the_default_scenario_runs_and_draws_a_png(tmp_path, capsys):
    # The default scenario's boat has its shipped coefficient file: potential flow is printed
    # beside; in a 3 L and a 10 L head sea its heave (Froude-Krylov pressure on the wetted
    # hull, nonlinear) follows it within 5 % (measured: 3.5 % at 10 L).
    out_png = tmp_path / "raos.png"
    assert main(["rao", "--wavelengths", "3", "10", "--directions-deg", "180",
                 "-o", str(out_png)]) == 0
    rows = _rows(capsys.readouterr().out)
    assert len(rows) == 2
    assert out_png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for row in rows:
        assert float(row[4]) == pytest.approx(float(row[5]), rel=0.05)
    # beam-sea roll at 1.5 L, near its resonance: potential flow with the boat's own viscous
    # roll damping (the curve used to leave it out: 94.9 against 187 deg/m, -49 %);
    # measured: 94.4 against 93.2
    assert main(["rao", "--wavelengths", "1.5", "--directions-deg", "90",
                 "-o", str(tmp_path / "beam.png")]) == 0
    (beam,) = _rows(capsys.readouterr().out)
    assert float(beam[6]) == pytest.approx(float(beam[7]), rel=0.05)


def test_a_boat_without_coefficients_says_so(tmp_path, capsys):
    scenario = tmp_path / "plain.yaml"
    scenario.write_text("boats: [{buoyancy: {pressure: hydrostatic}, "
                        "hydrodynamics: {coefficients: none}}]\n")
    assert main(["rao", str(scenario), "--wavelengths", "10", "--directions-deg", "180",
                 "-o", str(tmp_path / "r.png")]) == 0
    out = capsys.readouterr().out
    assert "none: no hydrodynamics.coefficients" in out
    # the seed notes' box in a 10 L head sea: heave follows the wave (RAO 1 within 10 %)
    assert float(_rows(out)[0][4]) == pytest.approx(1.0, rel=0.1)


def test_a_boat_with_coefficients_is_printed_beside_potential_flow(tmp_path, capsys):
    scenario = _box(tmp_path)
    assert main(["rao", str(scenario), "--boat", "box", "--wavelengths", "5",
                 "--directions-deg", "180", "90", "-o", str(tmp_path / "r.png")]) == 0
    rows = _rows(capsys.readouterr().out)
    head, beam = (np.array(r, dtype=float) for r in rows)
    # columns: direction, lambda/L, lambda, omega, heave, (pf), roll, (pf), pitch, (pf)
    assert head[0] == 180.0 and beam[0] == 90.0
    assert head[3] == pytest.approx(math.sqrt(2 * math.pi * 9.81 / 20.0), rel=1e-3)
    assert head[4] == pytest.approx(head[5], rel=0.15)  # heave, head seas
    assert head[8] == pytest.approx(head[9], rel=0.15)  # pitch
    assert beam[6] == pytest.approx(beam[7], rel=0.15)  # roll, beam seas
    assert head[9] > 10.0 and beam[7] > 10.0  # deg/m: a real motion, not two zeros


@pytest.mark.parametrize(("args", "message"), [
    (["--wavelengths", "0"], "--wavelengths: 0.0 is not allowed"),
    (["--amplitude", "-1"], "--amplitude: -1.0 is not allowed: metres, > 0"),
    (["--boat", "nobody"], "--boat: 'nobody' is not a boat of the scenario"),
    (["--speed", "60"], "--speed: 60.0 is not allowed: m/s ahead (negative: astern), from -50"),
])
def test_a_bad_request_is_refused_naming_the_option(tmp_path, capsys, args, message):
    assert main(["rao", *args, "-o", str(tmp_path / "r.png")]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "r.png").exists()


def test_a_bad_scenario_is_refused_naming_the_key(tmp_path, capsys):
    scenario = tmp_path / "bad.yaml"
    scenario.write_text("boats:\n  - {hydrodynamics: {coefficients: none, radiation: cummins}}\n")
    assert main(["rao", str(scenario)]) == 2
    assert "hydrodynamics.radiation" in capsys.readouterr().err


def test_the_potential_flow_curve_peaks_at_the_coupled_roll_resonance():
    # The plot's dense potential-flow curve (200 wavelengths): in beam seas the box's roll
    # peaks where its sway-coupled roll mode is (omega 3.067 rad/s: the complex root of
    # det(-w^2 (M + A) - i w B + C) = 0, tests/boat_dynamics/physics/potential_flow/test_hydro.py).
    from boat_dynamics.physics.scenario import parse_scenario
    from boat_dynamics.tools.rao import theory_curve

    params = parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                        "damping": {"critical_ratio": [0, 0, 0]},
                                        "hydrodynamics": {"coefficients": str(BOX)}}]}
                            ).boats[0].params
    curve = theory_curve(params, 9.81, math.inf)
    wavelengths = np.geomspace(4.0, 12.0, 2001)
    roll = curve(wavelengths, math.pi / 2)[:, 1]
    omega = math.sqrt(2 * math.pi * 9.81 / wavelengths[np.argmax(roll)])
    assert omega == pytest.approx(3.067, rel=0.01)
    plain = {"boats": [{"hydrodynamics": {"coefficients": "none"}}]}
    assert theory_curve(parse_scenario(plain).boats[0].params, 9.81, math.inf) is None


def test_towed_the_table_gives_the_encounter_frequency_and_a_ridden_wave_is_refused(
        tmp_path, capsys):
    # 1 m/s ahead into a 2 L head sea of the 4 m box: omega_e = omega + k U; in a following sea
    # of one boat length the wave's speed is 2.50 m/s: towed at 2.5 m/s the boat rides it.
    scenario = _box(tmp_path, " carriage: {speed: 3},")
    assert main(["rao", str(scenario), "--speed", "2.5", "--wavelengths", "1",
                 "--directions-deg", "0", "-o", str(tmp_path / "r.png")]) == 2
    assert "--speed: 2.5 m/s rides the wave of 4 m from 0 deg" in capsys.readouterr().err
    assert main(["rao", str(scenario), "--speed", "1", "--wavelengths", "2",
                 "--directions-deg", "180", "-o", str(tmp_path / "r.png")]) == 0
    out = capsys.readouterr().out
    assert "towed at 1 m/s (Froude number 0.16)" in out
    (row,) = _rows(out)
    k = 2 * math.pi / 8.0
    assert float(row[3]) == pytest.approx(math.sqrt(9.81 * k), abs=5e-4)
    assert float(row[10]) == pytest.approx(math.sqrt(9.81 * k) + k, abs=5e-4)
    assert float(row[8]) == pytest.approx(float(row[9]), rel=0.05)  # pitch, towed
    assert (tmp_path / "r.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
