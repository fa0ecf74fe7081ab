"""Scenarios as ``boatsim run`` steps them: parsed, then initialized by the pipeline."""

from boat_dynamics.physics.pipeline import init_scenario
from boat_dynamics.physics.scenario import Scenario, parse_scenario


def ready(data, **kwargs) -> Scenario:
    """``parse_scenario(data)`` with each boat's parameters derived and its start afloat."""
    return init_scenario(parse_scenario(data, **kwargs))
