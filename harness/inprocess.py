"""An FMU's model run as Python in this process, behind the FMI 2.0 calls FMPy makes: the oracle
the tests hold the compiled FMUs to.

Each FMU's binary compiles one lifecycle, scalar functions over flat arrays (``init``, ``step``
and, where the model has them, ``end`` and ``state_problem``): fmu_src/tripod_model/lifecycle.py,
reduced_model/analytic_kernel.py, driveline/mounts.py.  ``InProcess`` calls the same functions as
Python (the contact model's kernel through numba) over arrays laid out by the model's own
``native_layout``, and does what fmu_src/native/fmi2_native.c does around them: start values,
the checks of values and inputs, the call sequence, the notes worded into the log, FMU states
(all but the work array).  Used as FMPy's ``fmu_instance``::

    simulate_fmu(fmu, fmu_instance=InProcess(fmu), fmi_type="CoSimulation", ...)

runs the model through FMPy's own master (its input interpolation, its communication points), so
its outputs are the compiled FMU's to the last bit where the two compute alike.
"""
from __future__ import annotations

import importlib
import math

import numpy as np
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2Discard, fmi2Error, fmi2OK, fmi2Warning

from harness.fmus import builder
from reduced_model.cfuncs import worded_notes

ARRAYS = ("T", "IN", "X", "OUT", "W")
NO_NOTES = {"at": -1}     # (a model that leaves none: the powertrain)


def _layout_and_model(name):
    """(native_layout(), the module whose functions the binary compiles) of FMU ``name``."""
    spec, layout = builder().COMPILED[name]
    model = importlib.import_module(spec.split(":")[0])
    module, fn = layout.split(":")
    return getattr(importlib.import_module(module), fn)(), model


