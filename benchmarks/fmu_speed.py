"""Speed of the contact FMU through FMPy, in one process after warm-up (issue: FMU speed).

Two whirl cycles of the paper's scene at a 1e-4 s communication step; median of N runs for the
ideal and the lumped bearing, with and without traverse; plus fresh `fmpy simulate` processes
of the FMU (compiled, no Python in its model) and of its reference (Python: with the prebuilt
kernel, and with numba compiling it).
Prints a Markdown table.  Usage: python benchmarks/fmu_speed.py [--runs N]
"""
import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

from harness.fmus import ensure_fmu, reference_fmu

CASES = [
    ("ideal bearing, traverse (default)", {}),
    ("ideal bearing, no traverse", {"traverse": False}),
    ("lumped bearing, traverse", {"bearing": 1}),
    ("lumped bearing, no traverse", {"bearing": 1, "traverse": False}),
]
# rows of whole fresh processes, after the in-process CASES
PROCESS_ROWS = ("fresh `fmpy simulate` process, default scene: the FMU (compiled, no Python)",
                "the same, its reference (Python, the prebuilt kernel, no numba)",
                "the reference with numba compiling the kernel (TRIPOD_AOT=0), cache warm",
                "the reference, numba, empty cache: first run (compiles)",
                "the reference, numba, same cache: second run (FMPy extracts anew)")


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
    ref = str(reference_fmu("TripodRoller"))

    def fresh_run(env=None, fmu=ref):
        t0 = time.perf_counter()
        subprocess.run([str(Path(sys.executable).parent / "fmpy"), "simulate", fmu,
                        "--output-interval", "1e-4", "--output-file", "/dev/null"],
                       capture_output=True, env=env)
        return time.perf_counter() - t0

    import os
    import tempfile
    native = [fresh_run(fmu=fmu) for _ in range(args.runs)]
    fresh = [fresh_run() for _ in range(args.runs)]
    # numba instead of the prebuilt kernel (what the needle-resolved bearing, or a build
    # without the prebuilt library, pays): a warm cache, then an empty one, where the first
    # fresh process compiles and the second must not
    jit_env = dict(os.environ, TRIPOD_AOT="0")
    fresh_run(jit_env)
    jit = [fresh_run(jit_env) for _ in range(args.runs)]
    with tempfile.TemporaryDirectory() as cache:
        env = dict(jit_env, TRIPOD_NUMBA_CACHE=cache)
        cold, warm = fresh_run(env), fresh_run(env)
    lines = [f"Two whirl cycles (0.2 s) of the paper's scene, 1e-4 s communication step, "
             f"{args.runs} runs each, median [min-max]", "",
             "| case | wall time in one process after warm-up |", "|---|---|"]
    lines += [f"| {name} | {med:.3f} s [{lo:.3f}-{hi:.3f}] |" for name, med, lo, hi in rows]
    lines += [f"| {PROCESS_ROWS[k]} | {statistics.median(x):.2f} s [{min(x):.2f}-{max(x):.2f}] |"
              for k, x in enumerate((native, fresh, jit))]
    lines += [f"| {PROCESS_ROWS[3]} | {cold:.2f} s |", f"| {PROCESS_ROWS[4]} | {warm:.2f} s |"]
    print("\n".join(lines))
    if args.md:
        Path(args.md).parent.mkdir(parents=True, exist_ok=True)
        Path(args.md).write_text("\n".join(lines) + "\n")

if __name__ == "__main__":
    main()
