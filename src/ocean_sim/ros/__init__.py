"""The ROS 2 side of the ocean: the ocean node and a client of its surface service."""

__all__: list[str] = []
