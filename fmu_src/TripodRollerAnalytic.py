"""pythonfmu slave of the reduced (analytic) thrust model, numpy only: an adapter over
reduced_model.analytic_model.AnalyticModel (reduced_model/analytic_kernel.py's init, step and end as
Python).  The analytic FMU ships the same kernel compiled, under the native FMI layer, without
Python (fmu_src/native_fmu.py); this slave is the reference the tests hold it to (build/reference/TripodRollerAnalytic.fmu).

Same variable names as TripodRoller.fmu where the meaning is the same, so it can replace the
contact FMU when only the thrust excitation is needed.
"""
import numpy as np

from pythonfmu import Fmi2Slave
from pythonfmu.enums import Fmi2Status

from reduced_model import analytic_kernel as K
from reduced_model.analytic_model import AnalyticModel, state_problem
from reduced_model.scene import check_value, params_for
from slavekit import DataState, Guarded, StateError, describe, register, same_layout


@describe
class TripodRollerAnalytic(Guarded, DataState, Fmi2Slave):
    # a state belongs to the parameters it was taken with
    STRUCTURAL = tuple(p.name for p in params_for("analytic") if p.causality != "input")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        register(self)
        self._params = params_for("analytic")
        self.model = None

    def _say(self, text, warning=False):
        if warning:
            self.log(text, Fmi2Status.warning)
        else:
            self.log(text, Fmi2Status.ok, "logAll")

    def _initialise(self):
        self.model = AnalyticModel({p.name: getattr(self, p.name) for p in self._params},
                                   self._say)
        self._write_outputs()   # the outputs at the start time, not their declared zeros

    def _write_outputs(self):
        for name, v in self.model.outputs().items():
            setattr(self, name, v)

    # --- FMU state: the variables and the model's arrays -----------------------------------
    def _get_fmu_state(self):
        st = {"vars": super()._get_fmu_state()}
        st.update(self.model.get_state() if self.model is not None else {"X": None, "IN": None})
        return self._vouch(st)

    def _check_state(self, st):
        """A state fits this instance: its layout, its parameters, a model state the kernel
        can step (reduced_model.analytic_kernel.state_problem), every number finite."""
        if not isinstance(st, dict) or set(st) != {"vars", "X", "IN"}:
            raise StateError("expected the keys ['IN', 'X', 'vars']")
        vars_now = super()._get_fmu_state()
        same_layout(st["vars"], vars_now, "vars")
        self._check_structural(st["vars"])
        try:
            for n in K.INPUT_NAMES:
                check_value(n, st["vars"][n])
        except ValueError as e:
            raise StateError(str(e)) from None
        if st["X"] is None and st["IN"] is None:     # taken before initialisation
            return
        for key, n in (("X", K.X_LEN), ("IN", K.IN_LEN)):
            a = st[key]
            if not (isinstance(a, np.ndarray) and a.dtype == np.float64 and a.shape == (n,)):
                raise StateError(f"{key}: expected {n} float64 values")
        why = state_problem({p.name: getattr(self, p.name) for p in self._params}, st)
        if why:
            raise StateError(why)
        try:
            for n, v in zip(K.INPUT_NAMES, st["IN"]):
                check_value(n, float(v))
        except ValueError as e:
            raise StateError(str(e)) from None

    def _set_fmu_state(self, state):
        if self._needs_check(state):   # before anything changes
            self._check_state(state)
        super()._set_fmu_state(state["vars"])
        if state["X"] is None:          # taken before initialisation: back there
            self.model, self._ready = None, False
            return
        if self.model is None:          # restored before initialisation: initialise first
            self._initialise()
            self._ready = True
        self.model.set_state(state)

    def terminate(self):
        if self.model is not None:
            self.model.end()

    # --- a step --------------------------------------------------------------------------
    def _advance(self, current_time, step_size):
        try:
            self.model.step(step_size, current_time,
                            tuple(getattr(self, n) for n in K.INPUT_NAMES))
        finally:
            if self.drive_by_angle:          # the step's whirl, derived from the shaft angle
                self.omega = self.model.omega
        self._write_outputs()
        return True
