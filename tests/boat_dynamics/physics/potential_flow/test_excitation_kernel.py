"""The compiled wave excitation against its numpy oracle (``diffraction._excitation_numpy``)."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.potential_flow import diffraction
from boat_dynamics.physics.potential_flow.diffraction import excitation_wrench
from boat_dynamics.physics.potential_flow.hydro import load_coefficients
from ocean_sim.physics.waves import WaveComponent, WaveField

BOX = load_coefficients(Path(__file__).resolve().parents[3] / "data" / "hydro"
                        / "box_4x2x1_d0.5.npz")


def _full_circle(seed: int):
    """The box's file with a random table over a whole circle of directions (no mirroring)."""
    rng = np.random.default_rng(seed)
    directions = np.sort(rng.uniform(0.0, 2 * math.pi, 9))
    shape = (BOX.omega.shape[0], 9, 6)
    table = rng.normal(size=shape) + 1j * rng.normal(size=shape)
    return replace(BOX, directions=directions, diffraction=table,
                   froude_krylov=table[:, ::-1].copy())


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), boats=st.integers(1, 6), components=st.integers(1, 12),
       t=st.floats(0.0, 1e4), moving=st.booleans(), full=st.booleans(),
       part=st.sampled_from(["diffraction", "froude_krylov", "both"]))
def test_the_compiled_excitation_equals_numpys(seed, boats, components, t, moving, full, part):
    rng = np.random.default_rng(seed)
    wavelengths = rng.uniform(1.0, 300.0, components)  # beyond both ends of the table
    # a k <= 0.1 each: sum Q k a <= 0.6, an admissible sea
    amplitudes = rng.uniform(0.0, 0.1, components) * wavelengths / (2 * math.pi)
    sea = WaveField(tuple(WaveComponent(float(a), float(lam), float(rng.uniform(-math.pi, math.pi)),
                                        0.5, float(rng.uniform(0.0, 2 * math.pi)))
                          for a, lam in zip(amplitudes, wavelengths, strict=True)))
    hydro = _full_circle(seed) if full else BOX
    xy = rng.uniform(-500.0, 500.0, (boats, 2))
    heading = rng.uniform(-10.0, 10.0, boats)
    velocity = rng.normal(scale=4.0, size=(boats, 2)) if moving else None  # overtaking too
    got = excitation_wrench(hydro, sea, xy, heading, t, part, velocity)
    want = diffraction._excitation_numpy(hydro, sea, xy, heading, t, part, velocity)
    scale = sum(c.amplitude for c in sea.components) * np.abs(hydro.diffraction).max()
    for g, w in zip(got, want, strict=True):
        assert g.shape == w.shape
        assert np.abs(g - w).max() <= 1e-12 * max(scale, 1.0)


def test_one_boat_gives_vectors_and_a_still_sea_zero():
    sea = WaveField((WaveComponent(0.3, 25.0, 0.4, 0.5, 1.0),))
    force, torque = excitation_wrench(BOX, sea, np.array([3.0, -2.0]), 0.3, 2.0, "diffraction")
    assert force.shape == torque.shape == (3,)
    want = diffraction._excitation_numpy(BOX, sea, np.array([3.0, -2.0]), 0.3, 2.0,
                                         "diffraction")
    assert np.abs(force - want[0]).max() < 1e-9 and np.abs(force).max() > 1.0
    still = excitation_wrench(BOX, WaveField(), np.zeros(2), 0.0, 0.0, "diffraction")
    assert not np.any(still[0]) and not np.any(still[1])
