"""boat_msgs_py: the ROS contract of boatsim in Python, and how its processes live together.

The only place that knows topic and service names (:mod:`boat_msgs_py.names`), QoS profiles
(:mod:`boat_msgs_py.qos`) and how core objects become messages (:mod:`boat_msgs_py.convert`).
Shared by both layers' processes: :mod:`boat_msgs_py.process` (children that die with their
parent, signals, the simulation-time file the dynamics node writes and the surface server
reads).
"""

__all__: list[str] = []
