"""pythonfmu slave of the one-roller contact model: a thin adapter over tripod_model.

Variables are generated from the parameter table (reduced_model.scene) and the output list
(reduced_model.scene.OUTPUTS); units, ranges and display units are added by fmu_src/build.py.
"""
import math
import sys

from pythonfmu import Fmi2Slave
from pythonfmu.enums import Fmi2Status

from fmi2bridge import requirements
from reduced_model import switches
from reduced_model.scene import BY_NAME, check_value, params_for
from slavekit import (DataState, FastStep, Guarded, StateError, describe, omega_by_angle,
                      register, same_layout)
from tripod_model import native
from tripod_model.layout import H_TAKEN, OP_FP, OP_THETA, OP_TQ, OP_VP, OP_W
from tripod_model.model import JointModel, fast_argv
from tripod_model.state_check import BadState, check_joint_state

_INPUTS = ("theta", "omega", "F_press", "torque", "plunge_speed")
# the inputs the compiled step takes from the native layer: those, and the shaft angle (held for
# the layer, which derives omega from it when the whirl is driven by angle)
_FAST_INPUTS = _INPUTS + ("shaft_angle",)
# where the compiled step reads each input: the model's operating-point vector (a joint's
# header row, whose inputs every roller takes)
_OP_SLOTS = {"theta": OP_THETA, "omega": OP_W, "F_press": OP_FP, "torque": OP_TQ,
             "plunge_speed": OP_VP}


def _have_numba():
    """Whether this Python has numba, without importing it (the prebuilt kernel needs none)."""
    import importlib.util
    return importlib.util.find_spec("numba") is not None


_NUMBA_ON = switches.NUMBA   # off: plain Python on purpose


