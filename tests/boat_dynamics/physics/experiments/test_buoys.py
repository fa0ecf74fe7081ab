"""Buoys (``world.buoys``): afloat at their draft, their periods, a swell and a current.

A buoy is a cylinder hull under the waves' Froude-Krylov pressure, without potential-flow
coefficients (it is small against the waves: k r = 0.05 to 0.1 here, where radiation and
diffraction are small and a neutrally buoyant body moves with the water), held by an elastic
anchor line. Its checks against closed forms: the draft it floats at, its heave and roll
periods (the hydrostatics of an upright cylinder), its heave in a long swell, and where a
steady current holds it on its line.
"""

import math

import numpy as np

from boat_dynamics.physics.body.rigid_body import quat_from_euler
from boat_dynamics.physics.core import pipeline
from boat_dynamics.physics.core.commands import Commanded, CommandIntake
from boat_dynamics.physics.scenario import parse_scenario
from ocean_sim.physics.constants import GRAVITY

RHO = 1025.0
BUOY = {"name": "b", "radius": 0.4, "height": 1.5}  # draft 0.75, anchor 10 m down
N = 24  # facets round the hull (CYLINDER_SEGMENTS)
DT = 0.01


def _buoy(ocean=None, environment=None, tilt=0.0, lift=0.0):
    doc = {"ocean": ocean or {"components": []}, "environment": environment or {},
           "world": {"buoys": [BUOY]}, "boats": [{"name": "boat"}]}
    sc = parse_scenario(doc)
    (spec,) = [b for b in sc.boats if b.kind == "buoy"]
    initial = spec.initial
    initial = type(initial)(**{**initial.__dict__,
                               "orientation": quat_from_euler(tilt, 0.0, 0.0),
                               "position": initial.position + [0.0, 0.0, lift]})
    return sc, spec.__class__(**{**spec.__dict__, "initial": initial})


def _run(sc, spec, seconds):
    """(K, 8) t, x, y, z, roll, pitch of the centre of mass, and the line's tension (N)."""
    system, state = pipeline.start((spec,), sc.sea)
    intake = CommandIntake([Commanded(spec.params, spec.commands, 1)])
    rows = []
    while state.t < seconds - 1e-9:
        inputs, _ = intake.inputs(state.t, math.inf)
        step = pipeline.step(system, state, inputs, sc.sea, DT, environment=sc.environment)
        state = step.state
        x, y, z, w = state.orientation[0]
        roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
        pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
        rows.append((state.t, *state.position[0], roll, pitch,
                     float(np.linalg.norm(step.forces.mooring.force[0]))))
    return np.array(rows), system


def _root(f, low, high):
    """The root of f in [low, high] (a sign change), by bisection to 1e-12."""
    for _ in range(200):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if (f(low) < 0) == (f(mid) < 0) else (low, mid)
    return 0.5 * (low + high)


