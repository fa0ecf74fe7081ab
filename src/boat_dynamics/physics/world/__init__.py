"""The world the boats move in besides the sea: fixed obstacles (docks, piers, shore, pilings)."""

from boat_dynamics.physics.world.obstacles import (
    ContactParams,
    Cylinder,
    Obstacle,
    Prism,
    World,
    penetration,
)

__all__ = ["ContactParams", "Cylinder", "Obstacle", "Prism", "World", "penetration"]
