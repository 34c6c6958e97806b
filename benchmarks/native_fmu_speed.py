"""The FMUs, which need no Python, beside the same models through Python: the powertrain, the
analytic joint and the contact joint FMUs (compiled models under fmu_src/native/fmi2_native.c)
and their references (the pythonfmu slaves under the Python layer, build/reference/), each run
by the plain C host tests/c_host/fmu_run.c in fresh processes: the time from the program's start
(before the binary is loaded) to the first step done, and the cost of a step after it (setReal
of the inputs a master moves, doStep, getReal of every Real output).  The joints with one and
three rollers, at fixed inputs and with a master moving theta, omega and the torque every step
(the analytic FMU's slide then stepped in time); the contact joint's bearings too.  Medians of interleaved runs; prints a
markdown table and writes it into docs/benchmarks.md (between the native-speed markers).

    python -m benchmarks.native_fmu_speed [--runs N] [--no-docs]
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import tempfile
import zipfile
from pathlib import Path

from fmpy import read_model_description

from harness.docgen import write_marked
from harness.bench import bare_fmu
from harness.fmus import builder, ensure_fmu, reference_fmu

ROOT = Path(__file__).resolve().parents[1]
HOST = ROOT / "tests" / "c_host" / "fmu_run.c"
DOC = ROOT / "docs" / "benchmarks.md"
STEPS = 4000
# the analytic FMU's master: theta, omega [rad/s] and torque [N m] moving every step
MOVING = {"theta": (0.17, 0.05, 3.0), "omega": (62.8, 20.0, 5.0), "torque": (300.0, 100.0, 7.0)}
# (model, inputs the master moves: None every input (the host's default signals), Integer
# parameters, what the row says)
CASES = (("BareSlave", {"theta": (0.17, 0.05, 3.0), "omega": (62.8, 20.0, 5.0),
                        "torque": (300.0, 100.0, 7.0)}, {},
          "the bare boundary: a step that does nothing, inputs moving"),
         ("Powertrain", None, {}, "launch, every input moving"),
         ("TripodRollerAnalytic", {}, {}, "1 roller, fixed inputs"),
         ("TripodRollerAnalytic", MOVING, {}, "1 roller, inputs moving"),
         ("TripodRollerAnalytic", {}, {"n_rollers": 3}, "3 rollers, fixed inputs"),
         ("TripodRollerAnalytic", MOVING, {"n_rollers": 3}, "3 rollers, inputs moving"),
         ("TripodRoller", {}, {}, "1 roller, fixed inputs"),
         ("TripodRoller", MOVING, {}, "1 roller, inputs moving"),
         ("TripodRoller", {}, {"n_rollers": 3}, "3 rollers, fixed inputs"),
         ("TripodRoller", MOVING, {"n_rollers": 3}, "3 rollers, inputs moving"),
         ("TripodRoller", {}, {"bearing": 1, "n_rollers": 3}, "3 rollers, lumped bearing"),
         ("TripodRoller", {}, {"bearing": 2}, "1 roller, needle-resolved row (46 needles)"))


def bare_native_fmu() -> Path:
    """build/BareNative.fmu: the bare boundary compiled under the native layer, no Python
    (benchmarks/bare_model.py; built when missing or older than its sources): what that layer
    alone costs a step."""
    from benchmarks import bare_model
    b = builder()
    dest = ROOT / "build" / "BareNative.fmu"
    srcs = [ROOT / "benchmarks" / "bare_model.py", *b.NATIVE_FMU, *b.AOT]
    if not dest.exists() or any(dest.stat().st_mtime < f.stat().st_mtime for f in srcs):
        import zipfile
        with zipfile.ZipFile(bare_fmu()) as z:
            xml = z.read("modelDescription.xml")
        b.build_module("native_fmu").package(xml, dest, "benchmarks.bare_model:c_functions",
                                             bare_model.native_layout(), b._fmi_headers(),
                                             targets=("linux64",))
    return dest


def _time(host, binary, md, out, spec, ints):
    vr = {v.name: v.valueReference for v in md.modelVariables}
    ins = [v for v in md.modelVariables if v.causality == "input"]
    if spec is None:
        inputs = ",".join(str(v.valueReference) for v in ins)
    else:
        inputs = ",".join(f"{vr[n]}:{o!r}:{a!r}:{w!r}" for n, (o, a, w) in spec.items())
    outs = ",".join(str(v.valueReference) for v in md.modelVariables
                    if v.causality == "output" and v.type == "Real")
    sets = [",".join(f"{vr[k]}={v}" for k, v in ints.items())] if ints else []
    p = subprocess.run([str(host), str(binary), md.guid, str(STEPS), "1e-4", str(out), inputs,
                        outs, *sets], capture_output=True, text=True, timeout=600)
    if p.returncode != 0:
        raise RuntimeError(p.stdout + p.stderr)
    t = {ln.split()[1]: float(ln.split()[2]) for ln in p.stdout.splitlines()
         if ln.startswith("time ")}
    return t["load-to-first-step-s"], t["per-step-us"], "python-in-process no" in p.stdout


def table(runs=5) -> str:
    rows = []       # (label, fmu, binary, model description, spec, ints)
    with tempfile.TemporaryDirectory() as tmp:
        host = Path(tmp) / "fmu_run"
        subprocess.run([os.environ.get("CC") or "cc", "-std=c99", "-O2",
                        f"-I{builder()._fmi_headers()}", str(HOST), "-o", str(host), "-lm",
                        "-ldl"], check=True)
        for model, spec, ints, what in CASES:
            pair = ((bare_native_fmu(), bare_fmu()) if model == "BareSlave" else
                    (ensure_fmu(model), reference_fmu(model)))
            for kind, fmu in zip(("compiled, no Python", "through Python (reference)"), pair):
                d = Path(tmp) / str(len(rows))
                zipfile.ZipFile(fmu).extractall(d)
                md = read_model_description(str(fmu))
                rows.append((f"{model}: {what}; {kind}", fmu,
                             d / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so",
                             md, spec, ints))
        got = {r[0]: [] for r in rows}
        for _ in range(runs):
            for label, _, binary, md, spec, ints in rows:
                got[label].append(_time(host, binary, md, Path(tmp) / "o.bin", spec, ints))
    lines = [f"Generated by `python -m benchmarks.native_fmu_speed --runs {runs}` (medians of "
             f"{runs} fresh processes each, interleaved; {STEPS} steps of 1e-4 s).", "",
             "| FMU, scene, binary | load to first step [ms] | per step [us] | Python in the "
             "host process | size [kB] |", "|---|---|---|---|---|"]
    for label, fmu, *_ in rows:
        r = got[label]
        first = statistics.median(x[0] for x in r) * 1e3
        step = statistics.median(x[1] for x in r)
        lines.append(f"| {label} | {first:.2f} | {step:.2f} | "
                     f"{'no' if all(x[2] for x in r) else 'yes'} | "
                     f"{fmu.stat().st_size / 1024:.0f} |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--no-docs", action="store_true", help="do not write docs/benchmarks.md")
    a = ap.parse_args(argv)
    text = table(a.runs)
    print(text)
    if not a.no_docs:
        write_marked(DOC, "native-speed", text)


if __name__ == "__main__":
    main()
