"""Local search over gap-mode sets: minimise J = max(product fit error on the 40 grid points,
the memory's worst diagonal error against the 0.05 rad/s solve (B and A)), ties broken by the
narrow peaks left in smooth_part. Moves: drop one, add one, swap one (<= 26 modes).
With --test the objective is the test's: max(error, B and A errors outside omega0 +- 3 widths).
usage: search_sets.py START_SET (comma-separated) [--test]"""
import sys
sys.dont_write_bytecode = True

from compare_sets import metrics
from select_modes import MODES, POOL

CACHE = {}


OBJECTIVE = "fine"  # or "test": max(error, outside-band B and A errors), the test's metrics


def J(specs):
    key = frozenset(specs)
    if key not in CACHE:
        e, b, a, fb, fa, n, st = metrics(sorted(specs))
        top = max(e, fb, fa) if OBJECTIVE == "fine" else max(e, b, a)
        CACHE[key] = (top, n, e, fb, fa)
    return CACHE[key]


def main(start):
    cur = start
    best = J(cur)
    print(f"start {len(cur)}: J {best[0]:.4f} (error {best[2]:.4f}, fine {best[3]:.3f}/{best[4]:.3f},"
          f" smooth peaks {best[1]})", flush=True)
    while True:
        moves = [[c for c in cur if c != s] for s in cur]
        moves += [cur + [s] for s in POOL if s not in cur and len(cur) < 26]
        improved = False
        for m in moves:
            v = J(m)
            if (v[0], v[1]) < (best[0] - 1e-4, 99):
                cur, best, improved = m, v, True
                print(f"  -> {len(cur)}: J {v[0]:.4f} (error {v[2]:.4f}, fine {v[3]:.3f}/{v[4]:.3f}, "
                      f"smooth peaks {v[1]}): {','.join(sorted(cur, key=lambda s: MODES[s].omega0))}",
                      flush=True)
                break
        if not improved:
            # swaps
            for out in cur:
                for inn in POOL:
                    if inn in cur:
                        continue
                    m = [c for c in cur if c != out] + [inn]
                    v = J(m)
                    if v[0] < best[0] - 1e-4:
                        cur, best, improved = m, v, True
                        print(f"  swap {out}->{inn}: J {v[0]:.4f} (error {v[2]:.4f}, fine "
                              f"{v[3]:.3f}/{v[4]:.3f}, smooth peaks {v[1]})", flush=True)
                        break
                if improved:
                    break
        if not improved:
            break
    print("final:", ",".join(sorted(cur, key=lambda s: MODES[s].omega0)), f"J {best[0]:.4f}")


if __name__ == "__main__":
    if "--test" in sys.argv:
        OBJECTIVE = "test"
        sys.argv.remove("--test")
    main(sys.argv[1].split(","))
