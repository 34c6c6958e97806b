"""The analytic FMU's step cost in process, compiled (its C functions' numba copies): a step of
the march (the inputs moved every step, as a driveline master moves them) and a step with the
inputs held (the start's table), with the needle row (the default) and without it
(needle_row = false), on the paper's joint.  Prints a table of medians (docs/model.md's "Cost").

Usage: python -m benchmarks.march_cost [--runs N] [--steps N]
"""
import argparse
import math
import statistics
import time

import numpy as np

from reduced_model import analytic_kernel as K
from reduced_model.scene import defaults, validate
from reduced_model.traverse import params_array

# (label, theta [deg], pressing load per roller [N])
SCENES = (("8 deg, 4.5 kN", 8.0, 4500.0), ("8 deg, 45 kN", 8.0, 45000.0),
          ("3 deg, 45 kN", 3.0, 45000.0))
MOVED = ("theta", "omega", "F_press")   # moved by 1e-3 of their values, a slow sine


def step_cost(ns, row, theta_deg, F, steps, moved=True, warm=500):
    """One run's cost of a step [us]: ``warm`` steps first (the march settles), then ``steps``
    timed; 10 Hz whirl, 0.1 ms steps."""
    sc = validate(dict(defaults("analytic"), needle_row=row, theta=math.radians(theta_deg),
                       omega=20 * math.pi, F_press=F, torque=0.0), "analytic")
    T = params_array(sc)
    IN = np.array([float(sc[n]) for n in K.INPUT_NAMES])
    X, OUT, W = np.zeros(K.X_LEN), np.zeros(K.OUT_LEN), np.zeros(K.W_LEN)
    ns["init"](T, IN, X, OUT, W)
    at = [K.INPUT_NAMES.index(n) for n in MOVED]
    base = IN[at].copy()
    step = ns["step"]
    t0 = 0.0
    for k in range(warm + steps):
        if k == warm:
            t0 = time.perf_counter()
        if moved:
            IN[at] = base * (1.0 + 1e-3 * math.sin(0.01 * k))
        if step(T, IN, X, OUT, W, k * 1e-4, 1e-4) != 1:
            raise RuntimeError(f"the step at {k} was refused or not finite")
    return (time.perf_counter() - t0) / steps * 1e6


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=7, help="timed runs per cell, count (median)")
    ap.add_argument("--steps", type=int, default=4000, help="timed steps per run, count")
    a = ap.parse_args()
    ns = K.compiled_namespace()
    for row in (True, False):                       # compile before the clock
        step_cost(ns, row, 8.0, 4500.0, 10, warm=10)
    print("| scene | march, needle row [us] | march, needle_row = false [us] | ratio | "
          "inputs held, needle row [us] |")
    print("|---|---|---|---|---|")
    for label, th, F in SCENES:
        on, off, held = [], [], []
        for _ in range(a.runs):     # in alternation: the machine's speed drifts
            on.append(step_cost(ns, True, th, F, a.steps))
            off.append(step_cost(ns, False, th, F, a.steps))
            held.append(step_cost(ns, True, th, F, a.steps, moved=False))
        m_on, m_off = statistics.median(on), statistics.median(off)
        print(f"| {label} | {m_on:.2f} | {m_off:.2f} | {m_on / m_off:.2f} | "
              f"{statistics.median(held):.2f} |", flush=True)


if __name__ == "__main__":
    main()
