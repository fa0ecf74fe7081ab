"""Every compiled kernel module of the physics core, and :func:`warm`, which compiles them all.

``make setup`` calls :func:`warm` so that the first run finds every kernel in numba's cache
(:mod:`ocean_sim.physics.jit`); tests/boat_dynamics/physics/test_kernels.py checks that every
module compiled with :func:`ocean_sim.physics.jit.kernel` is listed here.
"""

from __future__ import annotations

import importlib
import time

__all__ = ["KERNEL_MODULES", "warm"]

#: The modules with compiled kernels, each with a ``warm()`` that compiles them.
KERNEL_MODULES = (
    "ocean_sim.physics.surface_kernel",
    "ocean_sim.physics.linear_kernel",
    "boat_dynamics.physics.body.clip_kernel",
    "boat_dynamics.physics.body.owner_kernel",
    "boat_dynamics.physics.body.rigid_body_kernel",
    "boat_dynamics.physics.potential_flow.excitation_kernel",
    "boat_dynamics.physics.potential_flow.memory_kernel",
    "boat_dynamics.physics.force_models.pressure_kernel",
    "boat_dynamics.physics.force_models.actuator_kernel",
)


def warm() -> float:
    """Compile (or load from the cache) every kernel; returns the s it took, imports included."""
    start = time.perf_counter()
    for name in KERNEL_MODULES:
        importlib.import_module(name).warm()
    return time.perf_counter() - start
