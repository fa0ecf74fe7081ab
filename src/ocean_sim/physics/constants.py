"""Physical constants and defaults shared by the ocean and the boats (SI units).

Every other module takes these from here; scenario files may override gravity and water
density per run (``simulation.gravity``, ``simulation.water_density``).
"""

__all__ = ["AIR_DENSITY", "GRAVITY", "TWO_PI", "WATER_DENSITY"]

#: Gravitational acceleration used by default, m/s^2 (DESIGN.md scenario default).
GRAVITY = 9.81

#: Density of sea water used by default, kg/m^3.
WATER_DENSITY = 1025.0

#: 2 * pi, the period of the wave phase, rad.
TWO_PI = 6.283185307179586

#: Density of air at sea level (15 degC, ISA), kg/m^3: the wind loads.
AIR_DENSITY = 1.225
