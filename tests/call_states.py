"""Calls every FMI 2.0 co-simulation function of a built FMU in every phase of its call sequence,
in its own process (tests/test_call_states.py).

Usage: python call_states.py FMU [SPEC_JSON]; SPEC: {"input": the Real input set to NaN and
back (default theta), "outputs": the Real outputs read (default the joint's)}; prints one
JSON object: "table" {phase: {function: status}},
the status the FMU returned (0 OK ... 3 Error), each call on a fresh instance brought to the
phase; and whether a state restored into an instance not yet initialised continues the run
of the instance it was taken from bit for bit.
"""
import ctypes
import json
import math
import sys

from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2LastSuccessfulTime

fmu = sys.argv[1]
md = read_model_description(fmu)
d = extract(fmu)
vr = {v.name: v.valueReference for v in md.modelVariables}
spec = json.loads(sys.argv[2]) if len(sys.argv) > 2 else {}
INPUT = spec.get("input", "theta")
OUTPUTS = spec.get("outputs", ["Fz", "Fx", "Fz_joint", "whirl_angle"])
THETA = float(next(v.start for v in md.modelVariables if v.name == INPUT))
INT = next((v.name for v in md.modelVariables if v.type == "Integer"), None)
BOOL = next((v.name for v in md.modelVariables if v.type == "Boolean"), None)


def status_of(call):
    try:
        call()
        return 0
    except FMICallException as e:
        return int(e.status)


def at(phase):
    """A fresh instance in `phase`."""
    s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=f"in-{phase}")
    s.instantiate()
    if phase == "instantiated":
        return s
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    if phase == "error":      # a failed call (an initialisation refusing its inputs) is an error
        s.setReal([vr[INPUT]], [math.nan])
        assert status_of(s.exitInitializationMode) == 3
        return s
    if phase == "initialization":
        return s
    s.exitInitializationMode()
    s.doStep(0.0, 1e-4)
    if phase == "step complete":
        return s
    if phase == "step failed":     # a step refused (an invalid input) is a failed step
        s.setReal([vr[INPUT]], [math.nan])
        assert status_of(lambda: s.doStep(1e-4, 1e-4)) == 2
        return s
    if phase == "terminated":
        s.terminate()
        return s
    raise ValueError(phase)


def _good_state():
    """A state of this FMU taken after a step (bytes): what a host restores into any phase."""
    donor = at("step complete")
    blob = donor.serializeFMUstate(donor.getFMUstate())
    donor.freeInstance()
    return blob


GOOD = None


def state_calls(s):
    """The state functions: get, size, serialise and free on a state taken in this phase;
    deserialise and set a good state from an instance after a step."""
    return {
        "fmi2GetFMUstate": lambda: s.getFMUstate(),
        "fmi2FreeFMUstate": lambda: s.freeFMUstate(s.getFMUstate()),
        "fmi2SerializedFMUstateSize": lambda: s.fmi2SerializedFMUstateSize(
            s.component, s.getFMUstate(), ctypes.byref(ctypes.c_size_t())),
        "fmi2SerializeFMUstate": lambda: s.serializeFMUstate(s.getFMUstate()),
        "fmi2DeSerializeFMUstate": lambda: s.deSerializeFMUstate(GOOD),
        "fmi2SetFMUstate": lambda: s.setFMUstate(s.deSerializeFMUstate(GOOD)),
    }


def calls(s):
    n0 = (ctypes.c_uint * 1)()
    r = ctypes.c_double()
    i = (ctypes.c_int * 1)()
    c = {
        "fmi2SetupExperiment": lambda: s.setupExperiment(startTime=0.0),
        "fmi2EnterInitializationMode": s.enterInitializationMode,
        "fmi2ExitInitializationMode": s.exitInitializationMode,
        "fmi2Terminate": s.terminate,
        "fmi2Reset": s.reset,
        "fmi2GetReal": lambda: s.getReal([vr[OUTPUTS[0]]]),
        # the first Integer and Boolean variable (none: a call for zero variables)
        "fmi2GetInteger": lambda: (s.getInteger([vr[INT]]) if INT else
                                   s.fmi2GetInteger(s.component, n0, 0, i)),
        "fmi2GetBoolean": lambda: (s.getBoolean([vr[BOOL]]) if BOOL else
                                   s.fmi2GetBoolean(s.component, n0, 0, i)),
        "fmi2GetString": lambda: s.fmi2GetString(s.component, n0, 0, (ctypes.c_char_p * 1)()),
        "fmi2SetReal": lambda: s.setReal([vr[INPUT]], [THETA]),
        "fmi2SetInteger": lambda: s.fmi2SetInteger(s.component, n0, 0, i),
        "fmi2SetBoolean": lambda: s.fmi2SetBoolean(s.component, n0, 0, i),
        "fmi2SetString": lambda: s.fmi2SetString(s.component, n0, 0, (ctypes.c_char_p * 1)()),
        "fmi2DoStep": lambda: s.doStep(1e-4, 1e-4),
        "fmi2GetRealStatus": lambda: s.fmi2GetRealStatus(s.component, fmi2LastSuccessfulTime,
                                                        ctypes.byref(r)),
    }
    c.update(state_calls(s))
    return c


GOOD = _good_state()
PHASES = ("instantiated", "initialization", "step complete", "step failed", "terminated", "error")
res = {}
for phase in PHASES:
    res[phase] = {}
    probe = at(phase)
    names = list(calls(probe))
    probe.freeInstance()
    for name in names:
        s = at(phase)
        res[phase][name] = status_of(calls(s)[name])
        try:
            s.freeInstance()
        except Exception:
            pass
# a state restored into an instance not yet initialised continues the run bit for bit
OUT = [vr[n] for n in OUTPUTS]
donor = at("step complete")
for i in range(1, 200):
    donor.doStep(i * 1e-4, 1e-4)
blob = donor.serializeFMUstate(donor.getFMUstate())
a = [donor.doStep(i * 1e-4, 1e-4) or donor.getReal(OUT) for i in range(200, 300)]
fresh = at("instantiated")
fresh.setFMUstate(fresh.deSerializeFMUstate(blob))
b = [fresh.doStep(i * 1e-4, 1e-4) or fresh.getReal(OUT) for i in range(200, 300)]
# a refused state leaves the instance as it was: the run goes on
s = at("step complete")
bad = bytearray(GOOD)
bad[-1] ^= 1
refused = status_of(lambda: s.deSerializeFMUstate(bytes(bad))) == 3
goes_on = status_of(lambda: s.doStep(1e-4, 1e-4)) == 0
print(json.dumps({"refused_state_keeps_running": refused and goes_on, "table": res, "restored_before_init_identical": a == b,
                  "moved": a[0] != a[-1]}))
