"""Heave and pitch in head seas, at rest and towed at speed, against towing-tank measurements.

Journee's (1992) Wigley models (J.M.J. Journee, "Experiments and calculations on four Wigley
hullforms", Delft University of Technology, Ship Hydromechanics Laboratory report 909): 3 m long,
0.3 m beam, 0.1875 m draft, fresh water, k_yy 0.25 L. The measured values are the report's as
transcribed by risingtideresearch/michell (crates/michell-seakeeping/src/validation.rs, commit
14db901ddaedda992cb99dc71ee68fbe44a13785: Wigley III heave, Table 8-III, and the zero-speed
heave and pitch, Table 10-III; its docs/seakeeping-findings.md, commit
1f4be505e8281f187dad2a0b5c33b0822027317e, sec. 4.2: Wigley I heave at Fn 0.3): motions against
lambda / L of the wave (not of encounter); pitch given as theta_a / (2 pi zeta_a / L), here
theta_a / (k zeta_a) = that x lambda / L.

Each model is the boat a user gets from its hull, mass and coefficient file
(tests/data/hydro/journee_wigley_reference.py; nothing else set: ``froude_krylov`` pressure,
Cummins radiation, diffraction, the default damping), towed on a carriage at U = Fn sqrt(g L)
into a small regular head sea
(:func:`boat_dynamics.physics.experiments.seakeeping.regular_wave_response`,
as ``boatsim rao --speed``). Asserted: within 20 % of the measurement (the issue's bound, where
potential flow itself agrees: its zero-speed heave within 8 %, its pitch 7-12 % low, its heave
at speed with Salvesen-Tuck-Faltinsen's terms within 9 %).

Measured (docs/DESIGN.md has the table with the values before these models):
Wigley III at Fn 0 heave -3, +7, +4 %, pitch -10, -9, -13 %; at Fn 0.2 heave +18, +5, -1 %;
at Fn 0.3 +19, +15, +15, +2 %; Wigley I at Fn 0.3, lambda / L 1.25 (its heave resonance) -3 %.
The diffraction is looked up at the encounter frequency (:mod:`.diffraction`); at the wave's own
frequency the Wigley III's heave at Fn 0.3 comes within 3 % and the Wigley I's falls 19 % short.
"""

import math
from pathlib import Path

import pytest

from boat_dynamics.physics.experiments.seakeeping import regular_wave_response
from boat_dynamics.physics.scenario import parse_scenario

DATA = Path(__file__).resolve().parents[3] / "data" / "hydro"
LENGTH, G = 3.0, 9.81
#: Mass (rho V of the 76 x 10 mesh) and centre of mass (body z, at the centre of buoyancy's
#: height) of the coefficient files (journee_wigley_reference.py).
HULLS = {"I": (93.9994868562572, -0.036293494700838355),
         "III": (77.82646417457902, -0.02645135914839236)}
TOLERANCE = 0.2

#: (hull, Froude number, lambda / L, heave z_a / zeta_a, pitch theta_a / (k zeta_a) or None)
MEASURED = [
    ("III", 0.0, 1.0, 0.29, 0.57), ("III", 0.0, 1.5, 0.57, 0.855),
    ("III", 0.0, 2.0, 0.74, 1.00),
    ("III", 0.2, 1.25, 0.71, None), ("III", 0.2, 1.5, 0.81, None), ("III", 0.2, 2.0, 0.90, None),
    ("III", 0.3, 1.25, 1.28, None), ("III", 0.3, 1.384, 1.11, None),
    ("III", 0.3, 1.5, 1.01, None), ("III", 0.3, 2.0, 0.99, None),
    ("I", 0.3, 1.25, 2.52, None),
]


def wigley(hull: str):
    """The model as a user would give it: hull, mass properties, coefficients, fresh water."""
    mass, com_z = HULLS[hull]
    return parse_scenario({"simulation": {"water_density": 1000.0}, "boats": [{
        "hull": {"type": "mesh", "path": str(DATA / f"journee_wigley_{hull}_24x4.stl")},
        "mass": mass, "center_of_mass": [0.0, 0.0, com_z],
        "inertia": [mass * 0.105**2, mass * 0.75**2, mass * 0.75**2],
        "inertia_products": [0.0, 0.0, 0.0],
        "hydrodynamics": {"coefficients": str(DATA / f"journee_wigley_{hull}.npz")}}]}
                          ).boats[0].params


@pytest.mark.parametrize(("hull", "froude", "wavelength", "heave", "pitch"), MEASURED)
def test_heave_and_pitch_in_head_seas_follow_the_towing_tank(hull, froude, wavelength, heave,
                                                             pitch):
    k = 2 * math.pi / (wavelength * LENGTH)
    amplitude = min(0.005 * LENGTH, 0.05 / k)  # small: k a at most 0.05
    r = regular_wave_response(wigley(hull), wavelength * LENGTH, math.pi, amplitude,
                              speed=froude * math.sqrt(G * LENGTH))
    assert r.encounter == pytest.approx(math.sqrt(G * k) + k * froude * math.sqrt(G * LENGTH))
    assert r.heave == pytest.approx(heave, rel=TOLERANCE)
    if pitch is not None:
        assert r.pitch / k == pytest.approx(pitch, rel=TOLERANCE)
