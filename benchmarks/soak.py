"""Many instances in one long process: instantiate, step, free, and unload the binary, N times.

A driveline tool loads and frees FMUs many times in one process.  Each cycle here does what
FMPy's FMU2Slave does for a run: load the FMU's binary, instantiate, initialise, step, read,
terminate, free the instance and dlclose the binary.  Prints the resident set size (RSS) over
the cycles and the growth per 100 cycles after a warm-up of 100.

Usage: python benchmarks/soak.py [--cycles 1000] [--steps 20] [--fmu NAME ...]
Exit status 1 if growth exceeds --limit-mb (default 1 MB) per 100 cycles.
"""
import argparse
import os
import sys
import time



def rss_mb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20


def soak(fmu, cycles, steps, dt=1e-4):
    """RSS [MB] after each 100th cycle; the last Fz of each cycle must agree."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(str(fmu))
    unzipped = extract(str(fmu))
    fz = next(v.valueReference for v in md.modelVariables if v.name == "Fz")
    rss, last = {}, None
    for k in range(1, cycles + 1):
        s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                      modelIdentifier=md.coSimulation.modelIdentifier, instanceName=f"i{k}")
        s.instantiate()
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.exitInitializationMode()
        for i in range(steps):
            s.doStep(i * dt, dt)
        y = s.getReal([fz])[0]
        s.terminate()
        s.freeInstance()          # frees the instance and unloads the binary
        if last is not None and y != last:
            raise AssertionError(f"cycle {k}: Fz {y!r} != {last!r}")
        last = y
        if k % 100 == 0:
            rss[k] = rss_mb()
    return rss


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=1000)
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--limit-mb", type=float, default=1.0)
    ap.add_argument("--fmu", nargs="*", default=["TripodRoller", "TripodRollerAnalytic"])
    args = ap.parse_args()
    from harness.fmus import ensure_fmu
    print(f"{args.cycles} cycles of load, instantiate, {args.steps} steps, free, unload; "
          "RSS in MB\n")
    print("| FMU | RSS at 100 | RSS at end | growth per 100 cycles after 100 | s per cycle |")
    print("|---|---|---|---|---|")
    worst = 0.0
    for name in args.fmu:
        t0 = time.perf_counter()
        rss = soak(ensure_fmu(name), args.cycles, args.steps)
        per_cycle = (time.perf_counter() - t0) / args.cycles
        ks = sorted(rss)
        growth = (rss[ks[-1]] - rss[ks[0]]) / max(1, (ks[-1] - ks[0]) / 100)
        worst = max(worst, growth)
        print(f"| {name} | {rss[ks[0]]:.1f} | {rss[ks[-1]]:.1f} | {growth:.3f} | "
              f"{per_cycle:.4f} |")
    sys.exit(0 if worst <= args.limit_mb else 1)


if __name__ == "__main__":
    main()
