"""pythonfmu slave of the reduced (analytic) thrust model, numpy only: an adapter over
reduced_model.analytic_model.AnalyticModel (the table or march, coast, the outputs).

Same variable names as TripodRoller.fmu where the meaning is the same, so it can replace the
contact FMU when only the thrust excitation is needed.

Steps run compiled, without entering Python (the native layer's fast path):
resources/_analytic_step.so, built from fmu_src/native/analytic_step.c with the FMU, does what
the model's step does, bit for bit (tests/test_fast.py): at unchanged inputs the table's
interpolation (or Eqs. 18-27), once the inputs moved the march at each step's inputs.
"""
import ctypes
import math
import os

from pythonfmu import DefaultExperiment, Fmi2Slave
from pythonfmu.enums import Fmi2Status

from reduced_model import switches
from reduced_model.analytic_model import INPUTS as _INPUTS, STATE_KEYS, AnalyticModel
from reduced_model.scene import (CONTACT_ONLY_OUTPUTS, MAX_SUBSTEPS, OUTPUTS, compiled_bounds,
                                 check_value, params_for, same_value, validate)
from slavekit import (DataState, FastStep, Guarded, StateError, omega_by_angle,
                      register_table, same_layout)

# outputs the reduced model defines (no contact point, no roller spin state)
_OUT = tuple(n for n, _, _ in OUTPUTS if n not in CONTACT_ONLY_OUTPUTS)
FAST_LIB = "_analytic_step.so"    # in resources/, from fmu_src/native/analytic_step.c

# the inputs the compiled steps take from the native layer: the model's, and the shaft angle
# (held for the layer, which derives omega from it when the whirl is driven by angle)
_FAST_INPUTS = _INPUTS + ("shaft_angle",)


def _fast_library(resources):
    """(library, step function's address, OP names, output names, march function's address,
    its OP names, its per-roller state names) of the compiled steps, or None (not built into
    this FMU, or TRIPOD_FAST=0 turns it off, for comparison).  The slave keeps the library
    object: the addresses are valid while it is loaded."""
    if not switches.FAST or not resources:
        return None
    try:
        lib = ctypes.CDLL(os.path.join(resources, FAST_LIB))
        layout = ctypes.cast(lib.tripod_analytic_layout, ctypes.CFUNCTYPE(ctypes.c_char_p))()
        address = ctypes.cast(lib.tripod_analytic_step, ctypes.c_void_p).value
        march = ctypes.cast(lib.tripod_analytic_march, ctypes.c_void_p).value
    except (OSError, AttributeError):
        return None
    op, out, mop, state = (part.split() for part in layout.decode().split("|"))
    return lib, address, op, out, march, mop, state


