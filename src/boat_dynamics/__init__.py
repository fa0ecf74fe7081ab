"""boat_dynamics: boats on Gerstner waves, in two layers and the tools around them.

- :mod:`boat_dynamics.physics`: the pure numpy core (force models, the fleet step, scenario
  specs); never imports rclpy or rosbags.
- :mod:`boat_dynamics.ros`: the dynamics node and the runner (thin ROS 2 adapters).
- :mod:`boat_dynamics.tools`: record, replay, compare, plot, teleop.
- :mod:`boat_dynamics.cli`: the ``boatsim`` command.
"""

__all__: list[str] = []
