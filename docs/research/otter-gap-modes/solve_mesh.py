"""Like solve_windows.py, but any omegas (also above 16.97) on the FILE's mesh: the panels are
planned for the file's omega_max (16.9706 rad/s) and solved at the requested frequencies.
usage: solve_mesh.py TAG wmin wmax step [...]  -> /tmp/cat2/solves/TAG.npz"""
import sys, time, numpy as np
from boat_dynamics.tools import bem
d = np.load('/tmp/cat/otter_inputs.npz')
z_eq = float(d['z_eq']); WMAX = 16.970562748477143
args = sys.argv[1:]
plan, mesh, _, directions = bem.plan_hull(d['vertices'], d['faces'], draft_offset=-z_eq,
                                          gravity=float(d['g']), omegas=np.array([1.0, WMAX]),
                                          lid=True, panel_size=0.05)
cog = d['com'] - np.array([0.0, 0.0, -z_eq])
print('panels', plan.panels, plan.lid_panels, 'z_lid', mesh['z_lid'], flush=True)
for i in range(0, len(args), 4):
    tag, wmin, wmax, step = args[i], float(args[i+1]), float(args[i+2]), float(args[i+3])
    n = int(round((wmax - wmin) / step)) + 1
    omegas = np.linspace(wmin, wmax, n)
    t0 = time.time()
    out = bem._coefficients(mesh, cog, float(d['mass']), d['M'], omegas, directions,
                            dict(rho=float(d['rho']), g=float(d['g']), water_depth=float(d['depth'])))
    out['center_of_mass'] = d['com']
    np.savez_compressed(f'/tmp/cat2/solves/{tag}.npz', **{k: np.asarray(v) for k, v in out.items()})
    print(tag, n, 'points', f'{time.time()-t0:.1f} s', flush=True)
