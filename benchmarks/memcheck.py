"""valgrind memcheck on one full run of each FMU, in FMPy and in the plain C host.

A run: instantiate, two whirl cycles (the joint angle and the step size moved at the first
steps), get and set the FMU state, free, exit; each FMU with one roller and with three (the
whole joint).  Python runs with PYTHONMALLOC=malloc so that valgrind sees every allocation.  A
baseline run of the same interpreter importing the same packages without any FMU tells the
reports that belong to the interpreter and the system (the dynamic loader) from those of the
FMU.  Prints, per run, the invalid reads and writes (and invalid frees), those whose stack
passes through the FMU's binary, and whether each was seen in the baseline too.  Logs go to
--out.

Usage: python benchmarks/memcheck.py [--out out/memcheck]   (several minutes: valgrind is
about 50x slower than a native run).  Needs valgrind (Debian: apt-get install valgrind).
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

FULL_RUN = """
import sys
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
md = read_model_description(sys.argv[1]); d = extract(sys.argv[1])
fz = next(v.valueReference for v in md.modelVariables if v.name == "Fz")
s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
              instanceName="memcheck")
s.instantiate(); s.setupExperiment(startTime=0.0)
if len(sys.argv) > 2:   # n_rollers: the whole joint (the contact FMU steps it as one array)
    nr = next(v for v in md.modelVariables if v.name == "n_rollers")
    s.setInteger([nr.valueReference], [int(sys.argv[2])])
s.enterInitializationMode(); s.exitInitializationMode()
dt = 1e-4
th = next(v for v in md.modelVariables if v.name == "theta")
# a master moving an input and the step size every step: both FMUs' compiled steps take the
# new inputs and sizes (the analytic FMU's march from its third step), then the march runs on
# at constant inputs and steps
moved = 200
t = 0.0
for i in range(1000):
    h = dt * (1.0 + 0.5 * ((i * 7919) % 13 - 6) / 6.0) if i < moved else dt
    if i < moved:
        s.setReal([th.valueReference], [float(th.start) * (1.0 + 1e-4 * (i + 1))])
    s.doStep(t, h)
    t += h
state = s.getFMUstate()
a = [s.doStep((1000 + i) * dt, dt) or s.getReal([fz])[0] for i in range(1000)]
s.setFMUstate(state)
b = [s.doStep((1000 + i) * dt, dt) or s.getReal([fz])[0] for i in range(1000)]
s.freeFMUstate(state); s.terminate(); s.freeInstance()
assert a == b, "rollback not exact"
print("run complete")
"""
BASELINE = "import fmpy, numpy, scipy, numba, fmpy.fmi2; print('run complete')"
KINDS = ("Invalid read", "Invalid write", "Invalid free", "Mismatched free")


def errors(log_text):
    """Invalid-access reports of a valgrind log: [(kind, first frames), ...]."""
    out = []
    for block in re.split(r"\n==\d+== \n", log_text):
        lines = [re.sub(r"^==\d+== ?", "", ln) for ln in block.splitlines()]
        head = next((ln for ln in lines if ln.startswith(KINDS)), None)
        if head:
            frames = [ln.strip() for ln in lines if re.match(r"\s+(at|by) 0x", ln)]
            out.append((head.split(" of size")[0], frames))
    return out


def definitely_lost_through(log_text, binary):
    """Bytes and records of 'definitely lost' leak records whose stack passes through binary."""
    total = n = 0
    for block in re.split(r"\n==\d+== \n", log_text):
        m = re.search(r"([\d,]+) bytes in [\d,]+ blocks are definitely lost", block)
        if m and binary in block:
            total += int(m.group(1).replace(",", ""))
            n += 1
    return total, n


def signature(frames):
    """Where an error is, without addresses: its first three functions."""
    return tuple(re.sub(r"0x[0-9A-F]+: ", "", f.split(" (")[0]) for f in frames[:3])


def valgrind(cmd, log, env):
    # keep-debuginfo: FMPy unloads the FMU's binary before exit; its frames must stay named
    full = ["valgrind", "--tool=memcheck", "--error-limit=no", "--num-callers=40",
            "--keep-debuginfo=yes", "--leak-check=full", f"--log-file={log}"] + cmd
    p = subprocess.run(full, capture_output=True, text=True, env=env, timeout=7200)
    return p.returncode, p.stdout + p.stderr


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(ROOT / "out" / "memcheck"))
    args = ap.parse_args()
    if not shutil.which("valgrind"):
        sys.exit("memcheck.py needs valgrind: apt-get install valgrind")
    from fmpy import extract, read_model_description
    from harness.fmus import FMU_NAMES, ensure_fmu
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, PYTHONMALLOC="malloc")
    # the C host of the test suite
    import fmpy
    host = out / "fmi2_host"
    subprocess.run(["cc", "-std=c11", "-O1", "-g", f"-I{Path(fmpy.__file__).parent / 'c-code'}",
                    str(ROOT / "tests" / "c_host" / "fmi2_host.c"), "-o", str(host), "-ldl",
                    "-lpthread"], check=True)
    runs = [("baseline: Python, fmpy, numpy, scipy, numba; no FMU",
             [sys.executable, "-c", BASELINE], None)]
    tmp = tempfile.mkdtemp()
    for name in FMU_NAMES:
        fmu = ensure_fmu(name)
        md = read_model_description(str(fmu))
        d = extract(str(fmu), unzipdir=os.path.join(tmp, name))
        fz = next(v.valueReference for v in md.modelVariables if v.name == "Fz")
        runs.append((f"{name} in FMPy", [sys.executable, "-c", FULL_RUN, str(fmu)], name))
        runs.append((f"{name}, three rollers, in FMPy",
                     [sys.executable, "-c", FULL_RUN, str(fmu), "3"], name))
        runs.append((f"{name} in the C host", [str(host), d, name, md.guid, str(fz), "0.2",
                                               "1e-4", os.path.join(tmp, "fz.txt")], name))
    base = set()
    print("| run | exit | invalid reads/writes/frees | of them in the FMU's binary | "
          "not in the baseline | definitely lost through the FMU's binary | run complete |")
    print("|---|---|---|---|---|---|---|")
    for label, cmd, name in runs:
        log = out / (re.sub(r"\W+", "_", label)[:40] + ".log")
        rc, text = valgrind(cmd, log, env)
        text_log = log.read_text()
        errs = errors(text_log)
        sigs = [signature(f) for _, f in errs]
        ours = sum(any(f"{name}.so" in fr for fr in f) for _, f in errs) if name else 0
        if name is None:
            base = set(sigs)
        new = [s for s in sigs if s not in base]
        done = "run complete" in text or "0 failed" in text
        lost = definitely_lost_through(text_log, f"{name}.so") if name else (0, 0)
        print(f"| {label} | {rc} | {len(errs)} | {ours} | {len(new)} | "
              f"{lost[0]} bytes in {lost[1]} records | {done} |")
        for s in sorted(set(new)):
            print(f"|   not in baseline: {' <- '.join(s)} | | | | | | |")
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
