"""The pure physics core of boatsim: numpy only, never rclpy or rosbags (tests/test_layering.py).

Folders by role:

- :mod:`.core`: the pipeline (``init`` and ``step`` over a :class:`~.core.system.System` of
  boats), its frozen data (:mod:`.core.model`, :mod:`.core.system`), where the hulls meet the
  water (:mod:`.core.contact`), the force sum (:mod:`.core.forces`), control modes after the
  step, derived parameters (:mod:`.core.tuning`), diagnostics, commands and snapshots.
- :mod:`.body`: the rigid hull: geometry, kinematics and integration, wrenches, and the clip of
  its triangles at the water surface.
- :mod:`.force_models`: one module per force model, each a function returning force and torque
  (buoyancy, hull drag, damping, propulsion, rudder, keel, slamming, mooring, wind, control,
  the towing carriage).
- :mod:`.potential_flow`: a hull's coefficients, the Cummins radiation, diffraction, gap modes,
  and the speed terms of the added mass (Munk moment) and the hull's lift.
- :mod:`.experiments`: a naval architect's runs: RAOs in regular waves, sea trials.
- :mod:`.scenario` (scenario files into frozen specs) and :mod:`.sensors`.

The modules of the flat folder this replaced still import under their old names (for
example ``boat_dynamics.physics.pipeline``), with a DeprecationWarning naming the new one.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings

__all__ = ["MOVED"]

#: Each module of the former flat physics folder and the folder it moved to.
MOVED = {
    **dict.fromkeys(("system", "pipeline", "contact", "forces", "modes", "tuning", "model",
                     "boat", "snapshot", "diagnostics", "commands"), "core"),
    **dict.fromkeys(("hull", "rigid_body", "wrench"), "body"),
    **dict.fromkeys(("buoyancy", "mesh_buoyancy", "hull_drag", "damping", "propulsion",
                     "rudder", "keel", "slamming", "mooring", "wind", "control", "carriage"),
                    "force_models"),
    **dict.fromkeys(("hydro", "radiation", "diffraction", "gap_modes", "added_mass",
                     "hull_lift"), "potential_flow"),
    **dict.fromkeys(("seakeeping", "trials"), "experiments"),
}


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports ``boat_dynamics.physics.X`` of :data:`MOVED` as its new module, and warns."""

    def find_spec(self, name, path, target=None):
        package, _, module = name.rpartition(".")
        if package != __name__ or module not in MOVED:
            return None
        return importlib.util.spec_from_loader(name, self)

    def create_module(self, spec):
        module = spec.name.rpartition(".")[2]
        new = f"{__name__}.{MOVED[module]}.{module}"
        warnings.warn(f"{spec.name} has moved to {new}; the old name will go", DeprecationWarning,
                      stacklevel=2)
        return importlib.import_module(new)

    def exec_module(self, module) -> None:
        """Nothing: :meth:`create_module` returned the new module, already executed."""


if not any(isinstance(f, _MovedModules) for f in sys.meta_path):
    sys.meta_path.append(_MovedModules())
