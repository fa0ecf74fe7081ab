"""boat_msgs_py: the ROS contract of boatsim in Python.

The only place that knows topic and service names (:mod:`boat_msgs_py.names`), QoS profiles
(:mod:`boat_msgs_py.qos`) and how core objects become messages (:mod:`boat_msgs_py.convert`).
"""

__all__: list[str] = []
