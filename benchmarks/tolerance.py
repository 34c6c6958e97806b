"""The host's tolerance against the error it buys and what it costs (docs/benchmarks.md, "The
host's tolerance"): the contact FMU through FMPy at 1 ms communication steps (a driveline
master's), the paper's scene, three whirl cycles, `relative_tolerance` handed to
fmi2SetupExperiment; orders 1 and 3 of Fz over the last cycle against a 1 us substep at the
same communication steps; the substeps roller 1 took (the FMU's log, one run in a fresh
process) and the wall time in process, median of --runs rounds (every tolerance once a round:
this machine is shared and noisy).
Usage: python -m benchmarks.tolerance [--runs 5] [--bearing 0]
"""
import argparse
import json
import math
import statistics
import subprocess
import sys
import time

import numpy as np
from fmpy import simulate_fmu

from harness.fmus import ensure_fmu
from reduced_model.orders import last_cycle_orders

TOLS = (None, 1e-2, 1e-3, 1e-4, 1e-5)
KW = dict(stop_time=0.3, output_interval=1e-3, step_size=1e-3)

_LOGGED = r'''
import json, sys
from fmpy import simulate_fmu
fmu, tol, start = sys.argv[1], json.loads(sys.argv[2]), json.loads(sys.argv[3])
simulate_fmu(fmu, relative_tolerance=tol, start_values=start, debug_logging=True,
             stop_time=0.3, output_interval=1e-3, step_size=1e-3)
'''


def orders(fmu, tol, start):
    """Orders 1 and 3 of Fz over the last cycle, complex [N]."""
    r = simulate_fmu(fmu, relative_tolerance=tol, start_values=start, **KW)
    t = r["time"]
    o = last_cycle_orders(t, r["Fz"], 20 * np.pi * t)
    return {k: o[k][0] * np.exp(1j * math.radians(o[k][1])) for k in (1, 3)}


def substeps(fmu, tol, start):
    """The substeps roller 1 took, from the FMU's log in a fresh process."""
    p = subprocess.run([sys.executable, "-c", _LOGGED, str(fmu), json.dumps(tol),
                        json.dumps(start)], capture_output=True, text=True, timeout=600)
    said = [x for x in p.stdout.splitlines() if "roller 1:" in x]
    return int(float(said[-1].split("roller 1:")[1].split()[0])) if said else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], allow_abbrev=False)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--bearing", type=int, default=0, choices=(0, 1))
    args = ap.parse_args()
    fmu = str(ensure_fmu("TripodRoller"))
    start = {"bearing": args.bearing}
    ref = orders(fmu, None, dict(start, max_substep=1e-6))
    walls = {t: [] for t in TOLS}
    for _ in range(args.runs):
        for tol in TOLS:
            t0 = time.perf_counter()
            simulate_fmu(fmu, relative_tolerance=tol, start_values=start, **KW)
            walls[tol].append(time.perf_counter() - t0)
    print(f"bearing {args.bearing}, paper's scene, 1 ms communication steps, 0.3 s; against a "
          f"1 us substep; wall: median of {args.runs}")
    print()
    print("| tolerance | order 1 off | order 3 off | substeps (roller 1) | wall |")
    print("|---|---|---|---|---|")
    for tol in TOLS:
        o = orders(fmu, tol, start)
        off = {k: abs(o[k] - ref[k]) / abs(ref[k]) for k in (1, 3)}
        print(f"| {'none (automatic)' if tol is None else f'{tol:g}'} | {off[1]:.1e} | "
              f"{off[3]:.1e} | {substeps(fmu, tol, start)} | "
              f"{statistics.median(walls[tol]):.3f} s |")


if __name__ == "__main__":
    main()
