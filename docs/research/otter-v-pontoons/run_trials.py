"""Calm-water trials of scenario files, as /tmp/otl/run.py: 60 s, straight at full thrust,
the same started yawing at 0.1 rad/s, and turning with thrusters (1.0, 0.5).
Prints the late (t > 40 s) surge speed, sway speed, yaw rate, the heading change over 60 s,
the hull's m, A11, A22, A66 (added_mass_inf of its coefficients) and the memory's fit error.
usage: run_trials.py SCENARIO [SCENARIO ...]"""
import math
import sys
import time
sys.dont_write_bytecode = True
from dataclasses import replace

import numpy as np

from boat_dynamics.physics.model import initial_state, reference_pose  # noqa: F401 (as run.py)
from boat_dynamics.physics.pipeline import init_scenario
from boat_dynamics.physics.scenario import load_scenario
from boat_dynamics.physics.trials import Order, sea_trials
from ocean_sim.physics.waves import WaveField

for f in sys.argv[1:]:
    c0 = time.process_time()
    sc = init_scenario(load_scenario(f))
    b = sc.boats[0]
    p = b.params
    h = p.hydro
    print(f, "hull_lift", p.hull_lift, "coefficients", None if h is None else h.source)
    if h is not None:
        a = h.added_mass_inf
        print(f"  m {p.mass:.1f} kg, A11 {a[0, 0]:.2f} kg, A22 {a[1, 1]:.2f} kg, A66 {a[5, 5]:.2f} "
              f"kg m^2, gap modes {len(h.gap_modes)}; m + A11 {p.mass + a[0, 0]:.2f} vs A22 "
              f"{a[1, 1]:.2f}")
    mem = getattr(p, "radiation_memory", None)
    if mem is not None:
        print(f"  radiation memory: {mem.poles.shape[0]} states, error {mem.error:.4f}")
    calm = WaveField(gravity=sc.sea.gravity, depth=sc.sea.depth)
    pert = replace(b, initial=replace(b.initial, angular_velocity=np.array([0, 0, 0.1])))
    orders = [Order("ahead", 0.0, 1.0, 0.0), Order("ahead-yawing", 0.0, 1.0, 0.0),
              Order("turn", 0.0, (1.0, 0.5), 0.0)]
    tr = sea_trials([b, pert, b], calm, orders, 60.0, 1 / sc.simulation.rate_hz)
    late = tr.t > 40
    for i, o in enumerate(orders):
        print(f"  {o.name:14s} u {tr.velocity[i, late, 0].mean():.3f} m/s"
              f"  v {tr.velocity[i, late, 1].mean():+.3f} m/s"
              f"  r {math.degrees(tr.angular_velocity[i, late, 2].mean()):+.2f} deg/s"
              f"  turned {math.degrees(tr.attitude[i, -1, 2] - tr.attitude[i, 0, 2]):+.0f} deg")
    print("  r(t) yawing, deg/s every 5 s:",
          np.round(np.degrees(tr.angular_velocity[1, ::50, 2]), 3).tolist())
    print(f"  CPU {time.process_time() - c0:.0f} s", flush=True)
