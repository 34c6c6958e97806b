"""Speed of the contact FMU through FMPy, in one process after warm-up (issue: FMU speed).

Two whirl cycles of the paper's scene at a 1e-4 s communication step; median of N runs for the
ideal and the lumped bearing, with and without traverse; plus fresh `fmpy simulate` processes
of the FMU (compiled, no Python in its model).
Prints a Markdown table.  Usage: python benchmarks/fmu_speed.py [--runs N]
"""
import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

from harness.fmus import ensure_fmu

CASES = [
    ("ideal bearing, traverse (default)", {}),
    ("ideal bearing, no traverse", {"traverse": False}),
    ("lumped bearing, traverse", {"bearing": 1}),
    ("lumped bearing, no traverse", {"bearing": 1, "traverse": False}),
]
# rows of whole fresh processes, after the in-process CASES
PROCESS_ROWS = ("fresh `fmpy simulate` process, default scene: the FMU (compiled, no Python)",)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--md", metavar="FILE", help="also write the table into FILE (make docs)")
    args = ap.parse_args()
    fmu = str(ensure_fmu())
    # one fresh process loads the built FMU, warms up (numba cache load), then times whole
    # two-cycle runs: instantiate, initialise, 2000 x (doStep + getReal of every output)
    from harness.bench import time_runs
    outs = ["Fx", "Fy", "Fz", "Fz_mod", "dFx", "contact_y", "contact_z", "slip_speed",
            "roller_spin"]
    res = time_runs(fmu, [{"sv": sv, "dt": 1e-4, "stop": 0.2} for _, sv in CASES],
                    runs=args.runs, read=outs)
    rows = [(name, r["wall"], min(r["walls"]), max(r["walls"])) for (name, _), r in zip(CASES, res)]
    def fresh_run(fmu):
        t0 = time.perf_counter()
        subprocess.run([str(Path(sys.executable).parent / "fmpy"), "simulate", fmu,
                        "--output-interval", "1e-4", "--output-file", "/dev/null"],
                       capture_output=True)
        return time.perf_counter() - t0

    native = [fresh_run(fmu) for _ in range(args.runs)]
    lines = [f"Two whirl cycles (0.2 s) of the paper's scene, 1e-4 s communication step, "
             f"{args.runs} runs each, median [min-max]", "",
             "| case | wall time in one process after warm-up |", "|---|---|"]
    lines += [f"| {name} | {med:.3f} s [{lo:.3f}-{hi:.3f}] |" for name, med, lo, hi in rows]
    lines += [f"| {PROCESS_ROWS[0]} | {statistics.median(native):.2f} s "
              f"[{min(native):.2f}-{max(native):.2f}] |"]
    print("\n".join(lines))
    if args.md:
        Path(args.md).parent.mkdir(parents=True, exist_ok=True)
        Path(args.md).write_text("\n".join(lines) + "\n")

if __name__ == "__main__":
    main()
