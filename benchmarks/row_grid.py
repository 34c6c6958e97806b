"""The fast models against the full one over the driveline envelope (issue 67 point 5): the
ideal and lumped bearings of the contact model and the analytic model, each against the
needle-resolved row, one roller, over harness/row_grid.py's quasi-random grid of scenes.
Prints the Markdown table of docs/validation.md ("The fast models against the full one over
the envelope"); "off" is the complex difference over the resolved row's amplitude.

Usage: python -m benchmarks.row_grid [--scenes N] [--first K]   (one resolved run is 7 s to
a minute here: about 5 minutes for twelve scenes)
"""
import argparse
import math
import time

from harness.row_grid import analytic_orders, contact_orders, off, scene


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", type=int, default=12)
    ap.add_argument("--first", type=int, default=1, help="the Halton index of the first scene")
    args = ap.parse_args()
    print("| # | joint | theta [deg] | load a roller [kN] | whirl [Hz] | resolved: order 1, order 3 "
          "[N] | ideal: order 1, 3 off | lumped: order 1, 3 off | analytic: order 1, 3 off | "
          "wall, resolved [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for i in range(args.first, args.first + args.scenes):
        path, theta, F, omega = scene(i)
        t0 = time.perf_counter()
        ref = contact_orders(path, theta, F, omega, 2)
        wall = time.perf_counter() - t0
        cells = [f"{off(o, ref, 1):.1f} %, {off(o, ref, 3):.1f} %"
                 for o in (contact_orders(path, theta, F, omega, 0),
                           contact_orders(path, theta, F, omega, 1),
                           analytic_orders(path, theta, F, omega))]
        print(f"| {i} | {path.stem} | {math.degrees(theta):.1f} | {F / 1e3:+.2f} | "
              f"{omega / 2 / math.pi:.1f} | {ref[1][0]:.2f}, {ref[3][0]:.2f} | "
              + " | ".join(cells) + f" | {wall:.0f} |", flush=True)


if __name__ == "__main__":
    main()
