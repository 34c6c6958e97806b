"""Input steps under a driveline master: how far Fz_joint strays from a converged reference in
the 20 communication steps after a step of +-1 % or +-10 % in omega, theta or torque
(harness/transients.py says how the reference is made).  Prints a markdown table.

    python benchmarks/transients.py [--quick] [--no-resolved] [--md FILE]
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from harness.transients import (DT, INPUTS, LAUNCH_ROW, LAUNCH_THETA, LAUNCH_TORQUE,  # noqa: E402
                                MEAN_SAMPLES, RESOLVED_ROWS, SIZES, case, settle)


def floor(params, nr, f, base, **kw):
    """The same deviation with no step at all: how far the default and its reference part
    anyway [% of order 3]."""
    return case(params, nr, f, "omega", 1.0, base, **kw)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="one roller count, ideal bearing")
    ap.add_argument("--md", help="write the table as markdown to this file")
    ap.add_argument("--no-resolved", action="store_true",
                    help="leave out the needle-resolved bearing's rows (about 40 s)")
    a = ap.parse_args(argv)
    bearings = [("ideal", {})] + ([] if a.quick else [("lumped", {"bearing": 1})])
    rollers = (3,) if a.quick else (1, 3)
    rows = []
    t0 = time.time()
    for bname, params in bearings:
        for nr in rollers:
            for f in (2, 10, 40):
                base = settle(params, nr, f)
                devs = [case(params, nr, f, name, fac, base) for name in INPUTS
                        for fac in SIZES]
                rows.append((bname, nr, f, base[1], floor(params, nr, f, base), devs))
                print(f"{bname:6s} {nr} roller(s) {f:3d} Hz: worst {max(devs):.2f} %",
                      file=sys.stderr)
    if not a.quick:
        # the whole joint at a launch's load and angle (45 kN per roller), where the roller's
        # slide rings at 8.6 kHz (docs/integrators.md)
        for f in (2, 10, 40):
            kw = {"theta": LAUNCH_THETA, "torque": LAUNCH_TORQUE}
            base = settle({}, 3, f, **kw)
            devs = [case({}, 3, f, name, fac, base, **kw) for name in INPUTS for fac in SIZES]
            rows.append((LAUNCH_ROW, 3, f, base[1], floor({}, 3, f, base, **kw), devs))
            print(f"launch 3 rollers {f:3d} Hz: worst {max(devs):.2f} %", file=sys.stderr)
    if not (a.quick or a.no_resolved):
        # the needle-resolved bearing (46 needles x 7 spheres, BDF2), slow to settle: one
        # roller at 10 Hz.  Three rows: single samples against the reference; single samples
        # against the same model from a state moved by 1e-15 (how far rounding alone moves
        # them: the row is chaotic on this scale); the 1 ms running mean against a reference
        # of h/20 (docs/benchmarks.md)
        params, nr, f = {"bearing": 2}, 1, 10
        base = settle(params, nr, f)
        for label, kw in ((RESOLVED_ROWS[0], {}), (RESOLVED_ROWS[1], {"perturb": 1e-15}),
                          (RESOLVED_ROWS[2], {"mean": MEAN_SAMPLES, "refine": 20})):
            devs = [case(params, nr, f, name, fac, base, **kw) for name in INPUTS
                    for fac in SIZES]
            rows.append((label, nr, f, base[1], floor(params, nr, f, base, **kw), devs))
            print(f"{label} 1 roller 10 Hz: worst {max(devs):.2f} %", file=sys.stderr)
    head = ("| bearing | rollers | whirl [Hz] | order 3 [N] | no step | "
            + " | ".join(f"{n} {100 * (s - 1):+.0f} %" for n in INPUTS for s in SIZES) + " |")
    lines = [head, "|" + "---|" * (5 + len(INPUTS) * len(SIZES))]
    for b, nr, f, a3, fl, devs in rows:
        lines.append(f"| {b} | {nr} | {f} | {a3:.1f} | {fl:.2f} | "
                     + " | ".join(f"{d:.2f}" for d in devs) + " |")
    table = "\n".join(lines)
    print(table)
    print(f"(largest deviation of Fz_joint in the 20 steps of {DT:g} s after the step, % of "
          f"order 3; {time.time() - t0:.0f} s)")
    if a.md:
        Path(a.md).write_text(table + "\n")


if __name__ == "__main__":
    main()
