"""The rigid hull: geometry, kinematics, wrenches, and its clip at the water surface."""
