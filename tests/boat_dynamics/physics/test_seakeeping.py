"""The default box in regular waves against potential flow: heave and pitch RAOs in head seas,
roll in beam seas.

The boat with ``froude_krylov`` pressure and the Capytaine coefficient file
(tests/data/hydro/box_4x2x1_d0.5.npz: diffraction, added mass and radiation damping at
resonance) is run in a small regular wave until steady; its motion amplitude per metre of wave
is compared with Capytaine's RAO at the file's own frequencies (no interpolation). What holds
today, and is asserted: heave within 15 % or 0.05 m/m from 0.57 to 1.1 boat lengths (the
seed notes' hydrostatic model is 4-33x there), pitch within 15 % at 0.57-0.72 L and 3-5.5 L,
roll in beam seas within 15 % from 0.57 to 1.9 L (its resonance included; measured 0-8 %).
Not yet: heave in long waves is 10-15 % low (the added mass is the resonance value, about
60 % of its low-frequency one), pitch near its resonance (1-2 L) is off by up to 22 %, and
roll in long beam seas is 24-35 % high (sway-roll coupling, A24 and B24, is not modelled):
they need the frequency-dependent, coupled radiation of issue 10 (Cummins).
"""

import math
from pathlib import Path

import numpy as np
import pytest

from boat_dynamics.physics import pipeline
from boat_dynamics.physics.boat import BoatInputs
from boat_dynamics.physics.hydro import load_coefficients
from boat_dynamics.physics.rigid_body import quat_to_euler
from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.physics.system import FleetInputs
from ocean_sim.physics.waves import WaveComponent, WaveField

BOX = Path(__file__).resolve().parents[2] / "data" / "hydro" / "box_4x2x1_d0.5.npz"
HEAD_SEAS = 4  # index of 180 deg (waves travelling toward -x) in the file's directions
BEAM_SEAS = 2  # index of 90 deg (waves travelling toward +y, from starboard)


def _response(omega: float, a: float = 0.02, direction: float = math.pi
              ) -> tuple[float, float, float]:
    """Heave (m/m), roll and pitch (rad/m) amplitudes of the centre of mass."""
    sea = WaveField((WaveComponent(a, 2 * math.pi * 9.81 / omega**2, direction, 0.0, 0.0),))
    sc = parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                    "buoyancy": {"pressure": "froude_krylov"},
                                    "hydrodynamics": {"coefficients": str(BOX)}}]})
    system, state = pipeline.start(sc.boats, sea)
    inputs, dt, period = FleetInputs.stack([BoatInputs()]), 0.01, 2 * math.pi / omega
    steps = round((20.0 + 10 * period) / dt)
    record = steps - round(6 * period / dt)
    heave, roll, pitch, times = [], [], [], []
    for k in range(steps):
        state = pipeline.step(system, state, inputs, sea, dt).state
        if k >= record:
            heave.append(state.position[0, 2])
            angles = quat_to_euler(state.orientation[0])
            roll.append(angles[0])
            pitch.append(angles[1])
            times.append(state.t)
    phase = np.exp(1j * omega * np.array(times))

    def amplitude(x):
        x = np.array(x)
        return 2 * abs(np.mean((x - x.mean()) * phase)) / a

    return amplitude(heave), amplitude(roll), amplitude(pitch)


@pytest.mark.parametrize(("index", "check"), [
    (16, "heave pitch"), (14, "heave pitch"), (12, "heave"), (11, "heave"),
    (6, "pitch"), (5, "pitch"), (4, "pitch"),
])
def test_head_sea_raos_of_the_box_follow_potential_flow(index, check):
    ref = load_coefficients(BOX)
    with np.load(BOX) as data:
        rao = data["rao"][index, HEAD_SEAS]
    heave, _, pitch = _response(float(ref.omega[index]))
    if "heave" in check:
        assert heave == pytest.approx(abs(rao[2]), rel=0.15, abs=0.05)
    if "pitch" in check:
        assert pitch == pytest.approx(abs(rao[4]), rel=0.15)


@pytest.mark.parametrize("index", [16, 14, 12, 11, 8])
def test_beam_sea_roll_of_the_box_follows_potential_flow(index):
    ref = load_coefficients(BOX)
    with np.load(BOX) as data:
        rao = data["rao"][index, BEAM_SEAS]
    _, roll, _ = _response(float(ref.omega[index]), a=0.01, direction=math.pi / 2)
    assert roll == pytest.approx(abs(rao[3]), rel=0.15)
