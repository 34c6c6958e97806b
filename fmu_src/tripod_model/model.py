"""The contact model in process: a thin adapter over the FMU's own lifecycle.

``JointModel`` holds lifecycle.py's arrays (the table's values T, the inputs IN, the state X,
the outputs OUT, the work W: fmu_arrays.py) and runs its functions as Python, the kernel
through numba; the FMU's binary compiles the same functions, so a run here is the FMU's run
(tests/test_native_fmu.py).  ``Roller`` is one roller's view of those arrays, for the harness
and the tests that read a roller's state; ``ContactModel`` is a one-roller joint's roller with
its step.
"""
from __future__ import annotations

import math

import numpy as np

from reduced_model import scene as scene_mod
from reduced_model.cfuncs import worded_notes
from reduced_model.scene import OUTPUTS  # noqa: F401  (declared once, with the parameters)
from reduced_model.scene import StepRefused, same_step
from . import fmu_arrays as FA, layout as K, lifecycle as LC, oppoint, roller_setup


_TABLES = {}   # the start's settled tables computed in this process (JointModel._cached_...)


class JointModel:
    """``n_rollers`` (1 or 3) rollers of one joint at whirl phases 0, 120, 240 deg, each in its
    own groove (the paper's one-roller model repeated), on a prescribed or floating spider.

    ``params``: overrides of the contact-model parameter table (SI units), validated here (a
    bad value raises ValueError naming the parameter and its range).  Pressing per roller is
    F_press, or torque / (3 s) when a transmitted torque [N m] is given (torque wins if not 0).
    """

    def __init__(self, params: dict | None = None):
        self.p = p = scene_mod.validate(params, "contact")
        self.T = np.array(roller_setup.params_array(p))
        self.IN = np.array([float(p[n]) for n in FA.INPUT_NAMES])
        self.X, self.OUT, self.W = np.zeros(FA.X_LEN), np.zeros(FA.OUT_LEN), np.zeros(FA.W_LEN)
        if not LC.check_scene(self.T, self.W):      # (validate words these first)
            raise ValueError(self._notes()[0][1])
        LC.setup(self.T, self.X, self.W)
        self.free = p["spider"] == scene_mod.SPIDER_FREE
        self.rollers = [Roller(self, i) for i in range(FA.shape_of(self.T)[0])]

    # --- the lifecycle ---
    def _notes(self):
        """[(level, message)] of the notes the last lifecycle call left (as the FMU logs them)."""
        return worded_notes(self.W, FA.W_NOTES, FA.NOTE_TEXT)

    def _inputs(self, theta, omega, F_press, torque, plunge_speed, shaft_angle=0.0):
        """The inputs where the lifecycle reads them (IN, in INPUT_NAMES' order)."""
        IN = self.IN
        IN[FA.THETA], IN[FA.OMEGA], IN[FA.F_PRESS] = theta, omega, F_press
        IN[FA.TORQUE], IN[FA.PLUNGE_SPEED], IN[FA.SHAFT_ANGLE] = torque, plunge_speed, shaft_angle

    def _cached_start_table(self, keep):
        """The start's settled table (W's traverse-table block, lifecycle.settled_table) shared
        between the models of this process: filled in before a start from one computed for
        the same analytic parameters and inputs (keep False), or kept after one (keep True);
        plain Python computes it in about 0.2 s, which a sweep of models would pay each."""
        IN = self.IN
        slots = [j for j in FA.ANALYTIC_SLOTS if j >= 0]
        key = (self.T[slots].tobytes(), IN[FA.THETA], IN[FA.OMEGA],
               scene_mod.pressing_load(IN[FA.F_PRESS], IN[FA.TORQUE], self.p["s"]),
               IN[FA.PLUNGE_SPEED])
        block = slice(FA.W_PA, FA.W_NW)
        if not keep and key in _TABLES:
            self.W[block] = _TABLES[key]
        elif keep and key not in _TABLES and self.W[FA.W_TKEY + 4] != 0.0:
            if len(_TABLES) >= 16:
                _TABLES.pop(next(iter(_TABLES)))
            _TABLES[key] = self.W[block].copy()

    def step(self, dt, theta, omega, F_press, torque=0.0, plunge_speed=0.0, shaft_angle=0.0):
        """Advance every roller by one communication step dt [s] at these inputs, held over
        the step (theta [rad], omega [rad/s], F_press [N], torque [N m], plunge_speed [m/s];
        driven by angle, shaft_angle [rad] at the step's end: lifecycle.step); returns the
        outputs (layout.OUTPUT_NAMES: roller 1's and the joint's)."""
        self._inputs(theta, omega, F_press, torque, plunge_speed, shaft_angle)
        starts = not self.started
        if starts:
            self._cached_start_table(False)
        rc = LC.step(self.T, self.IN, self.X, self.OUT, self.W, self.X[FA.X_TIME], dt)
        if starts:
            self._cached_start_table(True)
        if rc == 3:
            raise StepRefused(self.refusal())
        if rc == 5:
            raise ValueError(f"omega = {self.IN[FA.OMEGA]!r} from the shaft angle is outside "
                             f"its range {scene_mod.BY_NAME['omega'].range_text()}")
        if rc != 1:
            raise FloatingPointError("the step gave a non-finite output")
        return dict(zip(K.OUTPUT_NAMES, self.OUT.tolist()))

    def initial_outputs(self, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        """The outputs at the start state these inputs give (the FMU's at its start time,
        lifecycle.init), without a step and without moving the model."""
        kept = self.X.copy()
        self._inputs(theta, omega, F_press, torque, plunge_speed)
        self._cached_start_table(False)
        rc = LC.init(self.T, self.IN, self.X, self.OUT, self.W)
        self._cached_start_table(True)
        self.X[:] = kept
        if rc != 1:
            raise FloatingPointError("the start's outputs are not finite")
        return dict(zip(K.OUTPUT_NAMES, self.OUT.tolist()))

    def start(self, theta, omega, F, plunge_speed=0.0):
        """Every roller at its start (lifecycle.start) at these inputs and the pressing load F
        [N] per roller, without a step (the first step otherwise starts them)."""
        self._inputs(theta, omega, F, 0.0, plunge_speed)
        self._cached_start_table(False)
        LC.no_key(self.T, self.X)
        LC.start(self.T, self.IN, self.X, self.W, F)
        self._cached_start_table(True)
        self.X[FA.X_STARTED] = 1.0

    def refusal(self) -> str:
        """Why the last step was refused (the lifecycle's note, as the FMU logs it)."""
        said = [m for level, m in self._notes() if level == FA.ERROR]
        return said[0] if said else "no roller ran out of its budget"

    def summary(self) -> str:
        """One line: the integration steps roller 1 took (lifecycle.end's note)."""
        LC.end(self.T, self.IN, self.X, self.OUT, self.W)
        return self._notes()[0][1]

    # --- what the harness reads ---
    @property
    def started(self):
        """Whether the rollers have taken their first step (a restored state brings its own)."""
        return self.X[FA.X_STARTED] != 0.0

    @property
    def header(self):
        """The OP header row (a joint's inputs; a floating spider's pose and loads)."""
        return self.X[FA.X_OP:FA.X_OP + K.OP_LEN]

    def pressing(self, F_press, torque):
        """Pressing load per roller [N]: torque / (3 s) when torque is not 0, else F_press."""
        return scene_mod.pressing_load(F_press, torque, self.p["s"])

    def state_problem(self, st, theta, omega, plunge_speed=0.0) -> str:
        """Why the state st (get_state's) could not be stepped here at these inputs, as the
        FMU refuses a state a host sets (its layer: every value finite; then
        host_state.state_problem); "" when it can.  The model is not moved."""
        st = np.array(st, dtype=float)
        if not np.isfinite(st).all():
            return "the state holds a non-finite value"
        IN = self.IN.copy()
        IN[FA.THETA], IN[FA.OMEGA], IN[FA.PLUNGE_SPEED] = theta, omega, plunge_speed
        return FA.STATE_PROBLEMS[LC.state_problem(self.T, IN, st, self.W)]

    def get_state(self):
        """A copy of everything a step depends on (the FMU state's X)."""
        return self.X.copy()

    def set_state(self, st) -> None:
        """Set a state get_state took, here or from a model of the same layout and other step
        parameters (a reference at a finer substep): its rollers step at this model's own
        parameters (each roller's P from the table, the values its steps derived kept) and
        derive their operating point again at the next step."""
        self.X[:] = st
        for r in self.rollers:
            derived = r.P[list(oppoint.P_DERIVED)].copy()
            roller_setup.kernel_params(self.T, r.P)
            r.P[list(oppoint.P_DERIVED)] = derived
            r._OP[K.OP_KEY + 4] = math.nan
        self.header[K.OP_KEY + 4] = math.nan


class Roller:
    """Roller ``i`` of a JointModel: views of its rows of the lifecycle's arrays (Y, P, _OP,
    _hs, out; the work _W and the needle row's NW) and what is read of one roller."""

    def __init__(self, joint: JointModel, i: int):
        self.joint, self.p, self.T = joint, joint.p, joint.T
        self.phase = 2.0 * math.pi * i / 3.0
        X, W = joint.X, joint.W
        n, resolved, nn, ns, ny, ys = FA.shape_of(joint.T)
        self.n_needle_bodies = nn
        self.Y = X[FA.X_Y + i * ys:FA.X_Y + i * ys + ny]
        self.P = X[FA.X_P + i * K.P_LEN:FA.X_P + (i + 1) * K.P_LEN]
        r = FA.op_row(n, resolved, i)
        self._OP = X[FA.X_OP + r * K.OP_LEN:FA.X_OP + (r + 1) * K.OP_LEN]
        self._W = FA.work(X, W, i, ny, ys)
        self._L, self._res, self._Y2, self._b, self._hs, self._GW = (
            self._W.L, self._W.res, self._W.Y2, self._W.b, self._W.hs, self._W.GW)
        self.out = X[FA.X_OUTV + i * K.O_LEN:FA.X_OUTV + (i + 1) * K.O_LEN]
        self.NW = FA.needle_work(X, W, i, nn, ns) if resolved else None

    @property
    def time(self):
        return float(self.joint.X[FA.X_TIME])

    @property
    def substeps(self):
        """Substeps taken so far."""
        return int(self._hs[K.H_TAKEN])

    @property
    def whirl_angle(self):
        """This roller's whirl angle now [rad] (its phase included)."""
        return float(self.Y[K.Y_X]) - self.phase

    @property
    def load_ramped(self):
        """Whether a load change moves the pressing offset to its new value over the step
        rather than at once: the needle-resolved bearing's default step (lifecycle.py)."""
        return self.NW is not None and self.p["integrator"] == K.INT_DEFAULT

    @property
    def step_dt(self):
        """The communication step [s] the operating point is set for."""
        return float(self._OP[K.OP_DT])

    # --- what the inputs set (oppoint.py, roller_setup.py: the step's own functions) ---
    def v_st(self, theta, omega):
        """Transition velocity [m/s]: the parameter, or automatic sqrt(A^2+B^2)/4 (model.md)."""
        return oppoint.v_st(self.P, theta, omega)

    def substep(self, theta, omega, F_press, v_st, stiff=True):
        """Substep [s] at these inputs (oppoint.substep)."""
        return oppoint.substep(self.P, theta, omega, F_press, v_st, stiff)

    def pressing_offset(self, F_press):
        """Compulsory displacement: x position of the trunnion axis [m] that gives F_press
        with the roller at the groove bottom (Hertz approach, plus the needle row if any)."""
        return roller_setup.pressing_offset(self.P, self.T, F_press)

    def radial_offset(self, F):
        """Static x offset of the roller from the trunnion axis [m] under a radial load F [N]
        (roller_setup.radial_offset): 0 with the ideal bearing, negative in drive."""
        return roller_setup.radial_offset(self.P, self.T, F)

    def row_bore_radius(self):
        """Radius of the needles' outer race [m] (roller_setup.row_bore_radius)."""
        return roller_setup.row_bore_radius(self.T)

    def set_inputs(self, dt, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        """The inputs and step dt [s] of the next step into this roller's OP
        (lifecycle.set_inputs; a dt within the rounding of the last one is that step)."""
        OP = self._OP
        if OP[K.OP_DT] > 0 and same_step(dt, OP[K.OP_DT], self.time):
            dt = OP[K.OP_DT]
        IN = np.zeros(FA.IN_LEN)
        IN[FA.THETA], IN[FA.OMEGA], IN[FA.F_PRESS] = theta, omega, F_press
        IN[FA.TORQUE], IN[FA.PLUNGE_SPEED] = torque, plunge_speed
        LC.set_inputs(OP, IN, dt)

    # --- the bearing ---
    def bearing_load(self):
        """Radial load carried by the needle row now [N]: along the pressing direction, the sum
        over the needles at the last output (resolved), the row law (lumped), 0 (ideal)."""
        if self.p["bearing"] == K.BEAR_RESOLVED:
            return float(np.sum(self.NW.ND[:, K.D_R1]))
        if self.p["bearing"] != K.BEAR_LUMPED:
            return 0.0
        return oppoint.row_sums(self.P, abs(self.Y[K.Y_E]))[0]

    def needle_loads(self):
        """Needle diagnostics at the last output [N], one row per needle: normal loads on the
        bore, trunnion, neighbours, flange/retainer, and the needle's force on the roller
        along e1, e2, e3 of the trunnion frame (needles.D_*); positions from needle_positions."""
        return self.NW.ND[:self.n_needle_bodies].copy()

    def needle_positions(self):
        """(n, 3) needle centres in the trunnion frame (e1 = pressing direction, e3 = the
        trunnion axis, origin on it at the groove mid-plane) [m]."""
        q = K.Y_LEN + K.N_F * np.arange(self.n_needle_bodies)
        return np.stack([self.Y[q], self.Y[q + 1], self.Y[q + 2]], axis=1)

    def kernel_name(self) -> str:
        """Which kernel steps this roller (for the log)."""
        from . import jit
        return "numba" if jit.HAVE_NUMBA else "plain Python (numba missing or off)"


class ContactModel(Roller):
    """One roller in one groove, trunnion motions as driving constraints (paper section 2): a
    one-roller JointModel's roller, with the joint's step, start and state."""

    def __init__(self, params: dict | None = None):
        super().__init__(JointModel(dict(params or {}, n_rollers=1, spider=0)), 0)

    def step(self, dt, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        """Advance by one communication step dt [s] at these inputs (JointModel.step);
        returns the outputs."""
        return self.joint.step(dt, theta, omega, F_press, torque, plunge_speed)

    def start(self, theta, omega, F_press=0.0, plunge_speed=0.0):
        """The roller at its start at these inputs and the pressing load F_press [N]."""
        self.joint.start(theta, omega, F_press, plunge_speed)

    def initial_outputs(self, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        return self.joint.initial_outputs(theta, omega, F_press, torque, plunge_speed)

    def get_state(self):
        return self.joint.get_state()

    def set_state(self, st) -> None:
        self.joint.set_state(st)