class TripodRollerAnalytic(Guarded, DataState, Fmi2Slave):
    author = "tripod-thrust"
    description = ("Reduced (analytic) thrust model of one tripod-joint roller: sliding "
                   "velocities v1 + v2 (Eqs. 18-24), tanh friction, ftz = ft sin(phi), the "
                   "roller spin-inertia thrust and (traverse = true) the roller's slide across "
                   "the groove with micro-slip. Needs numpy only.")
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.2, step_size=1e-4)
    # a state belongs to the parameters it was taken with
    STRUCTURAL = tuple(p.name for p in params_for("analytic") if p.causality != "input")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self._params = register_table(self, "analytic", _OUT)
        self.model = None
        self._fast = None  # the compiled step offered to the native layer
        self._fast_lib = False   # not looked up yet
        self._fast_table = False  # the table whose rows _fast_rows holds

    def _say(self, text, warning=False):
        if warning:
            self.log(text, Fmi2Status.warning)
        else:
            self.log(text, Fmi2Status.ok, "logAll")

    def _initialise(self):
        self.model = AnalyticModel({p.name: getattr(self, p.name) for p in self._params},
                                   self._say)
        self.model.plunge = self.plunge
        self._fast = None
        self._steps = [0, 0]       # communication steps compiled, through Python (the log)
        self._write_outputs()   # the outputs at the start time, not their declared zeros

    def _inputs(self):
        return tuple(getattr(self, n) for n in _INPUTS)

    def _write_outputs(self):
        for name, v in self.model.outputs().items():
            setattr(self, name, v)

    # --- FMU state: the variables and the model's state, as data ---------------------------
    def _get_fmu_state(self):
        st = {"vars": super()._get_fmu_state()}
        st.update(self.model.get_state() if self.model is not None else
                  {"x": [0.0], "dt": None, "scene": None, "march": None, "span": None})
        return self._vouch(st)

    def _check_state(self, st):
        """A state fits this instance: its layout, its parameters, one whirl angle (and one
        march row of five outputs) a roller, every number finite, inputs in range.  Into an
        instance not initialised yet, a state taken after initialisation is checked against
        the scene this instance's parameters make (FMI allows fmi2SetFMUstate from
        fmi2Instantiate on)."""
        keys = {"vars", *STATE_KEYS}
        if not isinstance(st, dict) or set(st) != keys:
            raise StateError(f"expected the keys {sorted(keys)}")
        vars_now = super()._get_fmu_state()
        same_layout(st["vars"], vars_now, "vars")
        self._check_structural(st["vars"])
        if st["scene"] is None:        # taken before initialisation
            same_layout(st, {"vars": vars_now, "x": [0.0], "dt": None, "scene": None,
                             "march": None, "span": None})
            return
        for n in _INPUTS:
            check_value(n, st["vars"][n])
        scene = self.model.scene if self.model is not None else None
        if scene is None:   # the scene this instance's parameters and the state's inputs make
            try:
                values = {p.name: getattr(self, p.name) for p in self._params}
                values.update({n: st["vars"][n] for n in _INPUTS})
                scene = validate(values, "analytic")
            except ValueError as e:
                raise StateError(f"this instance's parameters cannot take the state: {e}") \
                    from None
        same_layout(st["scene"], scene, "scene")
        for n in self.STRUCTURAL:
            if st["scene"].get(n, scene.get(n)) != scene.get(n):
                raise StateError(f"state taken with another {n} than this instance's")
        for n in _INPUTS:
            check_value(n, st["scene"][n])
        n = scene["n_rollers"]
        same_layout(st["x"], [0.0] * n, "x")
        if st["dt"] is not None:
            same_layout(st["dt"], 1.0, "dt")
        if st["march"] is not None:
            for i, m in enumerate(st["march"] if isinstance(st["march"], list) else [None]):
                if not (isinstance(m, list) and len(m) == 3):
                    raise StateError(f"march[{i}]: expected [slip, p, outputs]")
                if m[0] is not None:
                    same_layout(m[0], 0.0, f"march[{i}][0]")
                same_layout(m[1], 0.0, f"march[{i}][1]")
                # p is the friction's share along the slide: |p| <= mu_groove (T3)
                if not abs(m[1]) <= scene["mu_groove"]:
                    raise StateError(f"march[{i}][1]: p = {m[1]!r} outside the allowed range "
                                     f"[-mu_groove, mu_groove] = [-{scene['mu_groove']:g}, "
                                     f"{scene['mu_groove']:g}]")
                if m[2] is not None:
                    same_layout(m[2], [0.0] * 5, f"march[{i}][2]")
            if len(st["march"]) != n:
                raise StateError(f"march: expected {n} rows, one a roller")
        if st["span"] is not None:
            same_layout(st["span"], [[0.0] * 3, [0.0] * 3], "span")

    def _set_fmu_state(self, state):
        if self._needs_check(state):   # before anything changes
            self._check_state(state)
        if state["scene"] is None:     # taken before initialisation: back there
            super()._set_fmu_state(state["vars"])
            self.model = None
            self._fast, self._ready = None, False
            return
        if self.model is None:         # restored before initialisation: initialise first,
            super()._set_fmu_state(state["vars"])   # at the state's inputs
            self._initialise()
            self._ready = True
        super()._set_fmu_state(state["vars"])
        self.model.set_state(state, self.plunge)
        self._fast = None      # the next step through Python (it may prepare the model anew)

    def terminate(self):
        if self.model is None:
            return
        outside = self.model.outside_run()
        if outside:
            self.log("during the run the inputs left the range the traverse model was "
                     "checked against the contact model in (docs/validation.md): "
                     + "; ".join(outside), Fmi2Status.warning)
        # how the steps ran, for a user who checks
        self.log(f"communication steps: {self._steps[0]} compiled, {self._steps[1]} "
                 f"through Python; traverse tables derived: {self.model.tables}"
                 + ("; the slide stepped in time since the inputs moved"
                    if self.model.march is not None else ""),
                 Fmi2Status.ok, "logAll")

    # --- a step through Python ---------------------------------------------------------------
    def _advance(self, current_time, step_size):
        self._fast = None
        self._steps[1] += 1
        check_value("shaft_angle", self.shaft_angle)   # an input even when unused
        if self.drive_by_angle:   # the whirl reaches the master's angle at the step's end
            self.omega = omega_by_angle(self.shaft_angle, self.model.x[0], step_size)
        self.model.step(step_size, current_time, self._inputs())
        self._write_outputs()
        self._offer_fast()
        return True

    # --- the compiled steps (analytic_step.c) ------------------------------------------------
    def _offer_fast(self):
        """After a step through Python: the compiled step for the next steps (at these inputs,
        or the march's at any; any step size), with its arrays (the native layer's _fast)."""
        if self._fast_lib is False:
            self._fast_lib = _fast_library(self.resources)
        m = self.model
        if self._fast_lib is None or len(m.x) > 3:
            return
        if m.march is None and (m.mirror or m.scene["omega"] < 0):
            return          # (the table runs drive at forward whirl; the march any)
        import numpy as np
        if m.march is not None:
            _, _, _, out_names, address, op_names, state_names = self._fast_lib
            got = m.fast_march_op(self._inputs())
            if got is None:
                return
            rows, op = got
            assert len(state_names) == len(rows[0])
            self._fast_state = np.array(rows, dtype=float).ravel()
            second = self._fast_state
        else:
            _, address, op_names, out_names = self._fast_lib[:4]
            rows, op = m.fast_table_op()
            if self._fast_table is not m.table:    # the table's rows, once per operating point
                self._fast_table = m.table
                self._fast_rows = np.array(rows)
            second = self._fast_rows
        self._fast_op = np.array([op[n] for n in op_names], dtype=float)
        # where the native layer writes each input: the march's OP (at the table, none: new
        # values go to _fast_inputs), the shaft angle where the layer keeps it for driving by
        # angle (it derives omega from it, as _advance)
        self._fast_shaft = np.zeros(1)
        slots = []
        for name in _FAST_INPUTS:
            lo, hi, lo_open, hi_open = compiled_bounds(name, m.scene, m.march is not None)
            at = (self._fast_shaft.ctypes.data if name == "shaft_angle" else
                  self._fast_op.ctypes.data + 8 * op_names.index(name) if m.march is not None
                  else 0)
            slots.append((at, -math.inf if lo is None else float(lo),
                          math.inf if hi is None else float(hi), int(lo_open), int(hi_open)))
        self._fast_x = np.array(m.x)
        self._fast_out = np.array([getattr(self, n) for n in out_names])
        # the step's argument: these arrays' addresses
        self._fast_argv = np.array([a.ctypes.data for a in (self._fast_x, second, self._fast_op,
                                                            self._fast_out)], dtype=np.uintp)
        vr = {v.name: ref for ref, v in self.vars.items()}
        self._fast_names = out_names
        # where both steps take the step size: a master's new one is written there
        self._fast_dt_at = op_names.index("dt")
        by_angle = ((vr["shaft_angle"], vr["omega"], list(out_names).index("whirl_angle"))
                    if self.drive_by_angle else ())
        self._fast = FastStep(address, self._fast_argv.ctypes.data, self._fast_out.ctypes.data,
                              m.dt, [vr[n] for n in out_names], [vr[n] for n in _FAST_INPUTS],
                              [float(getattr(self, n)) for n in _FAST_INPUTS], tuple(slots),
                              self._fast_op.ctypes.data + 8 * self._fast_dt_at, by_angle)

    def _fast_sync(self, k, elapsed):
        """The native layer took k compiled steps (over elapsed [s]): take their whirl angles
        and outputs (and the march's state and the inputs its operating point was derived
        for)."""
        self._steps[0] += k
        m = self.model
        m.dt = float(self._fast_op[self._fast_dt_at])   # the last step's size
        state = None
        if m.march is not None:
            state = self._fast_state.reshape(len(m.march), -1).tolist()
        m.fast_synced(self._fast_x, state,
                      {n: float(v) for n, v in zip(self._fast_lib[5], self._fast_op)}
                      if state is not None else None)
        for name, v in zip(self._fast_names, self._fast_out):
            setattr(self, name, float(v))
        m.plunge = self.plunge

    def _fast_inputs(self, values):
        """The master set inputs (_FAST_INPUTS order; omega derived by the layer when driven
        by angle) while the fast path ran: take them as setReal would.  Once the slide is
        stepped in time the compiled march takes them (the native layer wrote them into its
        OP: True); at the start's table, inputs moved only by rounding keep the table (as the
        model's prepare does: True), others start the march in Python."""
        for name, v in zip(_FAST_INPUTS, values):
            setattr(self, name, v)
        m = self.model
        return m.march is not None or (m.key is not None and
                                       all(map(same_value, values[:len(_INPUTS)], m.key)))

    def _fast_failed(self, current_time, code):
        """A compiled step failed (2: a non-finite output; 4: a step longer than MAX_SUBSTEPS
        substeps, refused before it started)."""
        if code == 4:
            self.log(f"step refused at t = {current_time:g} s: the communication step needs "
                     f"more than the {MAX_SUBSTEPS:.0f} substeps one step may take: take "
                     "shorter communication steps", Fmi2Status.error)
            return
        why = "non-finite output" if code == 2 else f"the compiled step returned {code}"
        self.log(f"{why} at t = {current_time:g} s; step rejected", Fmi2Status.error)
