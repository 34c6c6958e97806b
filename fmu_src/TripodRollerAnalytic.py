"""pythonfmu slave of the reduced (analytic) thrust model: numpy only.

traverse = true (default): the reduced traverse model's periodic solution, tabulated over the
whirl angle at the start (reduced_model/traverse.py); once a master moves the inputs, the
roller's slide is stepped in time at the inputs of each step (Traverse.march: T4 is an ODE in
time, the table its periodic solution), where a new table took 0.05 s or more a step.  false:
Eqs. (18)-(27).
Same variable names as TripodRoller.fmu where the meaning is the same, so it can replace the
contact FMU when only the thrust excitation is needed.  The whirl angle integrates omega.

Steps run compiled, without entering Python (the native layer's fast path):
resources/_analytic_step.so, built from fmu_src/native/analytic_step.c with the FMU, does what
_advance does, bit for bit (tests/test_fast.py): at unchanged inputs the table's interpolation
(or Eqs. 18-27), once the inputs moved the march at each step's inputs.
"""
import copy
import ctypes
import math
import os

from pythonfmu import DefaultExperiment, Fmi2Slave
from pythonfmu.enums import Fmi2Status

from reduced_model.housing import housing_forces
from reduced_model.scene import (ANALYTIC_LOWER, BY_NAME, CONTACT_ONLY_OUTPUTS, OUTPUTS,
                                 REGIME_CODES, check_value, params_for,
                                 pressing_load, same_step, same_value, validate)
from reduced_model.thrust import Thrust
from reduced_model.traverse import (INERTIA, Traverse, inertia_ratio, outside_checked,
                                    outside_span)
from slavekit import DataState, Guarded, StateError, register_table, same_layout

_INPUTS = ("theta", "omega", "F_press", "torque", "plunge_speed")
# outputs the reduced model defines (no contact point, no roller spin state)
_OUT = tuple(n for n, _, _ in OUTPUTS if n not in CONTACT_ONLY_OUTPUTS)
FAST_LIB = "_analytic_step.so"    # in resources/, from fmu_src/native/analytic_step.c


