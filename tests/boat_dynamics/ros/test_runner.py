"""The runner's pure parts: which command topics a sharded run's own recorder leaves alone."""

from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.ros.runner import _command_topics


def test_the_command_topics_are_those_the_boats_subscribe_to():
    scenario = parse_scenario({"boats": [
        {"name": "a"},
        {"name": "b", "commands": [{"t": 0.0, "thrust": 1.0, "rudder": 0.0}]},  # scripted
        {"name": "c", "propulsion": [
            {"name": "left", "steerable": True, "max_angle_deg": 30.0},
            {"name": "right"}]}]})
    assert _command_topics(scenario.boats) == {
        "/a/cmd_thrust", "/a/cmd_rudder", "/c/cmd_thrust", "/c/cmd_rudder",
        "/c/thrusters/left/thrust", "/c/thrusters/left/angle", "/c/thrusters/right/thrust"}
