"""No parameter change can end a node: an exception while checking or applying one refuses
it, with the exception in the reason and in the log, and the node takes the next one.

The nodes are made in-process without spinning (no graph): ``set_parameters`` runs the
callback directly. Nothing known raises there today, so the fault is injected.
"""

from rclpy.parameter import Parameter

from boat_dynamics.physics.core.pipeline import init_scenario
from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.ros.node import DynamicsNode, SimClock
from ocean_sim.ros.node import OceanNode


def _refused_then_taken(node, check: str, change: Parameter, monkeypatch) -> None:
    def fail(*_):
        raise ZeroDivisionError("injected")

    monkeypatch.setattr(node, check, fail)
    before = node.get_parameter(change.name).value
    result = node.set_parameters([change])[0]
    assert not result.successful
    assert result.reason == "refused: ZeroDivisionError: injected"
    assert node.get_parameter(change.name).value == before  # nothing applied
    monkeypatch.undo()
    assert node.set_parameters([change])[0].successful  # the node goes on
    assert node.get_parameter(change.name).value == change.value


def test_an_exception_in_the_oceans_parameter_check_refuses_the_change(ros_context, monkeypatch):
    scenario = parse_scenario({})
    node = OceanNode(scenario.sea, lambda: 0.0, context=ros_context)
    try:
        _refused_then_taken(node, "_check_and_apply", Parameter("depth", value=50.0),
                            monkeypatch)
    finally:
        node.destroy_node()


def test_an_exception_in_the_dynamics_parameter_check_refuses_the_change(ros_context, monkeypatch):
    scenario = init_scenario(parse_scenario({}))
    node = DynamicsNode(scenario, SimClock(rate_hz=scenario.simulation.rate_hz, epoch=0.0),
                        context=ros_context)
    try:
        _refused_then_taken(node, "_set_parameters", Parameter("control_mode", value="kinematic"),
                            monkeypatch)
    finally:
        node.destroy_node()
