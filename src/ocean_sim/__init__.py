"""ocean_sim: the Gerstner sea state (pure numpy) and the ROS 2 ocean node.

The core (:mod:`ocean_sim.physics`: waves, spectra, constants) never imports rclpy;
:mod:`ocean_sim.ros` holds the ocean node and the client of its surface service.
"""

__all__: list[str] = []
