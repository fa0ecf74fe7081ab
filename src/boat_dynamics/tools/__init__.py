"""The user tools behind the ``boatsim`` verbs.

record, replay, compare, plot, teleop, view, the ``ros2`` stand-ins (topic, node, param), rao
and hydro.

They work on rosbag2 (MCAP) bags (:mod:`~boat_dynamics.tools.bags`,
:mod:`~boat_dynamics.tools.recording`), on a running simulation over ROS 2
(:mod:`~boat_dynamics.tools.replay`, :mod:`~boat_dynamics.tools.teleop`,
:mod:`~boat_dynamics.tools.introspection`, :mod:`~boat_dynamics.tools.view`), or on a scenario
(:mod:`~boat_dynamics.tools.rao`, :mod:`~boat_dynamics.tools.hydro`,
:mod:`~boat_dynamics.tools.scenario_keys`).
"""

__all__: list[str] = []
