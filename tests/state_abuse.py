"""Feeds a built FMU bad serialised states in its own process (tests/test_state_abuse.py, and
benchmarks/state_fuzz.py for the long run).

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


def reseal(blob, tree_edit):
    """The native header and a state re-encoded with its tree edited (a crafted state with a
    valid checksum: what a hostile host writes)."""
    body = blob[HEADER:]
    n = struct.unpack_from("<I", body, 8)[0]
    head = json.loads(body[12:12 + n])
    arrays = body[12 + n:-4]
    tree_edit(head)
    h = json.dumps(head).encode()
    data = body[:8] + struct.pack("<I", len(h)) + h + arrays
    return blob[:HEADER] + data + struct.pack("<I", zlib.crc32(data))


def _float_arrays(h):
    """(offset [bytes], count) of every float64 array in the decoded header's state tree."""
    found, stack = [], [h["state"]]
    while stack:
        v = stack.pop()
        if isinstance(v, dict):
            if "@array" in v:
                dt, shape, off = v["@array"]
                if dt == "<f8" and math.prod(shape) > 0:
                    found.append((off, math.prod(shape)))
            else:
                stack += v.values()
        elif isinstance(v, list):
            stack += v
    return sorted(found)


# values a structure-aware fuzz writes into a state's arrays: plausible-looking and wrong
MUTANTS = (0.5, 1.0, 3.0, -3.0, 0.01, -0.01, 1e-3, 0.0, 1e6, -1e6, 1.8e308, -1.8e308,
           float("nan"), float("inf"), 5e-324)


def _float_leaves(h):
    """(container, key) of every float in the decoded header's state tree (the analytic FMU
    keeps its march there; non-finite floats are {"@float": ...})."""
    found, stack = [], [h["state"]]
    while stack:
        v = stack.pop()
        items = v.items() if isinstance(v, dict) else enumerate(v) if isinstance(v, list) else ()
        if isinstance(v, dict) and ("@array" in v or "@float" in v):
            continue
        for k, x in items:
            if type(x) is float or (isinstance(x, dict) and "@float" in x):
                found.append((v, k))
            else:
                stack.append(x)
    return found


def _json_float(x):
    return x if math.isfinite(x) else {"@float": repr(x)}


def mutate(blob, rng, count):
    """A good state with ``count`` values inside it changed (in its float arrays or its
    header's floats; to MUTANTS or the old value times a random factor) and its checksum made
    valid again."""
    body = bytearray(blob[HEADER:-4])
    n = struct.unpack_from("<I", body, 8)[0]
    head = json.loads(bytes(body[12:12 + n]))
    arrays, leaves = _float_arrays(head), _float_leaves(head)
    payload = bytearray(body[12 + n:])
    for _ in range(count):
        pick = rng.randrange(len(arrays) + len(leaves))
        if pick < len(arrays):
            off, cnt = arrays[pick]
            at = off + 8 * rng.randrange(cnt)
            old = struct.unpack_from("<d", payload, at)[0]
        else:
            box, key = leaves[pick - len(arrays)]
            old = box[key] if type(box[key]) is float else float(box[key]["@float"])
        new = rng.choice(MUTANTS) if rng.random() < 0.7 else old * rng.choice((-1, 10, 1e3))
        if pick < len(arrays):
            struct.pack_into("<d", payload, at, new)
        else:
            box[key] = _json_float(new)
    h = json.dumps(head).encode()
    data = bytes(body[:8]) + struct.pack("<I", len(h)) + h + bytes(payload)
    return blob[:HEADER] + data + struct.pack("<I", zlib.crc32(data))


def set_array_value(blob, path, index, value):
    """A state with one value of the array at ``path`` (keys into the state tree) set, and its
    checksum made valid again."""
    body = bytearray(blob[HEADER:-4])
    n = struct.unpack_from("<I", body, 8)[0]
    node = json.loads(bytes(body[12:12 + n]))["state"]
    for k in path:
        node = node[k]
    struct.pack_into("<d", body, 12 + n + node["@array"][2] + 8 * index, value)
    data = bytes(body)
    return blob[:HEADER] + data + struct.pack("<I", zlib.crc32(data))


ARRAY_EDITS = {   # name: (path, index, value); the contact FMU
    "slide-half-a-metre": (("model", 0, "Y"), 1, 0.5),
    "slide-three-mm": (("model", 0, "Y"), 1, 3e-3),
}


def _first_array(h):
    stack = [h["state"]]
    while stack:
        v = stack.pop()
        if isinstance(v, dict):
            if "@array" in v:
                return v["@array"]
            stack += v.values()
        elif isinstance(v, list):
            stack += v


def _deep(h):
    v = 0.0
    for _ in range(200):
        v = [v]
    h["state"]["vars"]["Fz"] = v


CRAFTED = {   # name: an edit of the decoded header (then re-sealed with a valid checksum)
    "nan-output": lambda h: h["state"]["vars"].update(Fz={"@float": "nan"}),
    "inf-input": lambda h: h["state"]["vars"].update(theta={"@float": "inf"}),
    "input-out-of-range": lambda h: h["state"]["vars"].update(omega=1e5),
    "extra-variable": lambda h: h["state"]["vars"].update(__class__=1.0),
    "missing-variable": lambda h: h["state"]["vars"].pop("Fz"),
    "other-guid": lambda h: h.update(guid="{00000000-0000-0000-0000-000000000000}"),
    "other-structural": lambda h: h["structural"].update(n_rollers=4 - h["structural"]["n_rollers"]),
    "other-version": lambda h: h.update(version=99),
    "array-longer-than-data": lambda h: _first_array(h).__setitem__(1, [10 ** 7]),
    "array-offset-past-end": lambda h: _first_array(h).__setitem__(2, 10 ** 9),
    "array-negative-shape": lambda h: _first_array(h).__setitem__(1, [-1]),
    "array-object-dtype": lambda h: _first_array(h).__setitem__(0, "|O"),
    "nested-200-deep": _deep,
    "string-for-number": lambda h: h["state"]["vars"].update(Fx="1.0"),
    # the analytic FMU's arrays (reduced_model/analytic_kernel.py's X): cut short, or not an array
    "X-cut-short": lambda h: h["state"]["X"]["@array"].__setitem__(1, [10]),
    "X-a-number": lambda h: h["state"].update(X=0.5),
}


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
for k in range(spec.get("mutations", 0)):
    cases[f"mutated-{k}"] = mutate(good, rng, 1 + k % 3)
for name in spec.get("crafted", ()):
    cases[name] = (set_array_value(good, *ARRAY_EDITS[name]) if name in ARRAY_EDITS else
                   reseal(good, CRAFTED[name]))
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
