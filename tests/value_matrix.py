"""Sets every parameter and input of a built FMU to hostile values, before and during a run, in
its own process (tests/test_value_matrix.py; python -m benchmarks.abuse for every bearing).

Usage: python value_matrix.py FMU SPEC_JSON.  SPEC: {"ints": {name: value} for the base scene,
"only": [names] (default: every Real and Integer parameter and input), "steps": n}.  Prints
one JSON line per case as soon as it ends (a case that hangs is the last line the caller
sees): {"case", "outcome", "seconds", "message"}.  Outcomes:
  finite     every output finite after the steps
  refused    a call returned a non-OK status and the FMU logged a one-line reason
  DEFECT:... a non-finite output, a refusal without a reason, a multi-line message or a
             traceback, or an exception other than a status
"""
import json
import math
import sys
import time

from fmpy import extract, read_model_description
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE,
                       fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE)
from fmpy.fmi1 import FMICallException
from fmpy.logging import addLoggerProxy
from ctypes import byref
from fmpy import calloc, free

fmu, spec = sys.argv[1], json.loads(sys.argv[2])
md = read_model_description(fmu)
d = extract(fmu)
VARS = {v.name: v for v in md.modelVariables}
OUT = [v.valueReference for v in md.modelVariables
       if v.causality == "output" and v.type == "Real"]
N = spec.get("steps", 20)
DT = 1e-4

REAL_VALUES = [("nan", math.nan), ("+inf", math.inf), ("-inf", -math.inf), ("0", 0.0),
               ("-0", -0.0), ("denormal", 5e-324), ("min", None), ("max", None),
               ("1e300", 1e300), ("-1e300", -1e300)]


def int_values(v):
    lo, hi = int(v.min), int(v.max)
    return [("min", lo), ("max", hi), ("0", 0), ("-1", -1), ("min-1", lo - 1), ("max+1", hi + 1),
            ("int-max", 2 ** 31 - 1), ("int-min", -2 ** 31)]


def values(v):
    if v.type == "Integer":
        return int_values(v)
    return [(k, float(v.min) if k == "min" else float(v.max) if k == "max" else x)
            for k, x in REAL_VALUES]


logs = []


def logger(component, name, status, category, message):
    logs.append((status, message.decode(errors="replace")))


CALLBACKS = fmi2CallbackFunctions()
CALLBACKS.logger = fmi2CallbackLoggerTYPE(logger)
CALLBACKS.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
CALLBACKS.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
addLoggerProxy(byref(CALLBACKS))    # the FMU's printf-style message, formatted


def make(name):
    s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=name)
    s.instantiate(loggingOn=True, callbacks=CALLBACKS)
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    return s


def set_value(s, v, x):
    if v.type == "Integer":
        s.setInteger([v.valueReference], [x])
    else:
        s.setReal([v.valueReference], [x])


def run_case(name, x, during):
    v = VARS[name]
    s = make(f"{name}")
    try:
        for k, val in spec.get("ints", {}).items():
            s.setInteger([VARS[k].valueReference], [int(val)])
        if not during:
            set_value(s, v, x)
        s.exitInitializationMode()
        for i in range(N):
            if during and i == N // 2:
                set_value(s, v, x)
            s.doStep(i * DT, DT)
        y = s.getReal(OUT)
        return "finite" if all(map(math.isfinite, y)) else "DEFECT: non-finite output"
    except FMICallException:
        return "refused"
    finally:
        try:
            s.terminate()
        except FMICallException:
            pass
        s.freeInstance()


def judge(outcome, msgs):
    if outcome != "refused":
        return outcome
    reasons = [m for st, m in msgs if st >= 2]     # fmi2Discard and worse carry the reason
    if not reasons:
        return "DEFECT: refused without a logged reason"
    for m in reasons:
        if "Traceback" in m or "\n" in m.strip():
            return "DEFECT: multi-line message"
    return outcome


# warm-up, not counted: the first run of each bearing compiles its kernels (numba, up to a
# minute for the needle row on a fresh machine; cached from then on)
for b in ((0, 1, 2) if "bearing" in VARS else (None,)):
    t0 = time.perf_counter()
    s = make("warm-up")
    if b is not None:
        s.setInteger([VARS["bearing"].valueReference], [b])
    s.exitInitializationMode()
    s.doStep(0.0, DT)
    s.terminate()
    s.freeInstance()
    print(json.dumps({"warm-up": b, "seconds": round(time.perf_counter() - t0, 3)}), flush=True)

names = spec.get("only") or [v.name for v in md.modelVariables
                             if v.causality in ("parameter", "input") and v.type in ("Real", "Integer")]
for name in names:
    v = VARS[name]
    phases = ("before", "during")
    for label, x in values(v):
        for phase in phases:
            del logs[:]
            t0 = time.perf_counter()
            try:
                outcome = judge(run_case(name, x, phase == "during"), logs)
            except Exception as e:   # anything but a status: the host saw a crash-like failure
                outcome = f"DEFECT: {type(e).__name__}: {e}"
            worst = max((m for st, m in logs if st >= 2), key=len, default="")
            print(json.dumps({"case": f"{name}={label} {phase}", "outcome": outcome,
                              "seconds": round(time.perf_counter() - t0, 3),
                              "message": worst[:300]}), flush=True)
