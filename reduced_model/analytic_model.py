"""The analytic FMU's model (fmu_src/TripodRollerAnalytic.py is its adapter): n rollers of the
reduced thrust model, numpy only.

traverse = true (default): the reduced traverse model's periodic solution, tabulated over the
whirl angle at the start (traverse.py); once a master moves the inputs, the roller's slide is
stepped in time at the inputs of each step (Traverse.march: T4 is an ODE in time, the table its
periodic solution), where a new table took 0.05 s or more a step.  false: Eqs. (18)-(27)
(thrust.py).  Coast runs as drive at the opposite whirl turned 180 deg about the trunnion axis
(docs/model.md, "Coast and reverse whirl").  The whirl angle integrates omega.
"""
from __future__ import annotations

import math

from .housing import housing_forces
from .scene import REGIME_CODES, check_value, pressing_load, same_step, same_value, validate
from .thrust import Thrust
from .traverse import INERTIA, Traverse, inertia_ratio, outside_checked, outside_span

INPUTS = ("theta", "omega", "F_press", "torque", "plunge_speed")
# what the model's state holds besides the FMU's variables (AnalyticModel.get_state; the
# plunge is an output variable, so the adapter's variables carry it)
STATE_KEYS = ("x", "dt", "scene", "march", "span")


def _copy_march(march):
    """A copy of the march's rows [slip, p, outputs] (numbers, the outputs a tuple or a list of
    numbers, or None): what copy.deepcopy gave, at a fraction of its cost (an iterative master
    takes a state and sets it back every step)."""
    if march is None:
        return None
    return [[s, p, out if out is None or isinstance(out, tuple) else list(out)]
            for s, p, out in march]


def _copy_span(span):
    """A copy of the span [lows, highs] (lists of numbers), or None."""
    return None if span is None else [list(side) for side in span]


