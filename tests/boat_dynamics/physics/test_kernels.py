"""Every compiled kernel is warmed by ``make setup``."""

from pathlib import Path

from boat_dynamics.physics import kernels

SRC = Path(__file__).resolve().parents[3] / "src"


def test_every_module_with_compiled_kernels_is_warmed_at_setup():
    compiled = sorted(
        ".".join(path.relative_to(SRC).with_suffix("").parts)
        for path in SRC.rglob("*.py")
        if "from ocean_sim.physics.jit import kernel" in path.read_text())
    assert compiled == sorted(kernels.KERNEL_MODULES)
    assert kernels.warm() >= 0.0