@describe
class TripodRoller(Guarded, DataState, Fmi2Slave):
    # a state belongs to the parameters it was taken with (the model's layout follows them)
    STRUCTURAL = tuple(p.name for p in params_for("contact") if p.causality != "input")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        register(self)
        self._params = params_for("contact")
        self.model = None
        self._checked = None
        self._fast = None          # the compiled step offered to the native layer (kernel.step)
        self._fast_args = None
        if _NUMBA_ON and not _have_numba():
            # say once what this Python lacks
            need = [r for r in requirements(self.resources or "") if r.startswith("numba")]
            self.log(f"numba is missing in this Python ({sys.executable}, "
                     f"{sys.version.split()[0]}): the contact kernel runs as plain Python, "
                     f"about 40x slower; {sys.executable} -m pip install "
                     f"'{need[0] if need else 'numba'}'", Fmi2Status.warning)

    def _param_values(self):
        return {p.name: getattr(self, p.name) for p in self._params}

    def _initialise(self):
        self.model = JointModel(self._param_values())
        self.log(self.model.info(self.theta, self.omega, self.F_press, self.torque),
                 Fmi2Status.ok, "logAll")
        self._fast = None
        self._fast_args = self._fast_arrays()
        self._steps = [0, 0]       # communication steps compiled, through Python (the log)
        # the outputs at the start time, not their declared zeros
        for k, v in self.model.initial_outputs(self.theta, self.omega, self.F_press,
                                               self.torque, self.plunge_speed).items():
            setattr(self, k, v)

    def _fast_arrays(self):
        """What the native layer needs to step without Python: one roller or three, ideal or
        lumped bearing, the prebuilt kernel (native.py) or numba (TRIPOD_FAST=0 turns it off,
        for comparison)."""
        arrays = self.model.fast_arrays()
        if arrays is None or not switches.FAST:
            return None
        fn = native.step_function()
        if fn is not None:
            address = native.address(fn)
        elif _NUMBA_ON and _have_numba():
            from tripod_model import kernel
            address = kernel.c_step().address
        else:
            return None
        import numpy as np
        from tripod_model import layout as L
        from tripod_model.layout import N_OUT, OUTPUT_NAMES
        vr = {v.name: ref for ref, v in self.vars.items()}
        self._fast_outputs = np.zeros(N_OUT)
        arrays = arrays[:3] + (self._fast_outputs,) + arrays[3:]
        # where each input goes (the model's OP: kernel.step derives its operating point) and
        # its allowed range, for the native layer to take a master's new values without Python
        # (a joint's: its header row, whose inputs every roller takes)
        OP = arrays[2].reshape(-1, L.OP_LEN)[0]
        self._fast_shaft = np.zeros(1)
        in_slots = []
        for name in _FAST_INPUTS:
            p = BY_NAME[name]
            in_slots.append((self._fast_shaft.ctypes.data if name == "shaft_angle" else
                             OP.ctypes.data + OP.itemsize * _OP_SLOTS[name],
                             -math.inf if p.lo is None else float(p.lo),
                             math.inf if p.hi is None else float(p.hi),
                             int(p.lo_open), int(p.hi_open)))
        # where it takes the step size (a master's new one is derived at there too); driven by
        # angle, what the layer derives omega from (TripodRoller._advance's formula)
        by_angle = ((vr["shaft_angle"], vr["omega"], OUTPUT_NAMES.index("whirl_angle"))
                    if self.drive_by_angle else ())
        return {"address": address, "argv": fast_argv(arrays), "in_slots": in_slots,
                "dt_slot": OP.ctypes.data + OP.itemsize * L.OP_DT, "by_angle": by_angle,
                "op": OP, "arrays": arrays, "out_vrs": [vr[n] for n in OUTPUT_NAMES],
                "in_vrs": [vr[n] for n in _FAST_INPUTS], "names": OUTPUT_NAMES}

    def _offer_fast(self, out):
        """After a step through Python: the outputs where the native layer reads them, and
        the compiled step for the next steps (at any inputs in range and any step size)."""
        f = self._fast_args
        if f is None:
            return
        for i, name in enumerate(f["names"]):
            self._fast_outputs[i] = out[name]
        self._fast_hs1 = [r._hs[H_TAKEN] for r in self.model.rollers]
        # the step the operating point was derived for: a step_size that differs from it
        # by the rounding of the master's times (reduced_model.scene.same_step) took that step
        self._fast = FastStep(f["address"], f["argv"].ctypes.data, self._fast_outputs.ctypes.data,
                              self.model.rollers[0].step_dt, f["out_vrs"], f["in_vrs"],
                              [float(getattr(self, n)) for n in _FAST_INPUTS],
                              tuple(f["in_slots"]), f["dt_slot"], f["by_angle"])

    def _fast_sync(self, k, elapsed):
        """The native layer took k compiled steps over elapsed [s]: count them, take their
        outputs."""
        for r, hs1 in zip(self.model.rollers, self._fast_hs1):
            r.fast_synced(k, elapsed, hs1)
        self._steps[0] += k
        self._fast_hs1 = [r._hs[H_TAKEN] for r in self.model.rollers]
        for name, v in zip(self._fast_args["names"], self._fast_outputs.tolist()):
            setattr(self, name, v)

    def _fast_inputs(self, values):
        """The master set inputs (_FAST_INPUTS order; omega derived by the layer when driven by
        angle) while the fast path ran: the native layer checked them against their ranges
        and wrote them where the compiled step takes them (the model's OP); it hands them over
        before Python next sees the instance, so the input variables are what a setReal (or
        _advance) would have made them."""
        for name, v in zip(_FAST_INPUTS, values):
            setattr(self, name, v)
        self._checked = tuple(values[:len(_INPUTS)])
        return True

    def _fast_failed(self, current_time, code):
        """A compiled step failed (2: a non-finite output; 3: a roller's adaptive substeps ran
        out of their budget, kernel.step; else an exception in it)."""
        if code == 3:
            self.log(f"step refused at t = {current_time:g} s: {self.model.refusal()}",
                     Fmi2Status.error)
            return
        why = ("non-finite output" if code == 2 else
               "the compiled step stopped on an arithmetic error (a division by zero or an "
               "overflow: a parameter at the edge of its range)")
        self.log(f"{why} at t = {current_time:g} s; step rejected", Fmi2Status.error)

    def terminate(self):
        if self.model is not None:   # what the integrator did, for a user who checks
            self.log(self.model.summary(), Fmi2Status.ok, "logAll")
            self.log(f"communication steps: {self._steps[0]} compiled, {self._steps[1]} "
                     "through Python", Fmi2Status.ok, "logAll")

    # FMU state: the registered variables plus the model's internal arrays, deep-copied, so a
    # rollback (get state, run, set state, run) reproduces the outputs bit for bit
    def _get_fmu_state(self):
        return self._vouch({"vars": super()._get_fmu_state(),
                            "model": None if self.model is None else self.model.get_state()})

    def _check_state(self, state):
        """A state fits this instance: its layout, its parameters, inputs in range.  Into an
        instance not initialised yet, a state taken after initialisation brings the model its
        parameters build (FMI allows fmi2SetFMUstate from fmi2Instantiate on)."""
        if not isinstance(state, dict) or set(state) != {"vars", "model"}:
            raise StateError("expected the keys ['model', 'vars']")
        same_layout(state["vars"], super()._get_fmu_state(), "vars")
        self._check_structural(state["vars"])
        if state["model"] is None:      # taken before initialisation
            return
        for n in _INPUTS:
            check_value(n, state["vars"][n])
        joint = self.model
        if joint is None:   # the model this instance's parameters and the state's inputs build
            try:
                values = self._param_values()
                values.update({n: state["vars"][n] for n in _INPUTS})
                joint = JointModel(values)
            except (ValueError, ArithmeticError) as e:
                raise StateError(f"this instance's parameters cannot take the state: {e}") from None
        same_layout(state["model"], joint.get_state(), "model")
        try:   # what the model can step, beyond the format
            check_joint_state(state["model"], joint.p, *(state["vars"][n] for n in
                                                         ("theta", "omega", "plunge_speed")))
        except BadState as e:
            raise StateError(f"the state cannot be stepped: {e}") from None

    def _set_fmu_state(self, state):
        if self._needs_check(state):   # before anything changes
            self._check_state(state)
        if state["model"] is None:     # taken before initialisation: back there
            super()._set_fmu_state(state["vars"])
            self.model, self._fast, self._ready = None, None, False
            return
        if self.model is None:         # restored before initialisation: initialise first,
            super()._set_fmu_state(state["vars"])   # at the state's inputs
            self._initialise()
            self._ready = True
        super()._set_fmu_state(state["vars"])
        self.model.set_state(state["model"])   # (copied into the model's own arrays)
        self._fast = None
        if self._fast_args is not None and self.model.started:
            # the compiled step from here (an iterative master's rollback, each step): the
            # state's inputs where it reads them, as the model's step would set them (its
            # operating point is derived again: set_state cleared its key), its outputs
            OP = self._fast_args["op"]
            for name, slot in _OP_SLOTS.items():
                OP[slot] = getattr(self, name)
            self._offer_fast({n: getattr(self, n) for n in self._fast_args["names"]})

    def _advance(self, current_time, step_size):
        self._fast = None
        self._steps[1] += 1
        check_value("shaft_angle", self.shaft_angle)   # an input even when unused
        if self.drive_by_angle:   # the whirl reaches the master's angle at the step's end
            self.omega = omega_by_angle(self.shaft_angle, self.model.rollers[0].whirl_angle,
                                        step_size)
        key = (self.theta, self.omega, self.F_press, self.torque, self.plunge_speed)
        if key != self._checked:       # validate inputs only when they change
            for name, value in zip(_INPUTS, key):
                check_value(name, value)
            self._checked = key
        out = self.model.step(step_size, float(self.theta), float(self.omega),
                              float(self.F_press), float(self.torque), float(self.plunge_speed))
        if not math.isfinite(sum(out.values())):   # one test for every output
            self.log(f"non-finite output at t = {current_time:g} s; step rejected",
                     Fmi2Status.error)
            return False
        for k, v in out.items():
            setattr(self, k, v)
        self._offer_fast(out)
        return True
