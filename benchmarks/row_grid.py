"""The fast models against the full one over the driveline envelope (issue 67 point 5): the
ideal and lumped bearings of the contact model and the analytic model (with its needle row, and
with the ideal bearing: needle_row = false), each against the needle-resolved row, one
roller, over harness/envelope_grid.py's quasi-random grid of scenes.  Prints the Markdown
table of docs/validation.md ("The fast models against the full one over the envelope"); "off"
is the complex difference over the resolved row's amplitude.

Usage: python -m benchmarks.row_grid [--scenes N] [--first K]   (one resolved run is 7 s to
a minute here: about 5 minutes for twelve scenes)
       python -m benchmarks.row_grid --three-rollers   (the paper's joint at 8 deg, 45 kN a
roller, 10 Hz: the three-roller joint against one roller, lumped and resolved; about 1 min)
"""
import argparse
import math

from harness.envelope_grid import (JOINTS, TABLE_HEAD, joint_orders, markdown_row, off,
                                   scene_orders)


def three_rollers():
    """The three-roller joint (spider prescribed) against one roller, lumped and resolved."""
    path = next(p for p in JOINTS if p.stem == "paper")
    theta, F, omega = math.radians(8.0), 45000.0, 20 * math.pi
    print("| bearing | Fz_joint: order 1, order 3 | roller 1: order 3 | joint's order 3 over "
          "three rollers' | joint's order 3 off the resolved joint's |")
    print("|---|---|---|---|---|")
    runs = {b: joint_orders(path, theta, F, omega, b) for b in (2, 1)}
    fmt = lambda o: f"{o[0]:.3g} N at {o[1]:.1f} deg"   # noqa: E731
    for b, name in ((1, "lumped"), (2, "needle-resolved")):
        j, r = runs[b]["joint"], runs[b]["roller"]
        print(f"| {name} | {fmt(j[1])}, {fmt(j[3])} | {fmt(r[3])} | "
              f"{j[3][0] / (3 * r[3][0]):.5f}, {j[3][1] - r[3][1]:+.2f} deg | "
              f"{off(j, runs[2]['joint'], 3):.1f} % |", flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", type=int, default=12)
    ap.add_argument("--first", type=int, default=1, help="the Halton index of the first scene")
    ap.add_argument("--three-rollers", action="store_true",
                    help="the three-roller joint against one roller instead")
    args = ap.parse_args()
    if args.three_rollers:
        three_rollers()
        return
    print(TABLE_HEAD)
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for i in range(args.first, args.first + args.scenes):
        print(markdown_row(i, scene_orders(i)), flush=True)


if __name__ == "__main__":
    main()
