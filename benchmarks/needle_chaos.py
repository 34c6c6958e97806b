"""How far the needle-resolved row's Fz_joint can be predicted: one roller settled at 10 Hz
(300 N m, 8 deg), the 20 communication steps (1e-4 s) after the same state, with no input step
and after omega +1 %.  Prints markdown tables:

- references of ever finer substep (h/10 ... h/160, h the default's) against the finest, as
  single samples and as their 1 ms running mean (harness.input_transients.MEAN_SAMPLES);
- the same model from a state moved by 1e-15 or 1e-12 (the roller's spin): how far rounding
  alone moves it, and the e-folding time of that difference in the state;
- with one Newton pass a substep (newton_passes = 1, harness.input_transients.ONE_PASS, the default
  before the second pass), settled with it: how far rounding moves its single samples.

    python benchmarks/needle_chaos.py [--md FILE]       (about 1 min)
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

from harness import input_transients as T
from reduced_model.scene import BY_NAME

REFINES = (10, 20, 40, 80, 160)
MIN_SUBSTEP = BY_NAME["max_substep"].auto_or_min   # max_substep's smallest value
CELLS = (("no step", 1.0), ("omega +1 %", 1.01))   # (label, omega's factor)
TWINS = (1e-15, 1e-12)
E_FOLD_STEPS = 30   # communication steps of e_folding's runs


def row_labels():
    """The first column of the table main() prints (harness/docgen.py checks it)."""
    out = []
    for label, _ in CELLS:
        out += [f"{label}: reference h/{k}" for k in REFINES[:-1]] + [f"{label}: default"]
        out += [f"{label}: default from the state moved by {eps:g}" for eps in TWINS]
        out += [f"{label}: one pass, settled with it, from its state moved by 1e-15"]
    return out


def fine_run(state, inputs, substep, steps=20):
    """Fz_joint at the steps of DT after ``state`` with BDF2 substeps of about ``substep`` [s]
    (below max_substep's range: one substep a communication step of that size)."""
    if substep >= MIN_SUBSTEP:
        return T.reference({"bearing": 2}, 1, state, inputs, steps, substep, 1)
    return T.reference({"bearing": 2}, 1, state, inputs, steps, MIN_SUBSTEP, 1,
                       sub=int(round(T.DT / substep)))


def e_folding(model, state, inputs, eps, a3, steps=E_FOLD_STEPS, sub=10):
    """The e-folding time [s] of the difference between the runs from ``state`` and from its
    twin (eps), the largest over the state's entries scaled by their largest magnitude, fitted
    where it lies between 1e3 eps and 1e-3; and when the twins' Fz_joint first part by 1 % of
    order 3 (a3 [N]) [s]."""
    runs = []
    for st in (state, T.twin(state, eps)):
        model.set_state(st)
        ys, fz = [], []
        for _ in range(steps * sub):
            o = model.step(T.DT / sub, inputs["theta"], inputs["omega"], 0.0, inputs["torque"])
            ys.append(model.rollers[0].Y.copy())
            fz.append(o["Fz_joint"])
        runs.append((np.array(ys), np.array(fz)))
    model.set_state(state)
    (ya, fa), (yb, fb) = runs
    sep = np.abs((ya - yb) / (np.abs(ya).max(axis=0) + 1e-300)).max(axis=1)
    t = T.DT / sub * np.arange(1, len(sep) + 1)
    fit = (sep > 1e3 * eps) & (sep < 1e-3)
    rate = np.polyfit(t[fit], np.log(sep[fit]), 1)[0] if fit.sum() > 3 else float("nan")
    part = np.abs(fa - fb) > 0.01 * a3
    return 1.0 / rate, (t[np.argmax(part)] if part.any() else float("nan"))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--md", help="write the tables as markdown to this file")
    a = ap.parse_args(argv)
    t0 = time.time()
    m, a3 = T.settle({"bearing": 2}, 1, 10)
    st = m.get_state()
    m2, _ = T.settle(T.ONE_PASS, 1, 10)
    st2 = m2.get_state()
    w = 2 * math.pi * 10
    h = m.rollers[0].substep(T.THETA, w, m.pressing(0.0, T.TORQUE), m.rollers[0].v_st(T.THETA, w))
    lines = ["| run | against | single samples [% of order 3] | 1 ms mean [% of order 3] |",
             "|---|---|---|---|"]

    def pc(y, ref, mean):
        return 100 * np.abs(T.running_mean(y, mean) - T.running_mean(ref, mean)).max() / a3

    for label, factor in CELLS:
        inputs = {"theta": T.THETA, "omega": w * factor, "torque": T.TORQUE}
        refs = {k: fine_run(st, inputs, h / k) for k in REFINES}
        finest = refs[REFINES[-1]]
        for k in REFINES[:-1]:
            lines.append(f"| {label}: reference h/{k} | h/{REFINES[-1]} | "
                         f"{pc(refs[k], finest, 1):.2f} | {pc(refs[k], finest, T.MEAN_SAMPLES):.2f} |")
        m.set_state(st)
        y = T.response(m, inputs, 20)
        m.set_state(st)
        lines.append(f"| {label}: default | h/{REFINES[-1]} | {pc(y, finest, 1):.2f} | "
                     f"{pc(y, finest, T.MEAN_SAMPLES):.2f} |")
        for eps in TWINS:
            m.set_state(T.twin(st, eps))
            yt = T.response(m, inputs, 20)
            m.set_state(st)
            lines.append(f"| {label}: default from the state moved by {eps:g} | default | "
                         f"{pc(yt, y, 1):.2f} | {pc(yt, y, T.MEAN_SAMPLES):.2f} |")
        m2.set_state(st2)
        y2 = T.response(m2, inputs, 20)
        m2.set_state(T.twin(st2, 1e-15))
        y2t = T.response(m2, inputs, 20)
        lines.append(f"| {label}: one pass, settled with it, from its state moved by "
                     f"1e-15 | one pass | {pc(y2t, y2, 1):.2f} | "
                     f"{pc(y2t, y2, T.MEAN_SAMPLES):.2f} |")
        print(f"{label}: done ({time.time() - t0:.0f} s)", file=sys.stderr)
    inputs = {"theta": T.THETA, "omega": w, "torque": T.TORQUE}
    fold, part = e_folding(m, st, inputs, 1e-12, a3)
    table = "\n".join(lines)
    parted = (f"after {1e3 * part:.2f} ms" if part == part
              else f"at no sample of the {1e3 * E_FOLD_STEPS * T.DT:.0f} ms run")
    tail = (f"\nThe difference a 1e-12 change of the spin makes to the state grows e-fold every "
            f"{1e6 * fold:.0f} us (default step; the largest entry, scaled); the twins' Fz_joint "
            f"part by 1 % of order 3 {parted}.")
    print(table + "\n" + tail)
    print(f"(order 3: {a3:.2f} N; {time.time() - t0:.0f} s)")
    if a.md:
        Path(a.md).write_text(table + "\n" + tail + "\n")


if __name__ == "__main__":
    main()
