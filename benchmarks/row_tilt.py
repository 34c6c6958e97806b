"""The roller's tilt on the row about e2 (the groove's axis): the experiment behind
docs/model.md's "The roller rocks on the row".

The groove's friction along the trunnion acts at the roller's rim, r_roller from its centre; its
moment about e2 (k_t2 b2 = -r_roller f_a + lever f_row, lumped row) rocks the roller on the row's
line contacts (k_t2 = k_r l^2 / 12). A rate b2' moves the groove contact along the trunnion by
-r_roller b2' on top of the slide: the friction acts through a compliance in series.

Runs, one roller, 10 Hz, three whirl cycles from the start, orders of Fz over the last one: the
ideal bearing; the lumped row with the needles' friction and rolling resistance off (only the
row's stiffness left), its tilt stiffness (both tilts: P_LT, l^2 / 12) as built and scaled by
10 and 100; the lumped row as built; the needle-resolved row (the reference). Columns: orders 1
and 3, the tilt about e2 (peak over the cycle, its order 2 amplitude), the groove contact's travel
r_roller b2 against the slide u (peaks), with the row's friction off the tilt stiffness fitted
over the last cycle against the lumped row's k_r l^2 / 12 at its mean offset, and again with
the moment of the row's load shifted along the trunnion (the needles ride the trunnion's stroke
and, resolved, float axially within their clearance: harness/row_rocking.py), order 3 off the
resolved row's (complex).
Usage: python -m benchmarks.row_tilt [--loads 4500,45000] [--theta-deg 8,3] (about 1 min a
scene)
"""
import argparse
import math
import time

import numpy as np

from harness.row_rocking import (C_B2, C_FZ, C_SHIFT, C_T, C_U, C_X, FRICTION_OFF, run,
                                  tilt_stiffness)
from reduced_model.orders import last_cycle_orders

RUNS = (   # name, overrides, the tilt stiffness's scale
    ("ideal", {"bearing": 0}, 1.0),
    ("lumped, row friction off", dict(FRICTION_OFF, bearing=1), 1.0),
    ("lumped, row friction off, tilt stiffness x10", dict(FRICTION_OFF, bearing=1), 10.0),
    ("lumped, row friction off, tilt stiffness x100", dict(FRICTION_OFF, bearing=1), 100.0),
    ("lumped", {"bearing": 1}, 1.0),
    ("lumped, tilt stiffness x100", {"bearing": 1}, 100.0),
    ("resolved, row friction off", dict(FRICTION_OFF, bearing=2), 1.0),
    ("resolved", {"bearing": 2}, 1.0),
)


def scene_table(F, theta, omega):
    lines = [f"Load {F / 1e3:g} kN, theta {math.degrees(theta):g} deg, "
             f"{omega / 2 / math.pi:g} Hz (orders of Fz on the groove, last of three cycles):",
             "",
             "| run | order 1 | order 3 | tilt about e2 (peak, order 2) | groove contact's travel "
             "r b2 / slide u (peaks) | tilt stiffness fitted / k_r l^2/12 (residual) "
             "| the same with the row load's shift (its amplitude) | order 3 off resolved "
             "| wall |",
             "|---|---|---|---|---|---|---|---|---|"]
    out = []
    for name, over, scale in RUNS:
        t0 = time.perf_counter()
        a, r, k_lumped, _m = run(over, scale, F, theta, omega)
        wall = time.perf_counter() - t0
        last = a[:, C_X] >= a[-1, C_X] - 2 * math.pi
        fit = shifted = "-"
        if over.get("friction_needle") is False and scale == 1.0:
            k, res = tilt_stiffness(a[last])
            fit = f"{k / k_lumped:.3f} ({100 * res:.0f} %)"
            if over["bearing"] in (1, 2):
                k, res = tilt_stiffness(a[last], shift=True)
                shifted = (f"{k / k_lumped:.3f} ({100 * res:.0f} %; "
                           f"{np.ptp(a[last, C_SHIFT]) * 1e6:.0f} um peak to peak)")
        o = last_cycle_orders(a[:, C_T], a[:, C_FZ], a[:, C_X])
        b2 = last_cycle_orders(a[:, C_T], a[:, C_B2], a[:, C_X], orders=(2,))[2][0]
        z3 = o[3][0] * np.exp(1j * math.radians(o[3][1]))
        peak = np.abs(a[last, C_B2]).max()
        out.append((name, o, peak, b2, r * peak, np.abs(a[last, C_U]).max(), fit, shifted, z3,
                    wall))
    ref = out[-1][8]
    fmt = lambda v: f"{v[0]:.1f} N at {v[1]:.1f} deg"   # noqa: E731
    for name, o, peak, b2, travel, slide, fit, shifted, z3, wall in out:
        lines.append(f"| {name} | {fmt(o[1])} | {fmt(o[3])} | {peak:.2e} rad, {b2:.2e} rad | "
                     f"{travel * 1e6:.1f} um / {slide * 1e6:.1f} um | {fit} | {shifted} | "
                     f"{100 * abs(z3 - ref) / abs(ref):.1f} % | {wall:.0f} s |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], allow_abbrev=False)
    ap.add_argument("--loads", default="4500,45000", help="pressing loads per roller [N]")
    ap.add_argument("--theta-deg", default="8,3", help="joint angles [deg]")
    ap.add_argument("--whirl-hz", type=float, default=10.0, help="whirl rate [Hz]")
    args = ap.parse_args()
    for deg in (float(v) for v in args.theta_deg.split(",")):
        for F in (float(v) for v in args.loads.split(",")):
            print(scene_table(F, math.radians(deg), 2 * math.pi * args.whirl_hz), flush=True)
            print(flush=True)


if __name__ == "__main__":
    main()
