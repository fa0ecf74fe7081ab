#!/usr/bin/env python3
"""The DTMB 5512 model towed in regular head seas by boatsim, against the IIHR data (digitized
from FRyDoM's figures), as tests/boat_dynamics/physics/test_towing_tank.py does for Journee's
Wigley hulls; and linear potential flow's frequency-domain answer from the same file.

Usage (one point after another; appends JSON lines to results_<hull tag>.jsonl, skipping points
already there):
    OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 PYTHONPATH=/work/main/src:/tmp/dtmb/overlay \
        /tmp/wigley/venv/bin/python run_points.py [--hull dtmb5512.stl] [--only I,J,...]
"""

import argparse
import csv
import json
import math
import time
from pathlib import Path

import numpy as np

from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.physics.seakeeping import (encounter_frequency, potential_flow_rao,
                                              regular_wave_response, rigid_body_matrix)

HERE = Path(__file__).resolve().parent
DATA = Path("/tmp/pitchdata/DTMB5512_frydom_digitized_lambda.csv")
LENGTH, G = 3.048, 9.81
#: the coefficient file's mass properties (dtmb_reference.py; read back from the file)
NPZ = HERE / "dtmb5512.npz"


def measured():
    """[(Fn, lambda/L, heave x3/A, pitch x5/(kA) or None)] in the file's order."""
    rows = []
    with DATA.open() as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    for r in csv.DictReader(lines):
        fn = float(r["Fn"])
        pitch = float(r["pitch_TF_as_plotted"]) if fn == 0.0 else None
        rows.append((fn, float(r["lambda_over_L"]), float(r["heave_TF_x3_over_A"]), pitch))
    return rows


def dtmb(hull: Path):
    """The model as a user would give it: hull, mass properties, coefficients, fresh water."""
    z = np.load(NPZ)
    mass, com, M = float(z["mass"]), [float(c) for c in z["center_of_mass"]], z["inertia_matrix"]
    return parse_scenario({"simulation": {"water_density": 1000.0}, "boats": [{
        "hull": {"type": "mesh", "path": str(hull)},
        "mass": mass, "center_of_mass": com,
        "inertia": [float(M[3, 3]), float(M[4, 4]), float(M[5, 5])],
        "inertia_products": [0.0, 0.0, 0.0],
        "hydrodynamics": {"coefficients": str(NPZ)}}]}).boats[0].params


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--hull", default=str(HERE / "dtmb5512.stl"))
    ap.add_argument("--only", default="")
    ap.add_argument("--out", default="")
    a = ap.parse_args()
    hull = Path(a.hull)
    out = Path(a.out or HERE / f"results_{hull.stem}.jsonl")
    done = set()
    if out.exists():
        done = {json.loads(ln)["index"] for ln in out.read_text().splitlines() if ln.strip()}
    params = dtmb(hull)
    mass = rigid_body_matrix(params)
    rows = measured()
    order = [int(i) for i in a.only.split(",")] if a.only else range(len(rows))
    for i in order:
        if i in done:
            continue
        fn, lam, heave, pitch = rows[i]
        wavelength = lam * LENGTH
        k = 2 * math.pi / wavelength
        omega = math.sqrt(G * k)
        speed = fn * math.sqrt(G * LENGTH)
        amplitude = min(0.005 * LENGTH, 0.05 / k)
        w_e = encounter_frequency(omega, k, speed, math.pi)
        pf = potential_flow_rao(params.hydro, mass, omega, math.pi, encounter=w_e, speed=speed,
                                held=(0, 1, 5) if speed else ())
        t0 = time.process_time()
        r = regular_wave_response(params, wavelength, math.pi, amplitude, speed=speed)
        cpu = time.process_time() - t0
        rec = dict(index=i, Fn=fn, lam=lam, omega=omega, encounter=r.encounter,
                   amplitude=amplitude, heave_meas=heave, pitch_meas=pitch,
                   heave_sim=r.heave, pitch_sim=r.pitch / k, roll_sim=r.roll,
                   heave_pf=float(abs(pf[2])), pitch_pf=float(abs(pf[4]) / k), cpu=cpu)
        print(json.dumps(rec), flush=True)
        with out.open("a") as fh:
            fh.write(json.dumps(rec) + "\n")


if __name__ == "__main__":
    main()
