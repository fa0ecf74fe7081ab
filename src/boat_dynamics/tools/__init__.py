"""The user tools behind the ``boatsim`` verbs: record, replay, compare, plot, teleop.

They work on rosbag2 (MCAP) bags (:mod:`~boat_dynamics.tools.bags`,
:mod:`~boat_dynamics.tools.recording`) or on a running simulation over ROS 2
(:mod:`~boat_dynamics.tools.replay`, :mod:`~boat_dynamics.tools.teleop`).
"""

__all__: list[str] = []
