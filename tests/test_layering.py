"""The physics core never imports rclpy (DESIGN.md: two layers, strictly)."""

import subprocess
import sys

CORE = [
    "ocean_sim.constants", "ocean_sim.spectra", "ocean_sim.waves",
    "boat_dynamics.bags", "boat_dynamics.boat", "boat_dynamics.buoyancy",
    "boat_dynamics.commands", "boat_dynamics.plot",
    "boat_dynamics.control", "boat_dynamics.diagnostics",
    "boat_dynamics.damping", "boat_dynamics.hull", "boat_dynamics.hull_drag",
    "boat_dynamics.fleet", "boat_dynamics.keel", "boat_dynamics.model",
    "boat_dynamics.mesh_buoyancy", "boat_dynamics.process",
    "boat_dynamics.propulsion",
    "boat_dynamics.rigid_body", "boat_dynamics.rudder", "boat_dynamics.scenario",
    "boat_dynamics.tuning",
    "boat_dynamics.wrench",
]


def test_core_modules_do_not_import_rclpy():
    code = (
        "import sys\n"
        f"for m in {CORE!r}: __import__(m)\n"
        "bad = sorted(m for m in sys.modules if m.split('.')[0] in "
        "('rclpy', 'rosbags', 'boat_msgs', 'boat_msgs_py', 'rpyutils'))\n"
        "print(','.join(bad))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == ""


def test_every_core_module_is_listed():
    from pathlib import Path

    src = Path(__file__).resolve().parents[1] / "src"
    adapters = {"ocean_sim.node", "ocean_sim.client", "boat_dynamics.node",
                "boat_dynamics.simulation",
                "boat_dynamics.recording", "boat_dynamics.cli", "boat_dynamics.__main__",
                "boat_dynamics.teleop", "boat_dynamics.replay"}
    modules = {
        ".".join(p.relative_to(src).with_suffix("").parts)
        for pkg in ("ocean_sim", "boat_dynamics") for p in (src / pkg).glob("*.py")
        if p.name != "__init__.py"
    }
    assert modules - adapters == set(CORE)
