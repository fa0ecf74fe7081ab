"""Builders for boats used by the physics tests."""

import numpy as np
import pytest

from boat_dynamics.physics.body.hull import BoxHull, box_mesh
from boat_dynamics.physics.core.boat import BoatParams
from boat_dynamics.physics.force_models.buoyancy import SamplePointBuoyancy
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy
from boat_dynamics.physics.force_models.propulsion import Propulsion
from boat_dynamics.physics.force_models.rudder import Rudder


def make_boat(length=4.0, beam=2.0, height=1.0, density_ratio=0.5, com=(0.0, 0.0, 0.0),
              linear=(0, 0, 0, 0, 0, 0), quadratic=(0, 0, 0, 0, 0, 0), grid=(5, 3),
              max_thrust=2000.0, thrust_at=None, rho=1025.0, g=9.81, model="sample_points",
              subdivisions=1):
    hull = BoxHull(length, beam, height)
    mass = density_ratio * rho * hull.volume
    buoyancy = (MeshBuoyancy(box_mesh(hull, subdivisions)) if model == "mesh" else
                SamplePointBuoyancy(hull.bottom_grid(*grid), hull.volume, height))
    return BoatParams(
        hull=hull,
        mass=mass,
        center_of_mass=np.array(com, dtype=float),
        inertia=hull.solid_inertia(mass),
        buoyancy=buoyancy,
        damping_linear=np.array(linear, dtype=float),
        damping_quadratic=np.array(quadratic, dtype=float),
        added_mass=np.zeros(6),
        propulsion=Propulsion(max_thrust, np.array(thrust_at if thrust_at is not None
                                                   else com, dtype=float),
                              np.array([1.0, 0.0, 0.0])),
        rudder=Rudder("lift", np.radians(35.0), 0.25, 1.0,
                      np.array([-length / 2, 0.0, -height / 2])),
        water_density=rho,
        gravity=g,
    )


@pytest.fixture
def boat_factory():
    return make_boat
