"""Load otter_v.yaml with boatsim; print its equilibrium, key, hydro source and stability."""
import sys
import numpy as np
from boat_dynamics.physics.scenario import load_scenario
from boat_dynamics.physics.model import coefficients_key
from boat_dynamics.physics.tuning import equilibrium_height

path = sys.argv[1] if len(sys.argv) > 1 else "/tmp/otter2/otter_v.yaml"
sc = load_scenario(path)
b = sc.boats[0]
p = b.params
z = equilibrium_height(p)
print("boat", b.name, "mass", p.mass, "com", p.center_of_mass.tolist())
print("z_eq", round(z, 5), "waterline body z", round(-z, 5), "CoM above waterline",
      round(p.center_of_mass[2] + z, 5))
print("key", coefficients_key(p, sc.sea.depth), "hydro", None if p.hydro is None else p.hydro.source)
print("initial z", b.initial.position.tolist() if hasattr(b, "initial") else None)
