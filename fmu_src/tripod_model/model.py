"""The one-roller contact model: parameters, state, step(dt) and outputs.

The contact model in process, for the harness, the benchmarks and the tests (the FMU's binary
runs lifecycle.py, over the same kernel).  Problem (parameters), integrator
(kernel.run_substeps) and result (outputs) are kept apart: the model owns the state and
advances it by communication steps.
"""
from __future__ import annotations

import math

import numpy as np

from reduced_model import scene as scene_mod

# (numba only when needed)
from . import layout as K, needle_setup, oppoint, roller_setup, start_slide

from reduced_model.scene import OUTPUTS  # noqa: F401  (declared once, with the parameters)
from reduced_model.housing import housing_forces, spider_orbit
from reduced_model.thrust import fz_mod
from reduced_model.scene import StepRefused, same_step
from .budget import refusal


class ContactModel:
    """One roller in one groove, trunnion motions as driving constraints (paper section 2).

    ``params``: overrides of the contact-model parameter table (SI units); validated here,
    so a bad value raises ValueError naming the parameter and its range.
    """

    def __init__(self, params: dict | None = None, phase: float = 0.0):
        self.phase = phase
        self.p = scene_mod.validate(params, "contact")
        p = self.p
        # the roller's parameter vector from the table's values (roller_setup: the FMU's binary
        # derives it by the same function)
        self.T = np.array(start_slide.params_array(p))
        P = np.zeros(K.P_LEN)
        roller_setup.kernel_params(self.T, P)
        self.Kh, self.a1 = P[K.P_K], P[K.P_A1]
        self.P = P
        self.n_needle_bodies = p["n_needles"] if p["bearing"] == K.BEAR_RESOLVED else 0
        # None unless the needles are resolved: the kernel is then compiled without them
        self.NW = (needle_setup.needle_work(self.T, self.n_needle_bodies, p["n_spheres"])
                   if self.n_needle_bodies else None)
        self.Y = np.zeros(K.Y_LEN + K.N_F * self.n_needle_bodies)
        self.out = np.zeros(K.O_LEN)
        self._L = np.full(K.L_LEN, np.nan)   # line kinematics + its cache key
        self._res = np.zeros(K.R_LEN)
        self._Y1 = np.zeros_like(self.Y)
        self._Y2 = np.zeros_like(self.Y)
        self._G = np.zeros((K.NV, 3))
        self._A = np.zeros((K.NV, K.NV))
        self._b = np.zeros(K.NV)
        # integrators 3 and 4: adaptive substep, accepted and rejected substeps; generalized-
        # alpha: whether its accelerations are valid, steps handed to the adaptive substeps,
        # the accelerations (NV)
        self._hs = np.zeros(K.H_LEN)
        self._GW = np.zeros((K.NV + 8, K.NV))   # generalized-alpha work array
        self._bind_work()
        self.time = 0.0
        self.substeps = 0
        self._OP = np.zeros(K.OP_LEN)   # inputs and operating point of a step (oppoint.py)
        self._OP[K.OP_KEY] = np.nan      # none derived yet
        self._started = False
        # resolved bearing: the pressing offset, the load it is for, whether set (a cache)
        self._x0c = np.zeros(3)

    def _bind_work(self):
        """The work record the kernel takes (layout.Work), over the arrays as now bound (a
        joint rebinds them to rows of its stacks: JointModel._stack)."""
        self._W = K.Work(self._L, self._res, self._Y1, self._Y2, self._G, self._A, self._b,
                         self._hs, self._GW)

    # --- inputs that set the operating point (oppoint.py: one implementation, compiled into
    # the step) ---
    def v_st(self, theta, omega):
        """Transition velocity [m/s]: the parameter, or automatic sqrt(A^2+B^2)/4 (model.md)."""
        return oppoint.v_st(self.P, theta, omega)

    def substep(self, theta, omega, F_press, v_st, stiff=True):
        """Substep [s] at these inputs (oppoint.substep)."""
        return oppoint.substep(self.P, theta, omega, F_press, v_st, stiff)

    def ga_step_size(self, theta, omega, F_press, v_st):
        """Step of the generalized-alpha integrator [s] (oppoint.ga_step_size)."""
        return oppoint.ga_step_size(self.P, theta, omega, F_press, v_st)

    def pressing_offset(self, F_press):
        """Compulsory displacement: x position of the trunnion axis [m] that gives F_press
        with the roller at the groove bottom (Hertz approach, plus the needle row if any)."""
        return roller_setup.pressing_offset(self.P, self.T, F_press)

    def radial_offset(self, F):
        """Static x offset of the roller from the trunnion axis [m] under a radial load F [N]
        (roller_setup.radial_offset): 0 with the ideal bearing, negative in drive."""
        return roller_setup.radial_offset(self.P, self.T, F)

    def bearing_load(self):
        """Radial load carried by the needle row now [N]: along the pressing direction, the sum
        over the needles at the last output (resolved), the row law (lumped), 0 (ideal)."""
        if self.p["bearing"] == K.BEAR_RESOLVED:
            return float(np.sum(self.NW.ND[:, K.D_R1]))
        if self.p["bearing"] != K.BEAR_LUMPED:
            return 0.0
        return oppoint.row_sums(self.P, abs(self.Y[K.Y_E]))[0]

    def start(self, theta, omega, F_press=0.0, plunge_speed=0.0):
        """Initial state at whirl angle ``self.phase`` [rad] (0, 2 pi/3, 4 pi/3 for the rollers
        of a joint): the roller rolling without slip, and along the trunnion where the settled
        cycle has it (start_slide; at the groove bottom and at rest where that does not hold)."""
        p = self.p
        roller_setup.start_state(self.Y, self.P, self.T, self.phase, theta, omega, F_press)
        table = start_slide.traverse_table(p, theta, omega, F_press, plunge_speed)
        if table is not None:
            roller_setup.place_on_cycle(self.Y, self.P, F_press, omega, table.slip, table.p,
                                        table.n, _probe, (self, theta, omega, F_press,
                                                          plunge_speed))
        if self.n_needle_bodies:
            from .contact import trunnion_axial   # numba: the resolved bearing compiles its kernel
            roller_setup.start_needles(self.Y, self.T, self.phase, theta, self.n_needle_bodies,
                                       trunnion_axial(self.phase, theta, p["s"], p["axial"]))
        self._hs[K.H_GA] = 0.0   # no previous step (generalized-alpha, BDF2) to continue from
        self._hs[K.H_RING] = K.RING_OPEN   # the roller's ring resolved from the start
        self._started = True

    def row_bore_radius(self):
        """Radius of the needles' outer race [m] (roller_setup.row_bore_radius)."""
        return roller_setup.row_bore_radius(self.T)

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

    def step(self, dt, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        """Advance by one communication step dt [s] at the given inputs; returns the outputs.

        theta [rad], omega [rad/s], F_press [N], torque [N m] (> 0: the pressing load is
        torque / (3 s)), plunge_speed [m/s] (the spider along the groove) are held over the
        step (continuous inputs).
        """
        if not self._started:
            self.start(theta, omega, scene_mod.pressing_load(F_press, torque, self.p["s"]),
                       plunge_speed)
        self.set_inputs(dt, theta, omega, F_press, torque, plunge_speed)
        acc = self._hs[K.H_TAKEN]
        self._run()
        self.substeps += int(self._hs[K.H_TAKEN] - acc)
        self.time += dt
        return self.outputs(self._OP[K.OP_F])

    def set_inputs(self, dt, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        """The inputs and step dt [s] of the next step into OP; the compiled step derives their
        operating point (oppoint.derive) when they changed.  A dt within the rounding of the
        master's times of the last one is that step (same_step), as lifecycle.step does."""
        OP = self._OP
        if OP[K.OP_DT] > 0 and same_step(dt, OP[K.OP_DT], self.time):
            dt = OP[K.OP_DT]
        OP[K.OP_THETA], OP[K.OP_W], OP[K.OP_FP], OP[K.OP_TQ], OP[K.OP_DT], OP[K.OP_VP] = (
            theta, omega, F_press, torque, dt, plunge_speed)

    @property
    def whirl_angle(self):
        """This roller's whirl angle now [rad] (its phase included)."""
        return float(self.Y[K.Y_X]) - self.phase

    @property
    def load_ramped(self):
        """Whether a load change moves the pressing offset to its new value over the step
        rather than at once (_run): the needle-resolved bearing's default step, whose substeps
        follow the ramp (bdf2.bdf2_steps); the comparison integrators keep the jump."""
        return self.NW is not None and self.p["integrator"] == K.INT_DEFAULT

    @property
    def step_dt(self):
        """The communication step [s] the operating point is set for."""
        return float(self._OP[K.OP_DT])

    def initial_outputs(self, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        """The outputs at the start state these inputs give (what the FMU reports at its
        start time), without a step and without moving the model: the first step still
        starts from the inputs it is given."""
        saved = self.get_state()
        F = scene_mod.pressing_load(F_press, torque, self.p["s"])
        self.start(theta, omega, F, plunge_speed)
        self.probe(theta, omega, F, plunge_speed)   # the outputs at the start state
        out = self.outputs(F)
        self.set_state(saved)
        return out

    def probe(self, theta, omega, F, vp):
        """The kernel's (L, res) at the state now, by a step of no substeps at these inputs
        [rad, rad/s, N, m/s] (the output vector written too; any step size: no substep is
        taken); the parameters, operating point and history kept."""
        kept = self.P.copy(), self._OP.copy(), self._hs.copy()
        self.set_inputs(1e-4, theta, omega, F, 0.0, vp)
        self._OP[K.OP_NOSTEP] = 1.0
        self._run()
        self.P[:], self._OP[:], self._hs[:] = kept
        return self._L, self._res

    def _run(self):
        """One step at OP's inputs through the kernel numba compiles: the operating point
        derived first (oppoint.derive); the resolved bearing's pressing offset is then the
        model's."""
        from . import kernel
        OP = self._OP
        # the load the last step ran at (none before the first: its key's theta is NaN)
        F_was = (scene_mod.pressing_load(OP[K.OP_KEY + 2], OP[K.OP_KEY + 3], self.p["s"])
                 if OP[K.OP_KEY] == OP[K.OP_KEY] else math.nan)
        kernel.inputs_moved(self.P, self._hs, kernel.derive_op(self.P, OP))
        n = 0 if OP[K.OP_NOSTEP] > 0 else int(OP[K.OP_N])
        x0, rate = OP[K.OP_X0], 0.0
        if self.NW is not None:
            x0, rate = kernel.resolved_drive(self.P, self.T, OP, F_was, n, self.load_ramped,
                                       self._x0c)
        if not kernel.run_substeps(self.Y, self.P, K.Drive(OP[K.OP_THETA], OP[K.OP_W], x0, rate),
                                   OP[K.OP_H], n, self.out, self._W, self.NW):
            raise StepRefused(refusal(self._hs, self.P))

    def kernel_name(self) -> str:
        """Which kernel steps this roller (for the log)."""
        from . import jit
        return "numba" if jit.HAVE_NUMBA else "plain Python (numba missing or off)"

    def get_state(self) -> dict:
        """A deep copy of everything a step depends on (for FMU state rollback)."""
        return {"Y": self.Y.copy(), "out": self.out.copy(), "vst": float(self.P[K.P_VST_OP]),
                "hs": self._hs.copy(), "Y2": self._Y2.copy(),   # Y2: BDF2's previous state
                "ND": None if self.NW is None else self.NW.ND.copy(),
                # the inputs the state was stepped at: a restore followed by other inputs is a
                # jump (kernel.inputs_moved), the same inputs are none
                "inputs": np.append(self._OP[K.OP_KEY:K.OP_KEY + 4], self._OP[K.OP_KEY + 5]),
                "time": self.time, "substeps": self.substeps, "started": self._started}

    def set_state(self, st: dict) -> None:
        self.Y[:] = st["Y"]
        self.out[:] = st["out"]
        if self.NW is not None:
            self.NW.ND[:] = st["ND"]
        self._hs[:] = st["hs"]
        self._Y2[:] = st["Y2"]
        self.P[K.P_VST_OP] = st["vst"]
        self._OP[K.OP_KEY:K.OP_KEY + 4] = st["inputs"][:4]
        self._OP[K.OP_KEY + 5] = st["inputs"][4]
        self._OP[K.OP_KEY + 4] = np.nan   # derive the operating point again at the next step
        self.time, self.substeps, self._started = st["time"], st["substeps"], st["started"]

    def outputs(self, F_press):
        o = self.out
        Fx = o[K.O_FX]
        Fz_mod = fz_mod(Fx, o[K.O_FZ], F_press)
        return {"Fx": Fx, "Fy": o[K.O_FY], "Fz": o[K.O_FZ], "Fz_mod": Fz_mod,
                "dFx": Fx - F_press, "contact_y": o[K.O_CY], "contact_z": o[K.O_CZ],
                "slip_speed": o[K.O_SLIP], "roller_spin": o[K.O_SPIN], "whirl_angle": o[K.O_X],
                "plunge": o[K.O_PL]}


def _probe(ctx):
    """(L, res) of ContactModel ctx[0] at its state now at the inputs ctx[1:] (its probe), for
    roller_setup.place_on_cycle."""
    return ctx[0].probe(ctx[1], ctx[2], ctx[3], ctx[4])


# the arrays a joint stacks (JointModel._stack)
_STACKED = ("Y", "P", "_OP", "_L", "_res", "_Y1", "_Y2", "_G", "_A", "_b", "_hs", "_GW", "out")


def _joint_outputs(outs, s, F, theta):
    """Roller 1's outputs plus the joint's: Fz_joint (the housing thrust, the sum of the
    rollers' Fz [N]), the other rollers' forces and contact points (0 where absent), the joint's
    force and torque on the housing (reduced_model/housing.py, at the contact radius s +
    contact_y [m]), the pressing load per roller F [N], the spider's centre on Eq. (5)'s orbit
    at the joint angle theta [rad] (kernel.spider_into) and each trunnion's load."""
    o = dict(outs[0])
    total = 0.0   # left to right, as lifecycle.joint_outputs (sum() compensates from 3.12 on)
    for x in outs:
        total += x["Fz"]
    o["Fz_joint"] = total
    zero = dict.fromkeys(("Fx", "Fy", "Fz", "contact_y", "contact_z"), 0.0)
    r2 = outs[1] if len(outs) > 1 else zero
    r3 = outs[2] if len(outs) > 2 else zero
    for k, r in (("2", r2), ("3", r3)):
        for name in ("Fz", "Fx", "Fy", "contact_y", "contact_z"):
            o[f"{name}_{k}"] = r[name]
    o1 = outs[0]
    o["F_housing_x"], o["F_housing_y"], o["T_housing"] = housing_forces(
        o1["Fx"], o1["Fy"], s + o1["contact_y"], r2["Fx"], r2["Fy"], s + r2["contact_y"],
        r3["Fx"], r3["Fy"], s + r3["contact_y"])
    o["F_roller"] = F
    o["spider_x"], o["spider_y"] = spider_orbit(s, theta, o1["whirl_angle"])
    for i in range(3):
        o[f"F_roller_{i + 1}"] = F if i < len(outs) else 0.0
    return o


class JointModel:
    """``n_rollers`` (1 or 3) rollers of one joint at whirl phases 0, 120, 240 deg.

    Each roller is an independent ContactModel in its own groove (the paper's one-roller model
    repeated); the housing thrust Fz_joint is the sum of their Fz.  Pressing per roller is
    F_press, or torque / (3 s) when a transmitted torque [N m] is given (torque wins if > 0).
    """

    def __init__(self, params: dict | None = None):
        params = dict(params or {})
        p = scene_mod.validate(params, "contact")
        self.p = p
        self.rollers = [ContactModel(params, phase=2 * math.pi * i / 3)
                        for i in range(p["n_rollers"])]
        self._stacks = (self._stack() if len(self.rollers) > 1 and p["bearing"] != K.BEAR_RESOLVED
                        else None)
        self.free = p["spider"] == scene_mod.SPIDER_FREE   # (validate: three rollers then)
        self._dst = np.zeros(K.N_OUT)    # the free spider's outputs (the FMU's OUT)

    def _stack(self):
        """The rollers' arrays as rows of one array each (kernel.step_joint steps them as a
        joint in one call), the OP array under a header row; each roller keeps views of its rows."""
        n = len(self.rollers)
        stacks = {}
        for name in _STACKED:
            rows = [getattr(r, name) for r in self.rollers]
            head = 1 if name == "_OP" else 0
            st = np.zeros((n + head,) + rows[0].shape)
            st[head:] = rows
            for i, r in enumerate(self.rollers):
                setattr(r, name, st[head + i])
            stacks[name] = st
        for r in self.rollers:
            r._bind_work()
        stacks["_OP"][0, K.OP_NROLL] = n
        # kernel.step_joint derives one operating point for all the rollers (oppoint.copy_derived):
        # they differ in their whirl phase, which P does not hold, and in nothing else
        assert all(np.array_equal(row, stacks["P"][0], equal_nan=True) for row in stacks["P"])
        return stacks

    @property
    def started(self):
        """Whether the rollers have taken their first step (a restored state brings its own)."""
        return self.rollers[0]._started

    def pressing(self, F_press, torque):
        """Pressing load per roller [N]: torque / (3 s) when torque is not 0, else F_press."""
        return scene_mod.pressing_load(F_press, torque, self.p["s"])

    def step(self, dt, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        """Advance every roller by dt [s]; returns roller 1's outputs plus the joint's."""
        if self.free:
            return self._step_free(dt, theta, omega, F_press, torque, plunge_speed)
        out = _joint_outputs([r.step(dt, theta, omega, F_press, torque, plunge_speed)
                              for r in self.rollers], self.p["s"], self.pressing(F_press, torque),
                             theta)
        if self._stacks is not None:   # the inputs and step a joint's step takes next
            head, op = self._stacks["_OP"][0], self.rollers[0]._OP
            for j in (K.OP_THETA, K.OP_W, K.OP_FP, K.OP_TQ, K.OP_DT, K.OP_VP):
                head[j] = op[j]
        return out

    def initial_outputs(self, theta, omega, F_press, torque=0.0, plunge_speed=0.0):
        """The outputs of step() at the start state, without a step (the FMU's start time)."""
        return _joint_outputs([r.initial_outputs(theta, omega, F_press, torque, plunge_speed)
                               for r in self.rollers], self.p["s"], self.pressing(F_press, torque),
                              theta)

    def _step_free(self, dt, theta, omega, F_press, torque, plunge_speed):
        """A step of the rollers on a floating spider (kernel.step_joint hands it to
        free_spider.step_free_spider): all three rollers and the spider in one call."""
        F = self.pressing(F_press, torque)
        for r in self.rollers:
            if not r._started:
                r.start(theta, omega, F, plunge_speed)
            r.set_inputs(dt, theta, omega, F_press, torque, plunge_speed)
        head, op = self._stacks["_OP"][0], self.rollers[0]._OP
        for j in (K.OP_THETA, K.OP_W, K.OP_FP, K.OP_TQ, K.OP_DT, K.OP_VP):
            head[j] = op[j]
        taken = [r._hs[K.H_TAKEN] for r in self.rollers]
        from . import kernel
        st = self._stacks
        rc = kernel.step_joint(3, st["Y"], st["P"], st["_OP"], K.Work(
            st["_L"], st["_res"], st["_Y1"], st["_Y2"], st["_G"], st["_A"], st["_b"],
            st["_hs"], st["_GW"]), st["out"], self._dst)
        if rc == 3:
            raise StepRefused(self.refusal())
        if rc != 1:
            raise FloatingPointError("the free spider's step gave a non-finite output")
        for r, t in zip(self.rollers, taken):
            r.substeps += int(r._hs[K.H_TAKEN] - t)
            r.time += dt
        return dict(zip(K.OUTPUT_NAMES, self._dst.tolist()))

    def refusal(self) -> str:
        """Why the last step ran out of its budget, and in which roller (budget.refusal)."""
        for i, r in enumerate(self.rollers):
            if r._hs[K.H_FAIL] != K.FAIL_NONE:
                return f"roller {i + 1}: {refusal(r._hs, r.P)}"
        return "no roller ran out of its budget"

    def get_state(self) -> list:
        """The rollers' states; a free spider's (its OP_SP_* slots) with roller 1's."""
        states = [r.get_state() for r in self.rollers]
        if self.free:
            states[0]["spider"] = self._stacks["_OP"][0, K.OP_SP_QX:K.OP_LEN].copy()
        return states

    def set_state(self, st: list) -> None:
        for r, s in zip(self.rollers, st):
            r.set_state(s)
        if self.free:
            self._stacks["_OP"][0, K.OP_SP_QX:K.OP_LEN] = st[0]["spider"]

    def summary(self) -> str:
        """One line for the FMU log at the end: the integration steps roller 1 took."""
        r = self.rollers[0]
        hs = r._hs
        text = f"roller 1: {r.substeps} steps, {r.time:.6g} s"
        if self.p["integrator"] == K.INT_DEFAULT and self.p["bearing"] != K.BEAR_RESOLVED:
            text += (f"; generalized-alpha, {int(hs[K.H_FALLBACK])} step(s) handed to the extrapolated "
                     f"substeps when Newton did not converge")
        elif self.p["integrator"] == K.INT_DEFAULT:      # BDF2, the needle-resolved bearing
            if self.p["newton_passes"] > 1:
                text += (f"; BDF2, a second Newton pass in {int(hs[K.H_PASSES])} substep(s), "
                         f"{int(hs[K.H_REJECTED])} pass(es) refused as not contracting")
        elif self.p["integrator"] == K.INT_ADAPTIVE:
            text += f"; {int(hs[K.H_REJECTED])} substep(s) rejected by the error estimate"
        return text

    def info(self, theta, omega, F_press, torque=0.0) -> str:
        """One line for the FMU log: the operating point the integrator chose."""
        r = self.rollers[0]
        F = self.pressing(F_press, torque)
        vst = r.v_st(theta, omega)
        h = r.substep(theta, omega, F, vst)
        return (f"{len(self.rollers)} roller(s), bearing {self.p['bearing']}, traverse "
                f"{self.p['traverse']}; pressing {F:.6g} N per roller, v_st {vst:.4g} m/s, "
                f"substep {h:.3g} s, pressing offset {r.pressing_offset(F):.6g} m; kernel "
                f"{r.kernel_name()}")
