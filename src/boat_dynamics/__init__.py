"""boat_dynamics: rigid-body boats on Gerstner waves (pure numpy core) and the dynamics node.

Core modules (never import rclpy): :mod:`~boat_dynamics.boat`, :mod:`~boat_dynamics.rigid_body`,
:mod:`~boat_dynamics.hull`, one module per force model (:mod:`~boat_dynamics.buoyancy`,
:mod:`~boat_dynamics.damping`, :mod:`~boat_dynamics.propulsion`, :mod:`~boat_dynamics.rudder`),
:mod:`~boat_dynamics.commands`, :mod:`~boat_dynamics.scenario`. ROS adapters:
:mod:`~boat_dynamics.node`, :mod:`~boat_dynamics.simulation`, :mod:`~boat_dynamics.recording`,
:mod:`~boat_dynamics.cli`.
"""

__all__: list[str] = []
