"""The ocean node's current and wind: ROS parameters, checked, published on a latched topic.

Parameters of ``/ocean`` (changeable at run time, e.g. ``ros2 param set`` or the parameter
service): ``current.speed`` (m/s, 0-20), ``current.direction_deg`` (-360..360, toward),
``wind.speed`` (m/s, 0-100, the one-hour mean at 10 m), ``wind.direction_deg``, ``wind.gusts``
(``none`` or ``norsok``) and ``wind.gust_components`` (1-1000; the bounds of
:mod:`ocean_sim.physics.environment`, every reader's). A change is checked as a whole
and refused with the reason (the old environment kept), or applied and republished on
``/ocean/environment``, which the dynamics nodes follow.
"""

from __future__ import annotations

import math

from boat_msgs.msg import Environment as EnvironmentMsg
from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor
from rclpy.node import Node

from boat_msgs_py.convert import environment_to_msg, seconds_to_time
from boat_msgs_py.names import ENVIRONMENT
from boat_msgs_py.qos import ENVIRONMENT_QOS
from boat_msgs_py.tap import Tap, TappedPublisher
from ocean_sim.physics.environment import (
    GUST_MODELS,
    MAX_CURRENT_SPEED,
    MAX_GUST_COMPONENTS,
    MAX_WIND_SPEED,
    Environment,
    Wind,
)

__all__ = ["ENVIRONMENT_PARAMETERS", "EnvironmentParameters"]

#: name -> (description with unit, low, high) of the numeric parameters.
ENVIRONMENT_PARAMETERS = {
    "current.speed": ("Current speed, m/s (uniform).", 0.0, MAX_CURRENT_SPEED),
    "current.direction_deg": ("Heading the current flows toward, deg, CCW from +x (east).",
                              -360.0, 360.0),
    "wind.speed": ("Mean wind speed at 10 m, m/s (one-hour mean).", 0.0, MAX_WIND_SPEED),
    "wind.direction_deg": ("Heading the wind blows toward, deg, CCW from +x (east).",
                           -360.0, 360.0),
}


class EnvironmentParameters:
    """Declares the environment parameters on ``node`` and publishes their environment.

    Args:
        node: the ocean node.
        environment: the scenario's environment (its wind's seed is kept for the gusts).
        epoch: s, the stamp of simulation time 0; None = not known yet (nothing is published
            before :meth:`start`).
        tap: the recorder's tap, or None.
    """

    def __init__(self, node: Node, environment: Environment, epoch: float | None,
                 tap: Tap | None) -> None:
        self._node = node
        self.environment = environment
        self._epoch = epoch
        values = {"current.speed": environment.current_speed,
                  "current.direction_deg": math.degrees(environment.current_direction),
                  "wind.speed": environment.wind.speed,
                  "wind.direction_deg": math.degrees(environment.wind.direction)}
        for name, (text, low, high) in ENVIRONMENT_PARAMETERS.items():
            node.declare_parameter(name, float(values[name]), ParameterDescriptor(
                description=text,
                floating_point_range=[FloatingPointRange(from_value=low, to_value=high)]))
        node.declare_parameter("wind.gusts", environment.wind.gusts, ParameterDescriptor(
            description=f"Gust model: one of {', '.join(GUST_MODELS)} (NORSOK spectrum)."))
        node.declare_parameter("wind.gust_components", environment.wind.components,
                               ParameterDescriptor(
                                   description="Harmonic components of the gusts.",
                                   integer_range=[IntegerRange(
                                       from_value=1, to_value=MAX_GUST_COMPONENTS, step=1)]))
        self._pub = TappedPublisher(node, EnvironmentMsg, ENVIRONMENT, ENVIRONMENT_QOS, tap)
        if epoch is not None:
            self.publish()

    def start(self, epoch: float) -> None:
        """Take the stamp of simulation time 0 (s) and publish the environment."""
        self._epoch = epoch
        self.publish()

    @staticmethod
    def names() -> set[str]:
        """Every parameter this class owns."""
        return {*ENVIRONMENT_PARAMETERS, "wind.gusts", "wind.gust_components"}

    def check(self, changes: dict) -> tuple[Environment | None, str | None]:
        """(the environment ``changes`` would make, None) or (None, why it is refused).

        ``changes`` maps parameter names to new values; the others keep theirs. The numeric
        ranges are rclpy's to enforce (the descriptors); this checks the gust model.
        """
        value = {k: changes.get(k, self._node.get_parameter(k).value) for k in self.names()}
        if value["wind.gusts"] not in GUST_MODELS:
            return None, (f"wind.gusts = {value['wind.gusts']!r} is not allowed: one of "
                          f"{', '.join(GUST_MODELS)}")
        wind = Wind.make(float(value["wind.speed"]), math.radians(value["wind.direction_deg"]),
                         value["wind.gusts"], int(value["wind.gust_components"]),
                         self.environment.wind.seed)
        return Environment(float(value["current.speed"]),
                           math.radians(value["current.direction_deg"]), wind), None

    def apply(self, environment: Environment) -> None:
        """Take ``environment``, republish it and log it."""
        self.environment = environment
        self.publish()
        self._node.get_logger().info(f"new environment: {describe(environment)}")

    def publish(self) -> None:
        """(Re)publish the environment on /ocean/environment, stamped at simulation time 0."""
        if self._epoch is None:
            return  # published by start()
        self._pub.publish(environment_to_msg(self.environment, seconds_to_time(self._epoch)))


def describe(environment: Environment) -> str:
    """One line on the current and the wind, degrees at the edge."""
    wind = environment.wind
    return (f"current {environment.current_speed:g} m/s toward "
            f"{math.degrees(environment.current_direction):g} deg, wind {wind.speed:g} m/s "
            f"toward {math.degrees(wind.direction):g} deg, gusts {wind.gusts}")