class AnalyticModel:
    """n rollers (0, 120, 240 deg) of the reduced model at the inputs of each step.

    values: the parameter table's values for "analytic" (reduced_model.scene), SI units.
    say(text, warning): where the model's messages go (the FMU's log)."""

    def __init__(self, values: dict, say=None):
        self.say = say or (lambda text, warning=False: None)
        self.scene = validate(values, "analytic")
        n = self.scene["n_rollers"]
        self.x = [2.0 * math.pi * i / 3.0 for i in range(n)]   # whirl angle of each roller [rad]
        self.dt = None        # the communication step taken [s] (same_step)
        self.key = None       # the inputs the operating point was derived at (INPUTS order)
        self.thrust = None    # Eqs. (18)-(27) at those inputs
        self.table = None     # the traverse model's settled table (at the start)
        self.march = None     # per roller [s, p, outputs] once the inputs moved (Traverse.march)
        self.op = None        # the operating point the march steps at
        self.span = None      # lowest and highest theta, omega, pressing load of the run
        self.regime = 0       # REGIME_CODES of the start's table
        self.tables = 0       # traverse tables derived (the log)
        self.plunge = 0.0     # the spider's travel [m]: the held plunge speed's integral
        # the settled table and the inputs it was derived at, kept when the march drops it: a
        # state restored from before the inputs moved takes it back (set_state) instead of
        # deriving a table again (0.05 s) at whatever inputs the next step brings
        self.start_table = None
        self.told_march = False   # the log said once that the slide is stepped in time
        self.prepare(tuple(self.scene[n] for n in INPUTS))

    # --- the operating point ------------------------------------------------------------
    def prepare(self, key):
        """Check the inputs key (INPUTS order) and, when the operating point changed, re-derive
        the constants: at the start the traverse model's settled table (about 0.05 s at the
        paper's scene), on an input change the operating point its slide is stepped at."""
        # inputs moved only in their last bits (a master interpolating an input table) keep
        # the operating point, the table and the compiled steps
        if self.key is not None and all(map(same_value, key, self.key)):
            return
        self.take_inputs(key)
        sc = self.inner()
        loaded = sc["mu_groove"] > 0 and pressing_load(sc["F_press"], sc["torque"], sc["s"]) > 0
        applies = sc["traverse"] and sc["omega"] > 0 and loaded
        if not sc["traverse"]:
            self.table, self.regime = None, 0
        elif self.key is None and self.march is None and sc["omega"] < 0 and loaded:
            # reverse whirl (or coast at forward whirl) from the start: no periodic table in
            # that sense; the slide is stepped in time from rest
            self.table, self.regime = None, 0
            self.march = [[None, 0.0, None] for _ in self.x]
            self.op = Traverse(sc, periodic=False)
        elif self.key is None and self.march is None:
            # the start (or a restored state from before the inputs moved): the settled table
            self.table, self.regime = None, 0
            if applies:
                self._start_table(sc)
        else:
            # the inputs moved: the slide is stepped in time from where the table had it
            if self.march is None:
                self.march = [list(self.table.state_at(self.at(x))) + [None]
                              if self.table is not None else [None, 0.0, None]
                              for x in self.x]
                if not self.told_march:    # (once: a rollback may start it again)
                    self.say("the inputs moved: from here on the traverse model steps the "
                             "roller's slide in time at each step's inputs (no new settled "
                             "table; regime stays that of the start)")
                    self.told_march = True
            self.table = None
            self.op = Traverse(sc, periodic=False)
        self.key = key

    def _start_table(self, sc):
        self.table = Traverse(sc)
        self.regime = REGIME_CODES.index(self.table.regime())
        self.tables += 1
        self.start_table = (tuple(float(self.scene[n]) for n in INPUTS), self.table, self.regime)
        outside = outside_checked(sc)
        if outside:
            self.say("the scene is outside the range the traverse model was checked against "
                     "the contact model in (docs/validation.md): " + "; ".join(outside), True)
        if not self.table.settled:
            self.say(f"the traverse table at theta = {sc['theta']:.6g} rad, omega = "
                     f"{sc['omega']:.6g} rad/s is not periodic: s(2 pi) - s(0) = "
                     f"{self.table.mismatch:.2e} m/s after {self.table.cycles} cycles of the "
                     "cycle map; its outputs are the best cycle run", True)

    def take_inputs(self, key):
        """Check the inputs key (INPUTS order) and make them the scene's."""
        for name, value in zip(INPUTS, key):
            check_value(name, value)
        for name, value in zip(INPUTS, key):
            self.scene[name] = float(value)
        self.thrust = Thrust(self.inner())
        sc = self.scene
        now = (sc["theta"], abs(sc["omega"]),
               abs(pressing_load(sc["F_press"], sc["torque"], sc["s"])))
        self.widen_span(now, now)

    def widen_span(self, lows, highs):
        """The span of the inputs over the run (theta [rad], omega [rad/s], pressing load [N]):
        what outside_run compares with where the traverse model was checked."""
        if self.span is None:
            self.span = [list(lows), list(highs)]
        else:
            self.span = [list(map(min, self.span[0], lows)),
                         list(map(max, self.span[1], highs))]

    def outside_run(self):
        """Where the run's inputs left the range the traverse model was checked in (once the
        slide was stepped in time), as phrases; empty when they did not."""
        if self.march is None or not self.scene["traverse"]:
            return []
        (t0, w0, f0), (t1, w1, f1) = self.span
        # the roller's inertia at its worst: the highest whirl on the lowest load
        worst = inertia_ratio(dict(self.scene, omega=w1, F_press=f0, torque=0.0))
        return [p for p in (outside_span("theta", math.degrees(t0), math.degrees(t1)),
                            outside_span("whirl", w0 / (2 * math.pi), w1 / (2 * math.pi)),
                            outside_span("pressing load", f0, f1),
                            outside_span(INERTIA, worst, worst)) if p]

    # --- coast: drive at the opposite whirl, turned 180 deg about the trunnion axis ----------
    # (x -> -x, z -> -z; Fx, Fz, Fz_mod, the whirl angle and the plunge speed flip, Fy and the
    # slip do not)
    @property
    def mirror(self):
        sc = self.scene
        return pressing_load(sc["F_press"], sc["torque"], sc["s"]) < 0

    def inner(self):
        """The scene the reduced model runs: the inputs, or for coast the drive scene whose
        turn it is."""
        sc = self.scene
        if not self.mirror:
            return sc
        return dict(sc, omega=-sc["omega"], F_press=-sc["F_press"], torque=-sc["torque"],
                    plunge_speed=-sc["plunge_speed"])

    def at(self, x):
        """The reduced model's whirl angle for the roller's angle x [rad]."""
        return -x if self.mirror else x

    def outer(self, Fz, Fz_mod, Fx, Fy, slip):
        """The reduced model's outputs (Fz, Fz_mod, Fx, Fy [N], slip speed [m/s]) as the
        joint's: turned back for coast."""
        if self.mirror:
            return -Fz, -Fz_mod, -Fx, Fy, slip
        return Fz, Fz_mod, Fx, Fy, slip

    # --- a communication step --------------------------------------------------------------
    def step(self, dt, current_time, key):
        """Advance by dt [s] from current_time [s] at the inputs key (INPUTS order)."""
        self.prepare(key)
        # a step that differs from the last one by the rounding of the master's times is
        # that step, as on the compiled path
        if self.dt is None or not same_step(dt, self.dt, current_time):
            self.dt = dt
        if self.march is not None and self.op is not None:
            for i, m in enumerate(self.march):
                m[0], m[1], x, m[2] = self.op.march(m[0], m[1], self.at(self.x[i]), self.dt)
                self.x[i] = self.at(x)
        else:
            w = self.scene["omega"] * self.dt
            for i in range(len(self.x)):
                self.x[i] += w
        self.plunge = self.plunge + self.scene["plunge_speed"] * self.dt   # held speed

    def roller_outputs(self):
        """Each roller's (Fz, Fz_mod, Fx, Fy [N], slip speed [m/s]) at its whirl angle now:
        the march's, the table's, or Eqs. (18)-(27) (where Fx is the pressing load)."""
        if self.march is not None and self.march[0][2] is not None:
            return [self.outer(*m[2]) for m in self.march]
        if self.table is not None:
            at = self.table.at
            return [self.outer(*at(self.at(x))) for x in self.x]
        at = self.thrust.at
        sign = -1.0 if self.mirror else 1.0
        F = self.pressing_load()
        rows = []
        for x in self.x:
            Fz, _, ft, V, phi, _ = at(self.at(x))
            rows.append((sign * Fz, sign * Fz, F, ft * math.cos(phi), abs(V)))
        return rows

    def pressing_load(self):
        sc = self.scene
        return pressing_load(sc["F_press"], sc["torque"], sc["s"])

    def outputs(self):
        """Every output the analytic FMU has, by name [SI]."""
        F = self.pressing_load()
        rows = self.roller_outputs()
        Fz, Fz_mod, Fx, Fy, slip = rows[0]
        total = 0.0   # in order, as analytic_step.c (sum() compensates from Python 3.12 on)
        for r in rows:
            total += r[0]
        # the other rollers and the joint on the housing (rollers at the pitch radius s: the
        # reduced model has no contact point)
        fx = [r[2] for r in rows] + [0.0] * (3 - len(rows))
        fy = [r[3] for r in rows] + [0.0] * (3 - len(rows))
        sp = self.scene["s"]
        hx, hy, ht = housing_forces(fx[0], fy[0], sp, fx[1], fy[1], sp, fx[2], fy[2], sp)
        return {"Fz": Fz, "Fz_mod": Fz_mod, "Fx": Fx, "Fy": Fy, "dFx": Fx - F,
                "slip_speed": slip, "Fz_joint": total,
                "Fz_2": rows[1][0] if len(rows) > 1 else 0.0,
                "Fz_3": rows[2][0] if len(rows) > 2 else 0.0,
                "Fx_2": fx[1], "Fy_2": fy[1], "Fx_3": fx[2], "Fy_3": fy[2],
                "F_housing_x": hx, "F_housing_y": hy, "T_housing": ht, "F_roller": F,
                "whirl_angle": self.x[0], "plunge": self.plunge, "regime": self.regime}

    # --- the compiled steps' operating points (analytic_step.c) ---------------------------
    def fast_table_op(self):
        """The table's rows (or two rows of zeros without one) and the operating point the
        compiled table step (tripod_analytic_step) takes, by name."""
        sc, th, tb = self.scene, self.thrust, self.table
        rows = tb.rows if tb is not None else [[0.0] * 5] * 2
        op = {"omega": sc["omega"], "n_rollers": len(self.x), "F": self.pressing_load(),
              "table": float(tb is not None), "scale": tb.scale if tb is not None else 0.0,
              "n": tb.n if tb is not None else 0,
              "A": th.A, "B": th.B, "muF": th.muF, "k": th.k, "th": th.th, "kspin": th.kspin,
              "s": sc["s"], "vp": th.vp, "plunge_speed": sc["plunge_speed"], "dt": self.dt}
        return rows, op

    def fast_march_op(self, inputs):
        """The march's state rows and the operating point the compiled march
        (tripod_analytic_march) takes, by name, the inputs as the master left them
        (INPUTS order); None while the march has not taken its first step."""
        if self.op is None or any(m[0] is None or m[2] is None for m in self.march):
            return None         # (the march starts at rest: its first step in Python)
        sc, op = self.scene, self.op
        mop = {n: float(v) for n, v in zip(INPUTS, inputs)}
        mop.update({"key_" + n: float(v) for n, v in zip(INPUTS, self.key)})
        mop.update(dt=self.dt, n_rollers=len(self.x), n=op.n, mu=op.mu, v_st=sc["v_st"],
                   K=op.K, a1=op.a1, clear=op.clear, r=op.r, s=sc["s"], I=op.inertia,
                   pitch=float(sc["pitch"]), roll=float(sc["roll"]),
                   spin_moment=float(op.spin_moment_on))
        (mop["theta_lo"], mop["omega_lo"], mop["load_lo"]), \
            (mop["theta_hi"], mop["omega_hi"], mop["load_hi"]) = self.span
        return [[m[0], m[1]] + list(m[2]) for m in self.march], mop

    def fast_synced(self, x, state, op):
        """The compiled steps ran: their whirl angles x, the march's state rows (None at the
        table) and its operating point by name (the inputs it was derived for, the span)."""
        self.x = [float(v) for v in x]
        if state is None:
            return
        for m, row in zip(self.march, state):
            m[0], m[1], m[2] = row[0], row[1], tuple(row[2:])
        self.widen_span([op[n + "_lo"] for n in ("theta", "omega", "load")],
                        [op[n + "_hi"] for n in ("theta", "omega", "load")])
        key = tuple(op["key_" + n] for n in INPUTS)
        if key != tuple(map(float, self.key)):
            self.take_inputs(key)
            self.op = Traverse(self.scene, periodic=False)
            self.key = key

    # --- state as data -------------------------------------------------------------------
    def get_state(self):
        return {"x": list(self.x), "dt": self.dt, "scene": dict(self.scene),
                "march": _copy_march(self.march), "span": _copy_span(self.span)}

    def set_state(self, st, plunge):
        """A state of get_state's keys (checked by the adapter), the plunge [m] at it."""
        self.x = list(st["x"])
        self.dt = st["dt"]
        march = _copy_march(st["march"])
        if st["scene"] != self.scene or (march is None) != (self.march is None):
            self.key = None        # else the table or march's operating point stays
            self.table = None
        self.march = march
        self.scene = dict(st["scene"])
        self.span = _copy_span(st["span"])
        self.plunge = plunge
        # a state from before the inputs moved, at the inputs the settled table was derived
        # at: that table and operating point again, as the step after get_state had them
        # (else the next step would derive a table at its own inputs: another path)
        key = tuple(float(self.scene[n]) for n in INPUTS)
        if march is None and self.start_table is not None and self.start_table[0] == key:
            self.key, self.table, self.regime = self.start_table
            self.thrust = Thrust(self.inner())