def _fast_library(resources):
    """(library, step function's address, OP names, output names, march function's address,
    its OP names, its per-roller state names) of the compiled steps, or None (not built into
    this FMU, or TRIPOD_FAST=0 turns it off, for comparison).  The slave keeps the library
    object: the addresses are valid while it is loaded."""
    if os.environ.get("TRIPOD_FAST", "1") == "0" or not resources:
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
        self._scene = None
        self._x = [0.0]   # whirl angle of each roller [rad]
        self._dt = None   # the communication step taken [s] (same_step)
        self._fast = None  # the compiled step offered to the native layer
        self._fast_lib = False   # not looked up yet
        self._fast_table = False  # the table whose rows _fast_rows holds
        self._march = None   # per roller [s, p, outputs] once the inputs moved (Traverse.march)
        self._span = None    # (a state may be taken before initialisation)

    def _initialise(self):
        self._scene = validate({p.name: getattr(self, p.name) for p in self._params}, "analytic")
        n = self._scene["n_rollers"]
        self._x = [2.0 * math.pi * i / 3.0 for i in range(n)]   # rollers at 0, 120, 240 deg
        self._key = None
        self._thrust = None
        self._table = None
        self._dt = None
        self._fast = None
        self._steps = [0, 0]       # communication steps compiled, through Python (the log)
        self._tables = 0           # traverse tables derived (the log)
        self._march = None
        self._op = None            # the operating point march steps at
        self._span = None          # lowest and highest theta, omega, pressing load of the run
        self._prepare()
        self._write_outputs()   # the outputs at the start time, not their declared zeros

    def _prepare(self):
        """Check the inputs and, when the operating point changed, re-derive the constants:
        at initialisation the traverse model's settled table (about 0.05 s at the paper's
        scene), on an input change the operating point its slide is stepped at."""
        key = (self.theta, self.omega, self.F_press, self.torque, self.plunge_speed)
        # inputs moved only in their last bits (a master interpolating an input table) keep
        # the operating point, the table and the compiled steps
        if self._key is not None and all(map(same_value, key, self._key)):
            return
        self._take_inputs(key)
        sc = self._inner()
        loaded = sc["mu_groove"] > 0 and pressing_load(sc["F_press"], sc["torque"], sc["s"]) > 0
        applies = sc["traverse"] and sc["omega"] > 0 and loaded
        if not sc["traverse"]:
            self._table, self.regime = None, 0
        elif self._key is None and self._march is None and sc["omega"] < 0 and loaded:
            # reverse whirl (or coast at forward whirl) from the start: no periodic table in
            # that sense; the slide is stepped in time from rest
            self._table, self.regime = None, 0
            self._march = [[None, 0.0, None] for _ in self._x]
            self._op = Traverse(sc, periodic=False)
        elif self._key is None and self._march is None:
            # the start (or a restored state from before the inputs moved): the settled table
            self._table = None
            self.regime = 0
            if applies:
                self._table = Traverse(sc)
                self.regime = REGIME_CODES.index(self._table.regime())
                self._tables += 1
                outside = outside_checked(sc)
                if outside:
                    self.log("the scene is outside the range the traverse model was checked "
                             "against the contact model in (docs/validation.md): "
                             + "; ".join(outside), Fmi2Status.warning)
                if not self._table.settled:
                    self.log(f"the traverse table at theta = {sc['theta']:.6g} rad, omega = "
                             f"{sc['omega']:.6g} rad/s is not periodic: s(2 pi) - s(0) = "
                             f"{self._table.mismatch:.2e} m/s after {self._table.cycles} "
                             "cycles of the cycle map; its outputs are the best cycle run",
                             Fmi2Status.warning)
        else:
            # the inputs moved: the slide is stepped in time from where the table had it
            if self._march is None:
                self._march = [list(self._table.state_at(self._at(x))) + [None]
                               if self._table is not None else [None, 0.0, None]
                               for x in self._x]
                self.log("the inputs moved: from here on the traverse model steps the "
                         "roller's slide in time at each step's inputs (no new settled table; "
                         "regime stays that of the start)", Fmi2Status.ok, "logAll")
            self._table = None
            self._op = Traverse(sc, periodic=False)
        self._key = key

    def _take_inputs(self, key):
        """Check the inputs key (_INPUTS order) and make them the scene's."""
        for name, value in zip(_INPUTS, key):
            check_value(name, value)
        for name, value in zip(_INPUTS, key):
            self._scene[name] = float(value)
        self._thrust = Thrust(self._inner())
        sc = self._scene
        now = (sc["theta"], abs(sc["omega"]),
               abs(pressing_load(sc["F_press"], sc["torque"], sc["s"])))
        self._widen_span(now, now)

    # --- coast: drive at the opposite whirl, turned 180 deg about the trunnion axis ------------
    # (docs/model.md, "Coast and reverse whirl": x -> -x, z -> -z; Fx, Fz, Fz_mod, the whirl
    # angle and the plunge speed flip, Fy and the slip do not)
    @property
    def _mirror(self):
        sc = self._scene
        return sc is not None and pressing_load(sc["F_press"], sc["torque"], sc["s"]) < 0

    def _inner(self):
        """The scene the reduced model runs: the inputs, or for coast the drive scene whose
        turn it is."""
        sc = self._scene
        if not self._mirror:
            return sc
        return dict(sc, omega=-sc["omega"], F_press=-sc["F_press"], torque=-sc["torque"],
                    plunge_speed=-sc["plunge_speed"])

    def _at(self, x):
        """The reduced model's whirl angle for the roller's angle x [rad]."""
        return -x if self._mirror else x

    def _outer(self, Fz, Fz_mod, Fx, Fy, slip):
        """The reduced model's outputs (Fz, Fz_mod, Fx, Fy [N], slip speed [m/s]) as the
        joint's: turned back for coast."""
        if self._mirror:
            return -Fz, -Fz_mod, -Fx, Fy, slip
        return Fz, Fz_mod, Fx, Fy, slip

    def _widen_span(self, lows, highs):
        """The span of the inputs over the run (theta [rad], omega [rad/s], pressing load [N]):
        what terminate compares with where the traverse model was checked."""
        if self._span is None:
            self._span = [list(lows), list(highs)]
        else:
            self._span = [list(map(min, self._span[0], lows)),
                          list(map(max, self._span[1], highs))]

    def _get_fmu_state(self):
        return {"vars": super()._get_fmu_state(), "x": list(self._x), "dt": self._dt,
                "scene": copy.deepcopy(self._scene), "march": copy.deepcopy(self._march),
                "span": copy.deepcopy(self._span)}

    def _check_state(self, st):
        """A state fits this instance: its layout, its parameters, one whirl angle (and one
        march row of five outputs) a roller, every number finite, inputs in range.  Into an
        instance not initialised yet, a state taken after initialisation is checked against
        the scene this instance's parameters make (FMI allows fmi2SetFMUstate from
        fmi2Instantiate on)."""
        keys = {"vars", "x", "dt", "scene", "march", "span"}
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
        scene = self._scene
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
                if m[2] is not None:
                    same_layout(m[2], [0.0] * 5, f"march[{i}][2]")
            if len(st["march"]) != n:
                raise StateError(f"march: expected {n} rows, one a roller")
        if st["span"] is not None:
            same_layout(st["span"], [[0.0] * 3, [0.0] * 3], "span")

    def _set_fmu_state(self, state):
        self._check_state(state)       # before anything changes
        if state["scene"] is None:     # taken before initialisation: back there
            super()._set_fmu_state(state["vars"])
            self._scene, self._x, self._dt, self._march, self._span = None, [0.0], None, None, None
            self._fast, self._ready = None, False
            return
        if self._scene is None:        # restored before initialisation: initialise first,
            super()._set_fmu_state(state["vars"])   # at the state's inputs
            self._initialise()
            self._ready = True
        super()._set_fmu_state(state["vars"])
        self._x = list(state["x"])
        self._dt = state["dt"]
        march = copy.deepcopy(state["march"])
        if state["scene"] != self._scene or (march is None) != (self._march is None):
            self._key = None        # else the table or march's operating point stays
            self._table = None
        self._march = march
        self._scene = copy.deepcopy(state["scene"])
        self._span = copy.deepcopy(state["span"])

    def terminate(self):
        if self._march is not None and self._scene["traverse"]:
            (t0, w0, f0), (t1, w1, f1) = self._span
            # the roller's inertia at its worst: the highest whirl on the lowest load
            sc = dict(self._scene, omega=w1, F_press=f0, torque=0.0)
            worst = inertia_ratio(sc)
            outside = [p for p in (outside_span("theta", math.degrees(t0), math.degrees(t1)),
                                   outside_span("whirl", w0 / (2 * math.pi), w1 / (2 * math.pi)),
                                   outside_span("pressing load", f0, f1),
                                   outside_span(INERTIA, worst, worst)) if p]
            if outside:
                self.log("during the run the inputs left the range the traverse model was "
                         "checked against the contact model in (docs/validation.md): "
                         + "; ".join(outside), Fmi2Status.warning)
        if self._scene is not None:   # how the steps ran, for a user who checks
            self.log(f"communication steps: {self._steps[0]} compiled, {self._steps[1]} "
                     f"through Python; traverse tables derived: {self._tables}"
                     + ("; the slide stepped in time since the inputs moved"
                        if self._march is not None else ""),
                     Fmi2Status.ok, "logAll")

    def _advance(self, current_time, step_size):
        self._fast = None
        self._steps[1] += 1
        check_value("shaft_angle", self.shaft_angle)   # an input even when unused
        if self.drive_by_angle:   # the whirl reaches the master's angle at the step's end
            self.omega = (self.shaft_angle - self._x[0]) / step_size
        self._prepare()
        # a step that differs from the last one by the rounding of the master's times is
        # that step, as on the compiled path
        if self._dt is None or not same_step(step_size, self._dt, current_time):
            self._dt = step_size
        if self._march is not None and self._op is not None:
            for i, m in enumerate(self._march):
                m[0], m[1], x, m[2] = self._op.march(m[0], m[1], self._at(self._x[i]),
                                                     self._dt)
                self._x[i] = self._at(x)
        else:
            w = self._scene["omega"] * self._dt
            for i in range(len(self._x)):
                self._x[i] += w
        self.plunge = self.plunge + self._scene["plunge_speed"] * self._dt   # held speed
        self._write_outputs()
        self._offer_fast()
        return True

    def _offer_fast(self):
        """After a step through Python: the compiled step (analytic_step.c) for the next steps
        at these inputs and this step size, with its arrays (the native layer's _fast)."""
        if self._fast_lib is False:
            self._fast_lib = _fast_library(self.resources)
        if self._fast_lib is None or len(self._x) > 3 or self.drive_by_angle or \
                self._mirror or self._scene["omega"] < 0:
            return          # (driven by angle: omega is derived each step, in Python; the
            #                  compiled steps do drive at forward whirl)
        if self._march is not None:
            self._offer_march()
            return
        import numpy as np
        _, address, op_names, out_names = self._fast_lib[:4]
        if self._fast_table is not self._table:    # the table's rows, once per operating point
            self._fast_table = self._table
            self._fast_rows = np.array(self._table._rows if self._table is not None
                                       else [[0.0] * 5] * 2)
        sc, th = self._scene, self._thrust
        op = {"w": sc["omega"] * self._dt, "n_rollers": len(self._x),
              "F": pressing_load(sc["F_press"], sc["torque"], sc["s"]),
              "table": float(self._table is not None),
              "scale": self._table._scale if self._table is not None else 0.0,
              "n": self._table.n if self._table is not None else 0,
              "A": th.A, "B": th.B, "muF": th.muF, "k": th.k, "th": th.th, "kspin": th.kspin,
              "s": sc["s"], "vp": th.vp, "vpdt": sc["plunge_speed"] * self._dt}
        self._fast_op = np.array([op[n] for n in op_names], dtype=float)
        self._offer(address, self._fast_rows, out_names, ())

    def _offer(self, address, second, out_names, slots):
        """The native layer's _fast: the step at address over (whirl angles, second, OP,
        outputs); slots: where it writes each input (none: new inputs go to _fast_inputs)."""
        import numpy as np
        self._fast_x = np.array(self._x)
        self._fast_out = np.array([getattr(self, n) for n in out_names])
        arrays = (self._fast_x, second, self._fast_op, self._fast_out)
        addresses = [a.ctypes.data for a in arrays] + [self._fast_x.ctypes.data] * 10
        vr = {v.name: ref for ref, v in self.vars.items()}
        self._fast_names = out_names
        self._fast = (address, self._dt, [vr[n] for n in out_names], [vr[n] for n in _INPUTS],
                      [float(getattr(self, n)) for n in _INPUTS], addresses) + \
            ((slots,) if slots else ())

    def _offer_march(self):
        """Once the inputs moved: the compiled march (analytic_step.c: Traverse.march with the
        operating point derived from the inputs, which the native layer checks against their
        ranges and writes into the march's OP), so a master's new inputs every step stay off
        Python too."""
        if self._op is None or any(m[0] is None or m[2] is None for m in self._march):
            return              # (the march starts at rest: its first step in Python)
        import numpy as np
        _, _, _, out_names, address, mop_names, state_names = self._fast_lib
        sc, op = self._scene, self._op
        # the inputs as the master left them, and those the operating point is derived for
        mop = {n: float(getattr(self, n)) for n in _INPUTS}
        mop.update({"key_" + n: float(v) for n, v in zip(_INPUTS, self._key)})
        mop.update(dt=self._dt, n_rollers=len(self._x), n=op.n, mu=op.mu, v_st=sc["v_st"],
                   K=op.K, a1=op.a1, clear=op.clear, r=op.r, s=sc["s"], I=op.inertia,
                   pitch=float(sc["pitch"]), roll=float(sc["roll"]), spin_moment=float(op._sm))
        (mop["theta_lo"], mop["omega_lo"], mop["load_lo"]), \
            (mop["theta_hi"], mop["omega_hi"], mop["load_hi"]) = self._span
        self._fast_state = np.array([[m[0], m[1]] + list(m[2]) for m in self._march],
                                    dtype=float).ravel()
        assert len(state_names) == 2 + len(self._march[0][2])
        self._fast_op = np.array([mop[n] for n in mop_names], dtype=float)
        # where the native layer writes each input (the march's OP) and its allowed range
        slots = []
        for name in _INPUTS:
            p = BY_NAME[name]
            lo = ANALYTIC_LOWER.get(name, p.lo)    # drive and forward whirl only
            slots.append((self._fast_op.ctypes.data + 8 * mop_names.index(name),
                          -math.inf if lo is None else float(lo),
                          math.inf if p.hi is None else float(p.hi),
                          int(p.lo_open), int(p.hi_open)))
        self._offer(address, self._fast_state, out_names, slots)

    def _fast_sync(self, k):
        """The native layer took k compiled steps: take their whirl angles and outputs (and
        the march's state and the inputs its operating point was derived for)."""
        self._steps[0] += k
        self._x = [float(v) for v in self._fast_x]
        for name, v in zip(self._fast_names, self._fast_out):
            setattr(self, name, float(v))
        if self._march is not None:
            state = self._fast_state.reshape(len(self._march), -1).tolist()
            for m, row in zip(self._march, state):
                m[0], m[1], m[2] = row[0], row[1], tuple(row[2:])
            names = self._fast_lib[5]
            at = {n: float(v) for n, v in zip(names, self._fast_op)}
            self._widen_span([at[n + "_lo"] for n in ("theta", "omega", "load")],
                             [at[n + "_hi"] for n in ("theta", "omega", "load")])
            key = tuple(at["key_" + n] for n in _INPUTS)
            if key != tuple(map(float, self._key)):
                self._take_inputs(key)
                self._op = Traverse(self._scene, periodic=False)
                self._key = key

    def _fast_inputs(self, values):
        """The master set inputs (_INPUTS order) while the fast path ran: take them as setReal
        would.  Once the slide is stepped in time the compiled march takes them (the native
        layer wrote them into its OP: True); at the start's table, inputs moved only by
        rounding keep the table (as _prepare does: True), others start the march in Python."""
        for name, v in zip(_INPUTS, values):
            setattr(self, name, v)
        return self._march is not None or (self._key is not None and
                                           all(map(same_value, values, self._key)))

    def _fast_failed(self, current_time, code):
        """A compiled step failed (2: a non-finite output)."""
        why = "non-finite output" if code == 2 else f"the compiled step returned {code}"
        self.log(f"{why} at t = {current_time:g} s; step rejected", Fmi2Status.error)

    def _write_outputs(self):
        """Every output at the rollers' present whirl angles self._x [rad]."""
        F = pressing_load(self._scene["F_press"], self._scene["torque"], self._scene["s"])
        fz, fx, fy = [], [], []
        if self._march is not None and self._march[0][2] is not None:
            for i, m in enumerate(self._march):
                r = self._outer(*m[2])
                if i == 0:
                    Fz, Fz_mod, Fx, Fy, slip = r
                fz.append(r[0])
                fx.append(r[2])
                fy.append(r[3])
            self.Fz, self.Fz_mod, self.Fx, self.Fy = Fz, Fz_mod, Fx, Fy
            self.dFx = Fx - F
            self.slip_speed = slip
        elif self._table is not None:
            at = self._table.at
            for i, x in enumerate(self._x):
                r = self._outer(*at(self._at(x)))
                if i == 0:
                    Fz, Fz_mod, Fx, Fy, slip = r
                fz.append(r[0])
                fx.append(r[2])
                fy.append(r[3])
            self.Fz, self.Fz_mod, self.Fx, self.Fy = Fz, Fz_mod, Fx, Fy
            self.dFx = Fx - F
            self.slip_speed = slip
        else:
            at = self._thrust.at
            sign = -1.0 if self._mirror else 1.0
            for i, x in enumerate(self._x):
                r = at(self._at(x))
                if i == 0:
                    _, _, ft, V, phi, _ = r
                fz.append(sign * r[0])
                fx.append(F)
                fy.append(r[2] * math.cos(r[4]))
            self.Fz = fz[0]
            self.Fy = ft * math.cos(phi)
            self.Fx = F
            self.dFx = 0.0
            self.Fz_mod = self.Fz          # Fx = F_press in Eqs. (18)-(27)
            self.slip_speed = abs(V)
        total = 0.0   # in order, as analytic_step.c (sum() compensates from Python 3.12 on)
        for v in fz:
            total += v
        self.Fz_joint = total
        self.Fz_2 = fz[1] if len(fz) > 1 else 0.0
        self.Fz_3 = fz[2] if len(fz) > 2 else 0.0
        # the other rollers and the joint on the housing (rollers at the pitch radius s: the
        # reduced model has no contact point)
        fx += [0.0] * (3 - len(fx))
        fy += [0.0] * (3 - len(fy))
        self.Fx_2, self.Fy_2, self.Fx_3, self.Fy_3 = fx[1], fy[1], fx[2], fy[2]
        sp = self._scene["s"]
        self.F_housing_x, self.F_housing_y, self.T_housing = housing_forces(
            fx[0], fy[0], sp, fx[1], fy[1], sp, fx[2], fy[2], sp)
        self.F_roller = F
        self.whirl_angle = self._x[0]
