"""Cost per step under a master whose communication step varies every step (a variable-step or
event-driven master), against the same master at a fixed step, with the compiled steps on and
off (TRIPOD_FAST=0: every step through Python).

Three rollers at 300 N m, theta, omega and torque moved by 1e-3 every step; steps drawn from
20-200 us (the same draw each run) or fixed at 100 us; 2000 doStep + getReal(Fz) a run, medians
of N runs after a warm-up, in one fresh process per row (harness.bench.time_runs).
Prints a Markdown table.  Usage: python benchmarks/varying_step.py [--runs N]
"""
import argparse
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from harness.bench import MASTER_INPUTS, time_runs  # noqa: E402
from harness.fmus import ensure_fmu  # noqa: E402

SV = {"n_rollers": 3, "torque": 300.0}
DT, N = 1e-4, 2000


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5, help="runs per row (median)")
    a = ap.parse_args(argv)
    print("| FMU (3 rollers, 300 N m, master moving theta, omega, torque) | communication step "
          "| us per step, compiled steps | through Python (TRIPOD_FAST=0) |")
    print("|---|---|---|---|")
    for fmu in ("TripodRoller", "TripodRollerAnalytic"):
        path = ensure_fmu(fmu)
        for spread, label in ((False, "fixed 100 us"), (True, "varying, 20-200 us")):
            us = []
            for fast in ("1", "0"):
                os.environ["TRIPOD_FAST"] = fast
                r = time_runs(path, [{"sv": SV, "dt": DT, "stop": N * DT,
                                      "vary": list(MASTER_INPUTS), "spread": spread}],
                              a.runs, read=("Fz",))[0]
                us.append(r["wall"] / r["n"] * 1e6)
            os.environ.pop("TRIPOD_FAST")
            print(f"| {fmu} | {label} | {us[0]:.1f} | {us[1]:.1f} |")


if __name__ == "__main__":
    main()
