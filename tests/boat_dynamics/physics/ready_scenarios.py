"""Scenarios as ``boatsim run`` steps them: parsed, then initialized by the pipeline."""

from boat_dynamics.physics.core.pipeline import init_scenario
from boat_dynamics.physics.scenario import Scenario, parse_scenario


def ready(data, **kwargs) -> Scenario:
    """``parse_scenario(data)`` with each boat's parameters derived and its start afloat."""
    return init_scenario(parse_scenario(data, **kwargs))


#: The seed notes' model, which a boat that set nothing got before the physically based default: the
#: hydrostatic mesh pressure rho g (eta - z) and no potential-flow coefficients. Tests of the
#: closed forms of that model (damping, thrust, decay, ...) ask for it by name.
SEED_MODEL = {"buoyancy": {"pressure": "hydrostatic"}, "hydrodynamics": {"coefficients": "none"}}


def seed(boat: dict) -> dict:
    """``boat`` (a scenario's boat block) with :data:`SEED_MODEL` where it sets neither key."""
    out = dict(boat)
    if "buoyancy" not in out:
        out["buoyancy"] = SEED_MODEL["buoyancy"]
    elif out["buoyancy"].get("model", "mesh") == "mesh" and "pressure" not in out["buoyancy"]:
        out["buoyancy"] = {**out["buoyancy"], "pressure": "hydrostatic"}
    out.setdefault("hydrodynamics", SEED_MODEL["hydrodynamics"])
    return out
