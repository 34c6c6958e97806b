"""The whole joint on the needle-resolved row through a launch (issue 68's launch check).

Three rollers (n_rollers = 3) on the needle-resolved bearing (bearing = 2) at a launch's
3000 N m, 8 deg, 10 Hz for 0.1 s (one whirl cycle, two communication steps more) through the built contact FMU (FMPy, one
process after warm-up, median of --runs), against one roller at the same load per roller: the
cost of the whole joint against one roller's.  Then the same three-roller run with its substep
a quarter of the automatic one (max_substep): orders 1 and 3 of the joint's thrust Fz_joint and
of roller 1's Fz over the cycle, the default's against the quarter step's.

Usage: python -m benchmarks.needle_launch [--runs N]
"""
import argparse
import math

import numpy as np

from harness.bench import time_runs
from harness.fmus import ensure_fmu
from reduced_model.orders import last_cycle_orders
from tripod_model.model import ContactModel

TORQUE = 3000.0                  # N m: the launch
THETA = math.radians(8.0)
OMEGA = 2.0 * math.pi * 10.0
DT = 1e-4
STOP = 0.1 + 2 * DT              # s: one whirl cycle (the orders' last whole one) and a margin


def automatic_substep(sv) -> float:
    """The needle-resolved row's automatic substep [s] at these start values (one
    communication step in process: the substeps it took)."""
    m = ContactModel(sv)
    m.step(DT, THETA, OMEGA, m.p["F_press"], TORQUE)
    return DT / m.substeps


def _orders(r, name):
    y = np.asarray(r["signals"][name])
    t = DT * np.arange(1, len(y) + 1)
    o = last_cycle_orders(t, y, OMEGA * t, (1, 3))
    return {k: a * np.exp(1j * math.radians(p)) for k, (a, p) in o.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3, help="timed runs a case (default 3)")
    args = ap.parse_args()
    base = {"bearing": 2, "theta": THETA, "omega": OMEGA, "torque": TORQUE}
    h = automatic_substep(dict(base, n_rollers=1))
    cases = [{"sv": dict(base, n_rollers=1), "dt": DT, "stop": STOP},
             {"sv": dict(base, n_rollers=3), "dt": DT, "stop": STOP},
             {"sv": dict(base, n_rollers=3, max_substep=h / 4), "dt": DT, "stop": STOP}]
    one, three, fine = time_runs(ensure_fmu("TripodRoller"), cases, runs=args.runs,
                                 read=("Fz", "Fz_joint"))
    print(f"Needle-resolved bearing, the whole joint through a launch: {TORQUE:g} N m, "
          f"{math.degrees(THETA):g} deg, {OMEGA / 2 / math.pi:g} Hz, {STOP:g} s at a {DT:g} s "
          f"communication step (FMPy, median of {args.runs}); automatic substep "
          f"{h * 1e6:.2f} us\n")
    print("| run | wall [s] | against one roller |")
    print("|---|---|---|")
    for name, r in (("one roller", one), ("three rollers", three),
                    ("three rollers, a quarter of the substep", fine)):
        print(f"| {name} | {r['wall']:.2f} [{min(r['walls']):.2f}-{max(r['walls']):.2f}] | "
              f"{r['wall'] / one['wall']:.2f}x |")
    print("\nOrders of the three-roller run (complex difference of the default's from the "
          "quarter substep's):\n")
    print("| signal | order | default | a quarter of the substep | difference |")
    print("|---|---|---|---|---|")
    for name in ("Fz_joint", "Fz"):
        a, b = _orders(three, name), _orders(fine, name)
        for k in (1, 3):
            d = abs(a[k] - b[k]) / abs(b[k])
            print(f"| {name} | {k} | {abs(a[k]):.3f} N at {math.degrees(np.angle(a[k])):.2f} deg"
                  f" | {abs(b[k]):.3f} N at {math.degrees(np.angle(b[k])):.2f} deg | "
                  f"{100 * d:.3f} % |")


if __name__ == "__main__":
    main()
