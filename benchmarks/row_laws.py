"""Which of the needle row's laws carries a fast model's gap to the resolved row: scenes of the
envelope grid (harness/envelope_grid.py) run with every law on, then with one law switched off
in the resolved row, the lumped row and the analytic model at once; order 3 of one roller's Fz,
each fast model against the resolved row and the analytic model against the lumped row
(complex differences).  Prints a table (issue 67's light loads at large angles).

Usage: python -m benchmarks.row_laws [--scenes 3 15]
"""
import argparse
import math

from harness.envelope_grid import analytic_orders, contact_orders, off, scene

# (label, the parameters set in all three models)
LAWS = (("every law on", {}), ("spin moment off", {"spin_moment": False}),
        ("rolling resistance off", {"rolling_resistance": False}),
        ("the needles' sliding friction off", {"friction_needle": False}))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, nargs="+", default=[3, 15],
                    help="envelope grid scenes (from 1)")
    a = ap.parse_args()
    print("| scene | laws | resolved: order 3 [N] | lumped off resolved | analytic off resolved "
          "| analytic off lumped |")
    print("|---|---|---|---|---|---|")
    for i in a.scenes:
        path, th, F, om = scene(i)
        where = (f"{i}: {path.stem}, {math.degrees(th):.1f} deg, {F / 1e3:+.2f} kN, "
                 f"{om / 2 / math.pi:.1f} Hz")
        for label, over in LAWS:
            res = contact_orders(path, th, F, om, 2, **over)
            lum = contact_orders(path, th, F, om, 1, **over)
            ana = analytic_orders(path, th, F, om, **over)
            print(f"| {where} | {label} | {res[3][0]:.3f} | {off(lum, res, 3):.2f} % | "
                  f"{off(ana, res, 3):.2f} % | {off(ana, lum, 3):.2f} % |", flush=True)


if __name__ == "__main__":
    main()
