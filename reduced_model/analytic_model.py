"""The analytic FMU's model as Python: analytic_kernel.py's init, step and end over its arrays,
run as plain Python, numpy only.  The analytic FMU's binary compiles the same functions
(fmu_src/native_fmu.py); the tests hold it to them (harness/inprocess.py).

traverse = true (default): the reduced traverse model's periodic solution, tabulated over the
whirl angle at the start; once a master moves the inputs, the roller's slide is stepped in time
at the inputs of each step (T4 is an ODE in time, the table its periodic solution).  false:
Eqs. (18)-(27).  Coast runs as drive at the opposite whirl turned 180 deg about the trunnion
axis (docs/model.md, "Coast and reverse whirl").  The whirl angle integrates omega.
"""
from __future__ import annotations

import numpy as np

from . import analytic_kernel as K
from .scene import StepRefused, check_value, validate
from .traverse import params_array

INPUTS = K.INPUT_NAMES[:K.N_KEY]   # the inputs an operating point is derived at


def state_problem(values: dict, st) -> str:
    """Why the state st (AnalyticModel.get_state's) cannot be stepped by a model of the
    parameters ``values`` ('' when it can): kernel.state_problem, every value finite."""
    if not np.all(np.isfinite(st["X"])) or not np.all(np.isfinite(st["IN"])):
        return "the state cannot be stepped: it holds a non-finite value"
    return K.STATE_PROBLEMS[K.state_problem(params_array(values), st["X"])]


class AnalyticModel:
    """n rollers (0, 120, 240 deg) of the reduced model at the inputs of each step.

    values: the parameter table's values for "analytic" (reduced_model.scene), SI units.
    say(text, warning): where the model's messages go (the FMU's log)."""

    def __init__(self, values: dict, say=None):
        self.say = say or (lambda text, warning=False: None)
        self.scene = validate(values, "analytic")     # (the table's ranges, with messages)
        self.T = params_array(self.scene)
        self.IN = np.array([float(self.scene[n]) for n in K.INPUT_NAMES])
        self.X, self.OUT, self.W = np.zeros(K.X_LEN), np.zeros(K.OUT_LEN), np.zeros(K.W_LEN)
        rc = K.init(self.T, self.IN, self.X, self.OUT, self.W)
        if rc == 3:
            raise ValueError(self._notes_text())
        if rc != 1:
            raise ArithmeticError("the start's outputs are not finite")
        self._tell()

    def _notes_text(self):
        return "; ".join(text for _, text in K.notes_text(self.W))

    def _tell(self):
        for level, text in K.notes_text(self.W):
            self.say(text, level == K.WARNING)

    def step(self, dt, current_time, inputs):
        """Advance by dt [s] from current_time [s] at the inputs (INPUT_NAMES: each checked);
        driven by angle, omega is derived (and checked)."""
        for name, value in zip(K.INPUT_NAMES, inputs):
            check_value(name, value)
        IN = np.array(inputs, dtype=float)
        rc = K.step(self.T, IN, self.X, self.OUT, self.W, current_time, dt)
        self.IN = IN
        if rc == 5:
            check_value("omega", IN[K.OMEGA])
        if rc == 3:
            raise StepRefused(self._notes_text())
        if rc == 2:
            raise ArithmeticError("non-finite output; step rejected")
        self._tell()

    def end(self):
        """The run's end: its notes (where the inputs left the checked range, how it ran)."""
        K.end(self.T, self.IN, self.X, self.OUT, self.W)
        self._tell()

    def outputs(self):
        """Every output the analytic FMU has, by name [SI] (regime an int)."""
        out = dict(zip(K.OUTPUT_NAMES, map(float, self.OUT)))
        out["regime"] = int(out["regime"])
        return out

    @property
    def omega(self):
        """The whirl speed of the last step [rad/s] (driven by angle: derived)."""
        return float(self.IN[K.OMEGA])

    # --- state as data -------------------------------------------------------------------
    def get_state(self):
        return {"X": self.X.copy(), "IN": self.IN.copy()}


    def set_state(self, st):
        self.X = np.array(st["X"], dtype=float)
        self.IN = np.array(st["IN"], dtype=float)
