"""Cost per step under masters the compiled steps once left to Python: a communication step
that varies every step (a variable-step or event-driven master), the whirl driven by angle
(drive_by_angle: the master sets shaft_angle for each step's end), and an iterative master that
rolls back every step (get the state, a trial step, set the state, the step again: the cost of
the step it keeps), against a fixed step driven by omega: the contact FMU with its compiled
steps on, and off (TRIPOD_FAST=0: every step through Python, which is what those masters got
before); the analytic FMU compiled throughout, against its reference (the same model through
Python, build/reference/).

Three rollers at 300 N m, theta, omega and torque moved by 1e-3 every step (driven by angle:
theta and torque, omega held by the angle); steps drawn from 20-200 us (the same draw each run)
or fixed at 100 us; 2000 doStep + getReal(Fz) a run, medians of N runs after a warm-up, one
fresh process per row and setting (harness.bench.time_runs).
Prints a Markdown table.  Usage: python -m benchmarks.varying_step [--runs N]
"""
import argparse
import os

from harness.bench import MASTER_INPUTS, time_runs
from harness.fmus import ensure_fmu, reference_fmu

SV = {"n_rollers": 3, "torque": 300.0}
DT, N = 1e-4, 2000
# (label, varying step, driven by angle, rollback every step)
MASTERS = (("fixed 100 us, by omega", False, False, False),
           ("varying 20-200 us, by omega", True, False, False),
           ("fixed 100 us, by angle", False, True, False),
           ("varying 20-200 us, by angle", True, True, False),
           ("fixed 100 us, by omega, rollback every step", False, False, True))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5, help="runs per row (median)")
    a = ap.parse_args(argv)
    print("| FMU (3 rollers, 300 N m) | master | us per step, compiled steps "
          "| through Python (contact: TRIPOD_FAST=0; analytic: its reference FMU) |")
    print("|---|---|---|---|")
    for fmu in ("TripodRoller", "TripodRollerAnalytic"):
        analytic = fmu == "TripodRollerAnalytic"
        for label, spread, angle, rollback in MASTERS:
            sv = dict(SV, drive_by_angle=True) if angle else SV
            vary = [k for k in MASTER_INPUTS if not (angle and k == "omega")]
            us = []
            for fast in ("1", "0"):
                os.environ["TRIPOD_FAST"] = fast
                path = reference_fmu(fmu) if analytic and fast == "0" else ensure_fmu(fmu)
                r = time_runs(path, [{"sv": sv, "dt": DT, "stop": N * DT, "vary": vary,
                                      "spread": spread, "rollback": rollback}], a.runs,
                              read=("Fz",))[0]
                us.append(r["wall"] / r["n"] * 1e6)
            os.environ.pop("TRIPOD_FAST")
            print(f"| {fmu} | {label} | {us[0]:.1f} | {us[1]:.1f} |", flush=True)


if __name__ == "__main__":
    main()
