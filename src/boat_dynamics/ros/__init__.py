"""The ROS 2 adapters of boatsim: the dynamics node and the runner that starts the nodes.

Thin: they read parameters, check commands, call the physics core
(:mod:`boat_dynamics.physics`) and convert with :mod:`boat_msgs_py`, the only place that knows
topic names, message types and QoS.
"""

__all__: list[str] = []
