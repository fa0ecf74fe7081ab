"""ocean_sim: the Gerstner sea state (pure numpy) and the ROS 2 ocean node.

The core (:mod:`ocean_sim.waves`, :mod:`ocean_sim.constants`) never imports rclpy;
:mod:`ocean_sim.node` is the thin ROS adapter.
"""

__all__: list[str] = []
