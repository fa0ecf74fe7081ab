"""Markdown tables from results_*.jsonl (run_points.py)."""
import json
import sys

TOL, ABS = 0.20, 0.08


def mark(sim, meas):
    d = sim - meas
    ok = abs(d) <= TOL * abs(meas) or abs(d) <= ABS
    return f"{100 * d / meas:+.0f} %", ("yes" if ok else "**no**")


def main(path):
    recs = sorted((json.loads(ln) for ln in open(path) if ln.strip()),
                  key=lambda r: (r["Fn"], r["lam"]))
    print("| Fn | lambda/L | omega_e rad/s | measured x3/A | boatsim | diff | within 20 % or 0.08 |"
          " potential flow | PF diff | CPU s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in recs:
        d, ok = mark(r["heave_sim"], r["heave_meas"])
        dp, _ = mark(r["heave_pf"], r["heave_meas"])
        print(f"| {r['Fn']:.2f} | {r['lam']:.3f} | {r['encounter']:.2f} | {r['heave_meas']:.3f} | "
              f"{r['heave_sim']:.3f} | {d} | {ok} | {r['heave_pf']:.3f} | {dp} | {r['cpu']:.0f} |")
    print()
    print("| Fn | lambda/L | measured x5/(kA) | boatsim | diff | within 20 % or 0.08 |"
          " potential flow | PF diff |")
    print("|---|---|---|---|---|---|---|---|")
    for r in recs:
        if r["pitch_meas"] is None:
            continue
        d, ok = mark(r["pitch_sim"], r["pitch_meas"])
        dp, _ = mark(r["pitch_pf"], r["pitch_meas"])
        print(f"| {r['Fn']:.2f} | {r['lam']:.3f} | {r['pitch_meas']:.3f} | {r['pitch_sim']:.3f} | "
              f"{d} | {ok} | {r['pitch_pf']:.3f} | {dp} |")
    n = len(recs)
    cpu = [r["cpu"] for r in recs]
    print(f"\n{n} points, CPU per point {min(cpu):.0f}-{max(cpu):.0f} s, mean "
          f"{sum(cpu) / n:.0f} s, total {sum(cpu) / 60:.1f} min")


if __name__ == "__main__":
    main(sys.argv[1])
