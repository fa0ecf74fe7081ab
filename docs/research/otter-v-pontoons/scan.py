"""Candidate gap modes from the 0.05 rad/s scan: per class, B diagonal local maxima and a
vector fit's lightly damped poles."""
import sys
import numpy as np
import otlib
from boat_dynamics.physics.gap_modes import _relocate

s = otlib.Solve(otlib.SOLVES / "fine05.npz")
for cls in otlib.CLASSES:
    w, Y, _ = otlib.class_data(s, cls, 5.0, 17.5)
    print(f"== {cls}")
    for e, (i, j) in enumerate(otlib.CLASSES[cls][:2] if cls != "Y" and cls != "H" else otlib.CLASSES[cls][:1]):
        B = Y[:, e].real
        pk = [k for k in range(1, len(w) - 1) if B[k] > B[k - 1] and B[k] > B[k + 1]]
        print(f"  B{i}{j} maxima:", ", ".join(f"{w[k]:.2f}({B[k]:.0f})" for k in pk))
    # vector fit of the class entries on 5..17.5 with n poles
    sc = np.abs(Y).max(axis=0)
    ss = np.concatenate([1j * w, -1j * w])
    F = np.concatenate([Y, Y.conj()]) / sc
    wr = np.ones_like(F.real)
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    im = np.linspace(5.0, 17.5, n // 2)
    poles = _relocate(ss, F, wr, wr, np.concatenate([-im / 100 + 1j * im, -im / 100 - 1j * im]))
    up = poles[poles.imag > 0]
    up = up[np.argsort(up.imag)]
    lab = []
    for p in up:
        w0 = abs(p); z = -p.real / w0
        if z < 0.05 and 6 < w0 < 17.6:
            lab.append(f"{w0:.3f}/{z:.1e}")
    print("  VF poles (w0/zeta<0.05):", ", ".join(lab))
