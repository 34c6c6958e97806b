"""Feeds a built FMU bad serialised states in its own process (tests/test_state_abuse.py, and
benchmarks/abuse.py for the long run under valgrind).

Usage: python state_abuse.py FMU CASES_JSON; prints one JSON object: for each case whether the
FMU refused it (fmi2Error from deserialise or set) or, where it took it, whether the outputs of
the next steps stayed finite.  A marker file that a pickle payload would create is checked.
"""
import json
import math
import os
import pickle
import random
import struct
import sys
import time
import zlib

from ctypes import byref

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
from fmpy.logging import addLoggerProxy

fmu, spec = sys.argv[1], json.loads(sys.argv[2])
md = read_model_description(fmu)
d = extract(fmu)
vr = {v.name: v.valueReference for v in md.modelVariables}
OUT = [vr[n] for n in ("Fx", "Fz", "Fz_mod", "Fz_joint", "Fz_2", "Fz_3")]
HEADER = 24                          # the native layer's: magic, phase, reserved, time


LOG = []
CALLBACKS = fmi2CallbackFunctions()
CALLBACKS.logger = fmi2CallbackLoggerTYPE(
    lambda c, n, status, cat, msg: LOG.append(msg.decode(errors="replace")))
CALLBACKS.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
CALLBACKS.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
addLoggerProxy(byref(CALLBACKS))    # the FMU's printf-style message, formatted


def make(ints=None, name="a"):
    s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=name)
    s.instantiate(loggingOn=bool(spec.get("log")), callbacks=CALLBACKS)
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    for k, v in (ints or {}).items():
        s.setInteger([vr[k]], [int(v)])
    s.exitInitializationMode()
    return s


SLOWEST = [0.0]   # the slowest doStep [s] after a state was set (the fuzz benchmark's)


def steps(s, n, t0, moving=False):
    for i in range(n):
        if moving:
            s.setReal([vr["theta"]], [0.17 + 0.001 * math.sin(i)])
        t = time.perf_counter()
        try:
            s.doStep(t0 + i * 1e-4, 1e-4)
        finally:
            SLOWEST[0] = max(SLOWEST[0], time.perf_counter() - t)
    return s.getReal(OUT)


def try_state(s, blob):
    """'refused', or 'finite'/'non-finite' for the outputs of 20 steps after restoring."""
    try:
        st = s.deSerializeFMUstate(blob)
        s.setFMUstate(st)
    except Exception:
        return "refused"
    try:
        y = steps(s, 20, 0.1)
    except Exception:
        return "refused-later"
    return "finite" if all(map(math.isfinite, y)) else "non-finite"


ints = spec.get("ints", {})
src = make(ints)
steps(src, 300, 0.0, moving=spec.get("moving", False))
good = src.serializeFMUstate(src.getFMUstate())
target = make(spec.get("target_ints", ints), "b")
steps(target, 10, 0.0)
marker = spec["marker"]
res = {"size": len(good), "cases": {}}


class Payload:
    def __reduce__(self):
        return (os.system, (f"touch {marker}",))


cases = {"good": good}
cases["pickle"] = good[:HEADER] + pickle.dumps(Payload())
cases["pickle-after-magic"] = good[:HEADER] + good[HEADER:HEADER + 8] + pickle.dumps(Payload())
rng = random.Random(spec.get("seed", 1))
for k in range(spec.get("truncations", 0)):
    n = rng.randrange(0, len(good))
    cases[f"truncated-{n}"] = good[:n]
if spec.get("every_truncation"):
    for n in range(len(good)):
        cases[f"truncated-{n}"] = good[:n]
for k in range(spec.get("flips", 0)):
    b = bytearray(good)
    i = rng.randrange(HEADER, len(b))
    b[i] ^= 1 << rng.randrange(8)
    cases[f"flip-{i}"] = bytes(b)
for k in range(spec.get("random", 0)):
    cases[f"random-{k}"] = good[:HEADER + 8] + rng.randbytes(rng.randrange(0, 2000))
for k in range(spec.get("resealed", 0)):
    # a byte of the body changed and the checksum made valid again: what gets past the CRC
    # reaches the decoder's own checks (lengths, dtypes, shapes, names, values)
    b = bytearray(good)
    i = rng.randrange(HEADER + 8, len(b) - 4)
    b[i] = rng.randrange(256)
    data = bytes(b[HEADER:-4])
    cases[f"resealed-{k}-{i}"] = bytes(b[:HEADER]) + data + struct.pack("<I", zlib.crc32(data))
SLOWEST[0] = 0.0    # (the source's and target's own steps above not counted)
for name, blob in cases.items():
    res["cases"][name] = try_state(target, blob)
    if res["cases"][name] != "refused":   # it stepped: a fresh target for the next case
        target.freeInstance()
        target = make(spec.get("target_ints", ints), "b")
        steps(target, 10, 0.0)
# after every refusal the instance is as it was: the good state still restores and runs
res["good_after"] = try_state(target, good)
for name, value in spec.get("inputs", ()):
    # a master sets a bad input during the run: the step is refused (fmi2Discard), outputs
    # stay the last good ones
    s = make(ints, f"in-{name}")
    steps(s, 50, 0.0)
    before = s.getReal(OUT)
    s.setReal([vr[name]], [float(value)])
    try:
        s.doStep(0.005, 1e-4)
        y = s.getReal(OUT)
        res.setdefault("inputs", {})[f"{name}={value}"] = \
            "ok-finite" if all(map(math.isfinite, y)) else "ok-non-finite"
    except Exception as e:
        kept = s.getReal(OUT) == before
        res.setdefault("inputs", {})[f"{name}={value}"] = \
            ("discard" if "2" in str(getattr(e, "status", "")) or "Discard" in str(e) else
             f"error: {e}") + ("" if kept else " (outputs changed)")
res["slowest_step_s"] = SLOWEST[0]
if spec.get("log"):
    res["log"] = "\n".join(LOG)
res["code_ran"] = os.path.exists(marker)
print(json.dumps(res))
