"""Input steps under a driveline master: how far Fz_joint strays from a converged reference in
the 20 communication steps after a step of +-1 % or +-10 % in omega, theta or torque
(harness/input_transients.py says how the reference is made).  Prints a markdown table.

    python benchmarks/transients.py [--quick] [--no-resolved] [--md FILE] [--realizations K]

--realizations K: then the needle-resolved row's +-10 % steps again on K other realizations of
the row (its settling whirl nudged, as another CPU's rounding would; about 35 s each): the
range of each cell's 1 ms mean and single samples over them.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from harness.input_transients import (DT, INPUTS, LAUNCH_ROW, LAUNCH_THETA, LAUNCH_TORQUE,
                                MEAN_SAMPLES, RESOLVED_CYCLE_ROW, RESOLVED_LAUNCH,
                                RESOLVED_ROWS, RESOLVED_ONE_PASS, SIZES, case, checked_case,
                                cycle_case, deviation, settle, step_runs)


def table_row(label, params, nr, f, base, **kw):
    """One row of the table: (label, rollers, whirl [Hz], order 3 [N], how far the reference
    moved from h/10 to h/20 (None against a twin), the no-step floor, each step's deviation
    [% of order 3]); kw goes to checked_case or, with perturb, to case (the scene's theta
    and torque, and how the row reads: mean, perturb)."""
    cells = [("omega", 1.0)] + [(name, fac) for name in INPUTS for fac in SIZES]
    if kw.get("perturb"):
        devs = [case(params, nr, f, name, fac, base, **kw) for name, fac in cells]
        moves = None
    else:
        got = [checked_case(params, nr, f, name, fac, base, **kw) for name, fac in cells]
        devs, moves = [d for d, _ in got], max(mv for _, mv in got)
    print(f"{label}, {nr} roller(s), {f} Hz: worst {max(devs[1:]):.2f} %, reference moved "
          f"{moves}", file=sys.stderr)
    return label, nr, f, base[1], moves, devs[0], devs[1:]


def cycle_row(label, params, nr, f, base):
    """table_row's tuple for order 3 over the whirl cycle after the step (cycle_case): the
    no-step cell and the theta steps, the other cells None (not measured: each costs about
    50 s with the needle-resolved row)."""
    cells = [("omega", 1.0)] + [(name, fac) for name in INPUTS for fac in SIZES]
    got = [cycle_case(params, nr, f, name, fac, base) if name == "theta" or fac == 1.0
           else None for name, fac in cells]
    devs = [None if g is None else g[0] for g in got]
    moves = max(g[1] for g in got if g is not None)
    print(f"{label}: worst {max(d for d in devs if d is not None):.2f} %, reference moved "
          f"{moves}", file=sys.stderr)
    return label, nr, f, base[1], moves, devs[0], devs[1:]


# the settling whirl's nudges of the other realizations (--realizations)
NUDGES = (1e-11, 1e-10, 3e-10, 1e-9, 3e-9, 3e-12, 3e-11, 1e-8, 3e-8, 1e-7, 3e-7, 1e-12)


def realizations(k):
    """The needle-resolved row's +-10 % steps on k realizations (NUDGES): a markdown table of
    each cell's range over them, the 1 ms mean and single samples [% of order 3], both against
    the reference of h/20 (one run of each serves both)."""
    params, nr, f = {"bearing": 2}, 1, 10
    cells = [(name, fac) for name in INPUTS for fac in SIZES if abs(fac - 1.0) > 0.05]
    mean, single = [], []
    for nudge in NUDGES[:k]:
        base = settle(params, nr, f, nudge=nudge)
        runs = [step_runs(params, nr, f, n, s, base, refines=(20,)) for n, s in cells]
        mean.append([deviation(y, refs[20], base[1], MEAN_SAMPLES) for y, refs in runs])
        single.append([deviation(y, refs[20], base[1]) for y, refs in runs])
        print(f"realization {nudge:g}: 1 ms mean worst {max(mean[-1]):.2f} %", file=sys.stderr)
    lines = ["| step | 1 ms mean [% of order 3] | single samples [% of order 3] |",
             "|---|---|---|"]
    for i, (n, s) in enumerate(cells):
        lo, hi = min(r[i] for r in mean), max(r[i] for r in mean)
        slo, shi = min(r[i] for r in single), max(r[i] for r in single)
        lines.append(f"| {n} {100 * (s - 1):+.0f} % | {lo:.2f}-{hi:.2f} | {slo:.2f}-{shi:.2f} |")
    above = sum(v > 1.0 for r in mean for v in r)
    lines.append(f"\n1 ms mean above 1 % in {above} of {len(mean) * len(cells)} "
                 "(realization, step) pairs")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="one roller count, ideal bearing")
    ap.add_argument("--md", help="write the table as markdown to this file")
    ap.add_argument("--no-resolved", action="store_true",
                    help="leave out the needle-resolved bearing's rows (most of the run)")
    ap.add_argument("--realizations", type=int, default=0, metavar="K",
                    help=f"then the needle row's +-10 %% steps on K (at most {len(NUDGES)}) "
                         "other realizations")
    a = ap.parse_args(argv)
    if not 0 <= a.realizations <= len(NUDGES):
        ap.error(f"--realizations must be in [0, {len(NUDGES)}], not {a.realizations}")
    bearings = [("ideal", {})] + ([] if a.quick else [("lumped", {"bearing": 1})])
    rollers = (3,) if a.quick else (1, 3)
    rows = []
    t0 = time.time()
    for bname, params in bearings:
        for nr in rollers:
            for f in (2, 10, 40):
                rows.append(table_row(bname, params, nr, f, settle(params, nr, f)))
    if not a.quick:
        # the whole joint at a launch's load and angle (45 kN per roller), where the roller's
        # slide rings at 8.6 kHz (docs/integrators.md)
        kw = {"theta": LAUNCH_THETA, "torque": LAUNCH_TORQUE}
        for f in (2, 10, 40):
            rows.append(table_row(LAUNCH_ROW, {}, 3, f, settle({}, 3, f, **kw), **kw))
    if not (a.quick or a.no_resolved):
        # the needle-resolved bearing (46 needles x 7 spheres, BDF2), slow to settle: one
        # roller at 10 Hz.  Three rows: single samples against the reference; single samples
        # against the same model from a state moved by 1e-15 (how far rounding alone moves
        # them: the row is chaotic on this scale); the 1 ms running mean against a reference
        # of h/20 (docs/benchmarks.md)
        params, nr, f = {"bearing": 2}, 1, 10
        base = settle(params, nr, f)
        for label, kw in ((RESOLVED_ROWS[0], {}), (RESOLVED_ROWS[1], {"perturb": 1e-15}),
                          (RESOLVED_ROWS[2], {"mean": MEAN_SAMPLES})):
            rows.append(table_row(label, params, nr, f, base, **kw))
        # order 3 over the cycle after each theta step, whose single samples have no
        # converged reference (docs/integrators.md#needle-resolved-bearing)
        rows.append(cycle_row(RESOLVED_CYCLE_ROW, params, nr, f, base))
        # the same row at a launch's torque, single samples (docs/benchmarks.md)
        for label, theta in RESOLVED_LAUNCH:
            kw = {"theta": theta, "torque": LAUNCH_TORQUE}
            rows.append(table_row(label, params, nr, f, settle(params, nr, f, **kw), **kw))
        # with one Newton pass a substep, the default before the second pass
        # (docs/integrators.md#needle-resolved-bearing)
        bases = {}
        for label, p, theta, torque, extra in RESOLVED_ONE_PASS:
            kw = {"theta": theta, "torque": torque}
            key = (tuple(sorted(p.items())), theta, torque)
            if key not in bases:
                bases[key] = settle(p, nr, f, **kw)
            rows.append(table_row(label, p, nr, f, bases[key], **kw, **extra))
    head = ("| bearing | rollers | whirl [Hz] | order 3 [N] | reference h/20 from h/10 | "
            "no step | " + " | ".join(f"{n} {100 * (s - 1):+.0f} %" for n in INPUTS for s in SIZES)
            + " |")
    lines = [head, "|" + "---|" * (6 + len(INPUTS) * len(SIZES))]
    for b, nr, f, a3, moves, fl, devs in rows:
        mv = "-" if moves is None else f"{moves:.2f}"
        lines.append(f"| {b} | {nr} | {f} | {a3:.1f} | {mv} | {fl:.2f} | "
                     + " | ".join("-" if d is None else f"{d:.2f}" for d in devs) + " |")
    table = "\n".join(lines)
    print(table)
    print(f"(largest deviation of Fz_joint in the 20 steps of {DT:g} s after the step, % of "
          f"order 3; {time.time() - t0:.0f} s)")
    if a.md:
        Path(a.md).write_text(table + "\n")
    if a.realizations:
        print(f"\nthe needle-resolved row on {a.realizations} other realizations:")
        print(realizations(a.realizations))


if __name__ == "__main__":
    main()
