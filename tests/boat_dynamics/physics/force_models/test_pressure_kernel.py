"""The compiled pressure wrench against its numpy oracle (``_pressure_wrenches_numpy``)."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.clip import clip_hulls
from boat_dynamics.physics.force_models import mesh_buoyancy
from boat_dynamics.physics.force_models.mesh_buoyancy import pressure_wrenches


@settings(max_examples=150, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), boats=st.integers(1, 5), faces=st.integers(0, 120),
       heads=st.booleans())
def test_the_compiled_pressure_wrench_equals_numpys(seed, boats, faces, heads):
    rng = np.random.default_rng(seed)
    vertices = rng.normal(size=(60, 3)) * 3.0
    depths = rng.normal(size=60)
    tri = rng.integers(0, 60, size=(faces, 3))
    wet = clip_hulls(tri, vertices, depths, depths + rng.normal(size=60) if heads else None)
    owner = rng.integers(0, boats, size=faces).take(wet.faces)
    com = rng.normal(size=(boats, 3))
    rho_g = rng.uniform(9000.0, 11000.0, boats)
    got = pressure_wrenches(wet, owner, boats, com, rho_g)
    want = mesh_buoyancy._pressure_wrenches_numpy(wet, owner, boats, com, rho_g)
    scale = 1e5 * max(1.0, float(np.abs(wet.vector_areas).sum()))
    for g, w in zip(got, want, strict=True):
        assert g.shape == w.shape == (boats, 3)
        assert np.abs(g - w).max() <= 1e-12 * scale
