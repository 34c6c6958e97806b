"""Every host ends clean: fresh processes that run an FMU and exit normally, counted.

Each run is a new Python process that simulates the FMU's DefaultExperiment (two whirl cycles)
and then exits as any user script does (interpreter teardown, exit handlers, library unload):
through ``fmpy.simulate_fmu`` and through the ``fmpy simulate`` command line.  pythonfmu 0.7's
binary aborted 15-42 % of such runs (``corrupted double-linked list``, exit 134); the table
counts non-zero exits and aborts (SIGABRT) of ours.  Two runs at a time (one per core).

Usage: python benchmarks/exit_clean.py [--runs 300] [--cli-runs 50] [--needle-runs 50]
       [--fmu PATH ...]
Exit status 1 if any run did not exit 0.
"""
import argparse
import signal
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from harness.fmus import FMU_NAMES, ensure_fmu

SCRIPT = """
import sys
from fmpy import simulate_fmu
r = simulate_fmu(sys.argv[1], output_interval=1e-4)
assert len(r) == 2001 and abs(r["Fz"][-1]) < 1e6, len(r)
"""

# the needle-resolved bearing (a short run)
SCRIPT_NEEDLES = """
import sys
from fmpy import simulate_fmu
r = simulate_fmu(sys.argv[1], stop_time=0.005, output_interval=1e-4,
                 start_values={"bearing": 2})
assert len(r) == 51 and abs(r["Fz"][-1]) < 1e6, len(r)
"""


def one_run(cmd, cwd):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600, cwd=cwd)
    return p.returncode, p.stderr[-600:]


def count(cmds, cwd):
    """(runs, non-zero exits, SIGABRT aborts, first failure's stderr) of the commands."""
    with ThreadPoolExecutor(2) as pool:
        res = list(pool.map(lambda c: one_run(c, cwd), cmds))
    bad = [(rc, err) for rc, err in res if rc != 0]
    aborts = sum(rc in (-signal.SIGABRT, 128 + signal.SIGABRT) for rc, _ in bad)
    return len(res), len(bad), aborts, (bad[0] if bad else None)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=300, help="fmpy.simulate_fmu runs per FMU")
    ap.add_argument("--cli-runs", type=int, default=50, help="fmpy simulate runs per FMU")
    ap.add_argument("--needle-runs", type=int, default=0,
                    help="fmpy.simulate_fmu runs of the contact FMU with bearing = 2 (numba)")
    ap.add_argument("--fmu", nargs="*", help="FMU files (default: both of this project)")
    args = ap.parse_args()
    fmus = [Path(f) for f in args.fmu] if args.fmu else [ensure_fmu(n) for n in FMU_NAMES]
    fmpy_cli = str(Path(sys.executable).with_name("fmpy"))
    rows, failed = [], False
    with tempfile.TemporaryDirectory() as tmp:
        for fmu in fmus:
            for how, n, cmd in (
                    ("simulate_fmu", args.runs, [sys.executable, "-c", SCRIPT, str(fmu)]),
                    ("fmpy simulate", args.cli_runs,
                     [fmpy_cli, "simulate", str(fmu), "--output-interval", "1e-4",
                      "--output-file", "out.csv"]),
                    ("simulate_fmu, bearing = 2",
                     args.needle_runs if fmu.stem == "TripodRoller" else 0,
                     [sys.executable, "-c", SCRIPT_NEEDLES, str(fmu)])):
                if n <= 0:
                    continue
                runs, bad, aborts, first = count([cmd] * n, tmp)
                rows.append((fmu.stem, how, runs, bad, aborts))
                if first:
                    failed = True
                    print(f"{fmu.stem} {how}: first failure, exit {first[0]}:\n{first[1]}",
                          file=sys.stderr)
    print("| FMU | how | fresh processes | exit status not 0 | aborts (SIGABRT) |")
    print("|---|---|---|---|---|")
    for r in rows:
        print("| {} | {} | {} | {} | {} |".format(*r))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