class InProcess(FMU2Slave):
    """FMU ``fmu``'s model (its name read from its model description), run as Python here."""

    def __init__(self, fmu, logger=None):   # (FMU2Slave's own loads a binary: not called)
        self.modelDescription = md = read_model_description(str(fmu))
        self.name = md.modelName
        self.component = None         # (FMPy's C-level setters take it: unused here)
        self.layout, self.model = _layout_and_model(self.name)
        self.logger = logger          # (status, message) -> None, or None
        self.log = []                 # [(status, message)]
        lay = self.layout
        self.sizes = lay["sizes"]
        self.vars = {}                # value reference, type -> (variable, array, slot, start)
        for v in md.modelVariables:
            array, slot = lay["arrays"][v.name]
            p = lay["by_name"].get(v.name)
            start = float(p.default) if p is not None else \
                float({"true": 1, "false": 0}.get(v.start, v.start or 0))
            kind = {"Real": "R", "Integer": "I", "Boolean": "B"}[v.type]
            self.vars[(v.valueReference, kind)] = (v, array[3:], slot, start)
        self._reset()

    # --- the arrays and the call sequence ---
    def _reset(self):
        self.a = {k: np.zeros(self.sizes[k]) for k in ARRAYS}
        for v, array, slot, start in self.vars.values():
            self.a[array][slot] = start
        self.phase = "instantiated"
        self.time = 0.0
        self.tolerance = 0.0

    def _say(self, status, msg):
        self.log.append((status, msg))
        if self.logger is not None:
            self.logger(status, msg)

    def _fail(self, fn, msg, status=fmi2Error):
        self._say(status, msg)
        raise FMICallException(fn, status)

    def _notes(self, prefix=""):
        """The notes the last call left in W, worded and logged as the native layer does."""
        notes = self.layout.get("notes", NO_NOTES)
        if notes["at"] < 0:
            return
        for level, msg in worded_notes(self.a["W"], notes["at"], notes["text"]):
            self._say_note(level, prefix, msg)

    def _say_note(self, level, prefix, msg):
        if level >= 2:
            self._say(fmi2Error, prefix + msg)
        else:
            self._say(fmi2Warning if level == 1 else fmi2OK, msg)

    def _call(self, fn, *extra):
        """fn(T, IN, X, OUT, W, *extra): one of the model's lifecycle functions, its code."""
        return int(fn(*(self.a[k] for k in ARRAYS), *extra))

    def _check(self, names):
        """The first of these variables whose value its range refuses: (False, why)."""
        from reduced_model.scene import check_param
        for name in names:
            p = self.layout["by_name"].get(name)
            array, slot = self.layout["arrays"][name]
            if p is None:
                continue
            x = self.a[array[3:]][slot]
            try:
                check_param(p, bool(x) if p.kind == "bool" else x)
            except ValueError as e:
                return False, str(e)
        return True, ""

    # --- FMI 2.0, as FMPy's FMU2Slave offers it ---
    def instantiate(self, *args, **kwargs):
        self._reset()

    def setupExperiment(self, tolerance=None, startTime=0.0, stopTime=None):
        self.time = startTime
        self.tolerance = tolerance if tolerance and tolerance > 0 and math.isfinite(tolerance) \
            else 0.0
        return fmi2OK

    def enterInitializationMode(self):
        self.phase = "init"
        return fmi2OK

    def _take_host_tolerance(self):
        if not self.tolerance or "tolerance" not in self.layout["by_name"]:
            return
        array, slot = self.layout["arrays"]["tolerance"]
        T = self.a[array[3:]]
        if T[slot] != 0.0:
            return
        p = self.layout["by_name"]["tolerance"]
        t = self.tolerance
        if p.auto_or_min and t < p.auto_or_min:
            t = p.auto_or_min
        if p.hi is not None and t > p.hi:
            t = p.hi
        T[slot] = t
        self._say(fmi2OK, f"tolerance = {t:g}: the host's {self.tolerance:g} "
                          f"(fmi2SetupExperiment)")

    def exitInitializationMode(self):
        self._take_host_tolerance()
        ok, why = self._check(self.layout["check_order"])
        if not ok:
            self.phase = "errored"
            self._fail("fmi2ExitInitializationMode",
                       f"fmi2ExitInitializationMode: invalid parameter: {why}")
        rc = self._call(self.model.init)
        if rc in (1, 3):
            self._notes("fmi2ExitInitializationMode: invalid parameter: ")
        if rc != 1:
            self.phase = "errored"
            raise FMICallException("fmi2ExitInitializationMode", fmi2Error)
        self.phase = "ok"
        return fmi2OK

    def _set(self, fn, vr, values, kind):
        rows = []
        for r, x in zip(vr, values):
            row = self.vars.get((int(r), kind))
            if row is None:
                self._fail(fn, f"{fn}: no variable with value reference {r}")
            v, array, slot, _ = row
            if array == "OUT":
                self._fail(fn, f"{fn}: {v.name} is an output")
            if array == "T" and self.phase == "ok":
                self._fail(fn, f"{fn}: {v.name} is a fixed parameter: set it before "
                               f"initialisation")
            rows.append((array, slot, float(x)))
        for array, slot, x in rows:
            self.a[array][slot] = x

    def _get(self, vr, kind):
        out = []
        for r in vr:
            v, array, slot, _ = self.vars[(int(r), kind)]
            out.append(self.a[array][slot])
        return out

    def setReal(self, vr, value):
        self._set("fmi2SetReal", vr, value, "R")

    def setInteger(self, vr, value):
        self._set("fmi2SetInteger", vr, value, "I")

    def setBoolean(self, vr, value):
        self._set("fmi2SetBoolean", vr, [1.0 if x else 0.0 for x in value], "B")

    # (FMPy's input table sets inputs through the C-level setters)
    def fmi2SetReal(self, component, vr, nvr, value):
        self.setReal(list(vr)[:nvr], list(value)[:nvr])
        return fmi2OK

    def fmi2SetInteger(self, component, vr, nvr, value):
        self.setInteger(list(vr)[:nvr], list(value)[:nvr])
        return fmi2OK

    def fmi2SetBoolean(self, component, vr, nvr, value):
        self.setBoolean(list(vr)[:nvr], list(value)[:nvr])
        return fmi2OK

    def getReal(self, vr):
        return self._get(vr, "R")

    def getInteger(self, vr):
        return [int(x) for x in self._get(vr, "I")]

    def getBoolean(self, vr):
        return [x != 0.0 for x in self._get(vr, "B")]

    def doStep(self, currentCommunicationPoint, communicationStepSize,
               noSetFMUStatePriorToCurrentPoint=True):
        t, h = currentCommunicationPoint, communicationStepSize
        names = [n for n, (arr, _) in self.layout["arrays"].items() if arr == "IN_IN"]
        ok, why = self._check(names)
        if not ok:
            self.phase = "failed"
            self._fail("fmi2DoStep", f"invalid input at t = {t:g} s: {why}", fmi2Discard)
        rc = self._call(self.model.step, t, h)
        notes = self.layout.get("notes", NO_NOTES)
        if notes["at"] >= 0 and self.a["W"][notes["at"]] != 0.0:
            self._notes(f"step refused at t = {t:g} s: ")
        if rc != 1:
            self.phase = "failed"
            raise FMICallException("fmi2DoStep", fmi2Discard)
        self.time = t + h
        return fmi2OK

    def terminate(self):
        if hasattr(self.model, "end"):
            self._call(self.model.end)
            self._notes("fmi2Terminate: ")
        self.phase = "terminated"
        return fmi2OK

    def freeInstance(self):
        pass

    def reset(self):
        self._reset()

    # --- FMU states: every array but the work (rebuilt by every call) ---
    def getFMUState(self):
        return ({k: self.a[k].copy() for k in ARRAYS if k != "W"}, self.phase, self.time)

    def setFMUState(self, state):
        arrays, phase, time = state
        stepping = ("ok", "failed", "terminated")
        built = np.array_equal(arrays["T"], self.a["T"]) and self.phase in stepping
        if phase in stepping and not built:   # the work for the state's parameters: its start
            for k in arrays:
                self.a[k][:] = arrays[k]
            self.a["W"][:] = 0.0
            self._call(self.model.init)
        for k in arrays:
            self.a[k][:] = arrays[k]
        self.phase, self.time = phase, time
        return fmi2OK

    def freeFMUState(self, state):
        pass

    getFMUstate, setFMUstate, freeFMUstate = getFMUState, setFMUState, freeFMUState   # (FMPy's)
