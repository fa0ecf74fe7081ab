"""The pure physics core of boatsim: numpy only, never rclpy or rosbags (tests/test_layering.py).

- :mod:`~boat_dynamics.physics.model`: the frozen dataclasses of one boat (parameters, state,
  inputs, forces); :mod:`~boat_dynamics.physics.fleet`: many boats stepped as one.
- One module per force model, each a function returning force and torque:
  :mod:`~boat_dynamics.physics.mesh_buoyancy`, :mod:`~boat_dynamics.physics.buoyancy`,
  :mod:`~boat_dynamics.physics.hull_drag`, :mod:`~boat_dynamics.physics.damping`,
  :mod:`~boat_dynamics.physics.propulsion`, :mod:`~boat_dynamics.physics.rudder`,
  :mod:`~boat_dynamics.physics.keel`.
- :mod:`~boat_dynamics.physics.rigid_body` (integration, quaternions),
  :mod:`~boat_dynamics.physics.control` (control modes), :mod:`~boat_dynamics.physics.hull`
  (hull geometry), :mod:`~boat_dynamics.physics.wrench`.
- :mod:`~boat_dynamics.physics.scenario` parses scenario files into frozen specs;
  :mod:`~boat_dynamics.physics.commands` checks commands; :mod:`~boat_dynamics.physics.tuning`
  and :mod:`~boat_dynamics.physics.diagnostics` derive hydrostatic figures.
"""

__all__: list[str] = []
