"""The fast models against the full one over the driveline envelope (issue 67 point 5, a
first grid; research, not yet the slow tier's test): the ideal and lumped bearings of the
contact model and the analytic model, each against the needle-resolved row, one roller.

Scenes: a Halton sequence over the joint angle 2-25 deg, the load per roller 0.3-45 kN
(logarithmic), the whirl 2-30 Hz (logarithmic), the joints of joints/ and drive or coast
(the pressing load's sign).  Each model runs three whirl cycles from the start at a 0.1 ms
communication step, in process; orders 1 and 3 of Fz over the last whole cycle; "off" is the
complex difference over the resolved row's amplitude.

Usage: python -m benchmarks.row_grid [--scenes N] [--first K]   (one resolved run is 15 s to
a minute here: about 10 minutes for twelve scenes)
"""
import argparse
import math
import time
from pathlib import Path

import numpy as np

from benchmarks.needle_mechanism import phasor, run
from reduced_model.analytic_model import AnalyticModel
from reduced_model.joint import for_model, load_joint
from reduced_model.kernel import INPUT_NAMES
from reduced_model.orders import last_cycle_orders
from reduced_model.scene import defaults

JOINTS = sorted(Path(__file__).resolve().parents[1].glob("joints/*.toml"))
CYCLES = 3
DT = 1e-4


def halton(i, base):
    """The i-th (from 1) element of the van der Corput sequence in base."""
    f, r = 1.0, 0.0
    while i > 0:
        f /= base
        r += f * (i % base)
        i //= base
    return r


def scene(i):
    """Scene i (from 1): (joint path, theta [rad], pressing load per roller [N], omega [rad/s])."""
    theta = math.radians(2.0 + 23.0 * halton(i, 2))
    F = 300.0 * (45000.0 / 300.0) ** halton(i, 3)
    f = 2.0 * (30.0 / 2.0) ** halton(i, 5)
    joint = JOINTS[int(halton(i, 7) * len(JOINTS))]
    sign = 1.0 if halton(i, 11) < 0.5 else -1.0     # drive or coast
    return joint, theta, sign * F, 2.0 * math.pi * f


def analytic_orders(joint, theta, F, omega):
    """Orders 1 and 3 of Fz [N, deg] of the analytic model (one roller) over the last cycle."""
    values = dict(defaults("analytic"), **for_model(joint, "analytic"), theta=theta, omega=omega,
                  F_press=F, n_rollers=1)
    m = AnalyticModel(values)
    inputs = [values[n] for n in INPUT_NAMES]
    t, fz, x = [], [], []
    for k in range(int(round(CYCLES * 2 * math.pi / abs(omega) / DT))):
        m.step(DT, k * DT, inputs)
        o = m.outputs()
        t.append((k + 1) * DT)
        fz.append(o["Fz"])
        x.append(o["whirl_angle"])
    return last_cycle_orders(np.array(t), np.array(fz), np.array(x), (1, 3))


def contact_orders(joint, theta, F, omega, bearing):
    over = dict(for_model(joint, "contact"), bearing=bearing)
    rows = run(over, F, theta, omega, cycles=CYCLES, dt=DT)
    return last_cycle_orders(rows[:, 0], rows[:, 2], rows[:, 1], (1, 3))


def off(o, ref, k):
    return 100.0 * abs(phasor(o[k]) - phasor(ref[k])) / ref[k][0]


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
        joint = load_joint(path)
        t0 = time.perf_counter()
        ref = contact_orders(joint, theta, F, omega, 2)
        wall = time.perf_counter() - t0
        cells = []
        for o in (contact_orders(joint, theta, F, omega, 0),
                  contact_orders(joint, theta, F, omega, 1),
                  analytic_orders(joint, theta, F, omega)):
            cells.append(f"{off(o, ref, 1):.1f} %, {off(o, ref, 3):.1f} %")
        print(f"| {i} | {path.stem} | {math.degrees(theta):.1f} | {F / 1e3:+.2f} | "
              f"{omega / 2 / math.pi:.1f} | {ref[1][0]:.2f}, {ref[3][0]:.2f} | "
              + " | ".join(cells) + f" | {wall:.0f} |", flush=True)


if __name__ == "__main__":
    main()