def _period(t, signal):
    """s, the mean period between the signal's up-crossings of its final mean."""
    s = signal - signal[len(signal) // 2:].mean()
    up = t[np.flatnonzero((s[:-1] < 0) & (s[1:] >= 0))]
    return float(np.diff(up[:4]).mean())


def _waterplane():
    """m^2 and m^4: the 24-gon's area and its second moment about a diameter."""
    r, a = BUOY["radius"], 2 * math.pi / N
    area = N / 2 * r**2 * math.sin(a)
    return area, area * r**2 * (2 + math.cos(a)) / 12  # regular polygon, circumradius r


def test_a_buoy_floats_upright_at_its_draft():
    sc, spec = _buoy()
    track, _ = _run(sc, spec, 2.0)
    bottom = track[-1, 3] - spec.params.center_of_mass[2] - BUOY["height"] / 2
    assert abs(bottom + 0.75) < 1e-4, f"its bottom at {bottom:.5f} m, not at its draft -0.75"
    assert np.abs(track[:, 4:6]).max() < 1e-9 and track[:, 6].max() == 0.0  # line slack


def test_its_heave_and_roll_periods_are_the_upright_cylinders():
    # heave: T = 2 pi sqrt(m / (rho g A_wp)); roll: T = 2 pi sqrt(I_xx / (rho g V GM)),
    # GM = KB + BM - KG; both damped at the default ratios (0.2 heave, 0.1 roll)
    sc, spec = _buoy(lift=0.1)
    p = spec.params
    area, second = _waterplane()
    heave = 2 * math.pi * math.sqrt(p.mass / (RHO * GRAVITY * area)) / math.sqrt(1 - 0.2**2)
    track, _ = _run(sc, spec, 6.0)
    assert abs(_period(track[:, 0], track[:, 3]) / heave - 1) < 0.03
    volume = p.mass / RHO
    draft = 0.75
    gm = draft / 2 + second / volume - (p.center_of_mass[2] + BUOY["height"] / 2)
    roll = (2 * math.pi * math.sqrt(p.inertia[0] / (RHO * GRAVITY * volume * gm))
            / math.sqrt(1 - 0.1**2))
    sc, spec = _buoy(tilt=math.radians(10.0))
    track, _ = _run(sc, spec, 8.0)
    measured = _period(track[:, 0], track[:, 4])
    assert abs(measured / roll - 1) < 0.02, f"roll period {measured:.3f} s, closed form {roll:.3f}"


def test_it_rides_a_long_swell_and_stays_in_its_watch_circle():
    # lambda 40 m (k r = 0.06), 0.3 m: its heave follows the surface (RAO 1 below its
    # 1.7 s heave period; the swell's is 5.1 s); its tilt follows the slope k a = 2.7 deg,
    # amplified by 1 / (1 - (T_roll / T)^2) = 1.2 at most
    swell = {"components": [{"amplitude": 0.3, "wavelength": 40.0, "steepness": 0.5}]}
    sc, spec = _buoy(ocean=swell)
    track, _ = _run(sc, spec, 40.0)
    late = track[track[:, 0] > 10.0]
    heave = (late[:, 3].max() - late[:, 3].min()) / 2
    assert abs(heave / 0.3 - 1) < 0.1, f"heave amplitude {heave:.3f} m in a 0.3 m swell"
    tilt = math.degrees(np.abs(late[:, 5]).max())
    slope = math.degrees(2 * math.pi / 40.0 * 0.3)
    assert slope < tilt < 1.4 * slope, f"tilt {tilt:.2f} deg on a slope of {slope:.2f}"
    line = spec.params.anchor_line
    reach = -line.anchor[2] - 0.75
    watch = math.sqrt(line.length**2 - reach**2)
    assert np.hypot(track[:, 1], track[:, 2]).max() < watch + 0.05


def test_a_current_holds_it_on_its_line_where_drag_tension_and_buoyancy_balance():
    # U = 1 m/s: the form drag D = 1/2 rho C_d (2 r) T U^2 pulls it downstream until the
    # stretched line (tension k (l - L)) holds it, sunk by s where rho g A_wp s is the
    # tension's vertical share: solved here for the offset, which the run must reach
    sc, spec = _buoy(environment={"current": {"speed": 1.0, "direction_deg": 0.0}})
    track, system = _run(sc, spec, 90.0)
    line, area = spec.params.anchor_line, _waterplane()[0]
    drag = system.damping_quadratic[0, 0] * 1.0**2
    reach = -line.anchor[2] - 0.75

    def imbalance(s):  # for a sink s: the line's vertical pull minus the lost buoyancy
        vertical = RHO * GRAVITY * area * s
        tension = math.hypot(drag, vertical)
        length = line.length + tension / line.stiffness
        offset = math.sqrt(length**2 - (reach - s) ** 2)
        return vertical / drag - (reach - s) / offset

    sink = _root(imbalance, 1e-6, 0.5)
    tension = math.hypot(drag, RHO * GRAVITY * area * sink)
    offset = math.sqrt((line.length + tension / line.stiffness) ** 2 - (reach - sink) ** 2)
    late = track[track[:, 0] > 70.0]
    x = late[:, 1].mean()
    assert abs(x - offset) < 0.03, f"held {x:.3f} m downstream; closed form {offset:.3f} m"
    assert abs(late[:, 6].mean() / tension - 1) < 0.05
    assert abs(late[:, 2]).max() < 1e-6  # straight downstream
