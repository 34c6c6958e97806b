"""The contact model's communication step: n substeps of the integrator the parameters name
(layout.py names them), then the outputs: one roller (step_roller), a joint of ideal or lumped
rollers in one call (step_joint: the rollers' arrays as rows of one array each), a
needle-resolved roller's substeps (run_substeps).  Scalar math only so that numba compiles it
(jit.py); lifecycle.py composes these into the FMU's step, and model.py calls them in process.

Frame (model.md): groove fixed, groove axis = z axis through the origin, x = pressing
direction, y = trunnion axis (nominal).  Forces are reported from the roller on the groove.
"""
import math

from reduced_model.housing import housing_forces
from reduced_model.thrust import fz_mod
from . import layout as K
from . import oppoint, roller_setup, spider
from .jit import compiled_copies, inline, njit
from .assembly import resolved_forces
from .budget import MAX_SUBSTEPS
from . import bdf2, genalpha
from .bdf2 import bdf2_steps
from .contact import groove_contact, line_kinematics, roller_motion
from .steplib import adaptive_run, fixed_steps
from .genalpha import ga_steps
from .layout import (BEAR_IDEAL, BEAR_RESOLVED, INT_ADAPTIVE, INT_DEFAULT, O_CY, O_CZ, O_FN, O_FX, O_FY, O_FZ, O_PL, O_SLIP, O_SPIN, O_X, P_BEARING,
    P_INTEGRATOR, P_VP, R_FN, R_FX, R_FY, R_FZ, R_PY, R_PZ, R_SLIP, Y_OM, Y_PL, Y_X)
from .layout import (OP_DT, OP_F, OP_FP, OP_H, OP_LEN, OP_N, OP_NOSTEP, OP_NROLL, OP_THETA, OP_TQ,
    OP_VP, OP_W, OP_X0, N_OUT, OUT_FX_2, OUT_FZ_2, OUT_FZ_3, OUT_FZ_JOINT, OUT_PLUNGE,
    OUT_SPIDER_X)
from reduced_model.scene import SPIDER_FREE


# the operating point at OP's inputs (oppoint.derive), compiled with the callees it names;
# oppoint itself stays plain Python (jit.compiled_copies leaves it untouched)
_op = compiled_copies(oppoint, oppoint.FUNCTIONS)
derive_op, copy_op = _op.derive, _op.copy_derived
_housing = njit(housing_forces)
# the needle-resolved row's static offset (roller_setup.py), compiled with its callees
_pressing_offset = compiled_copies(roller_setup, (
    "needle_line_stiffness", "row_load", "needle_radial_offset", "radial_offset",
    "pressing_offset"), {"groove_offset": _op.groove_offset,
                         "lumped_offset": _op.lumped_offset}).pressing_offset
_fz_mod = njit(fz_mod)


@njit
def inputs_moved(P, hs, jump):
    """The inputs changed at this communication point (oppoint.derive's ``jump``): the default
    integrator takes it as its module says (genalpha.inputs_jumped, bdf2.inputs_jumped); the
    others are one-step methods that need nothing."""
    if P[P_INTEGRATOR] != INT_DEFAULT:
        return
    if P[P_BEARING] == BEAR_RESOLVED:
        bdf2.inputs_jumped(P, hs, jump)
    else:
        genalpha.inputs_jumped(P, hs, jump)


@njit
def run_substeps(Y, P, drive, h, n, out, W, NW):
    """Advance Y by n substeps of h [s] at the held inputs drive (layout.Drive) (advance);
    write the outputs at the end (roller_outputs).  Returns advance's verdict."""
    if not advance(Y, P, drive, h, n, W, NW):
        return False
    roller_outputs(Y, P, drive, out, W, NW)
    return True


@njit
def advance(Y, P, drive, h, n, W, NW):
    """Advance Y by n substeps of h [s] at the held inputs drive (layout.Drive).  W: the
    roller's work arrays (layout.Work); NW: the needle work arrays (layout.NeedleWork) with the
    resolved bearing, else None.

    The integrator P[P_INTEGRATOR] names (layout.py), each behind one call
    steps(Y, P, drive, h, n, W, NW) -> finished: INT_EULER, INT_EXPLICIT: n plain substeps
    (steplib.fixed_steps); INT_EXTRAPOLATED: each Richardson-extrapolated from one step of h and
    two of h/2 (second order, L-stable: the scheme of LIMEX/SEULEX with two stages; the same
    call); INT_ADAPTIVE: the same with its substep chosen by its own error estimate
    (steplib.adaptive_run); INT_DEFAULT: generalized-alpha with the ideal or lumped bearing
    (genalpha.ga_steps), BDF2 with the needle-resolved one (bdf2.bdf2_steps).

    Returns False where the step is longer than MAX_SUBSTEPS substeps (refused before it
    starts) or the adaptive substeps ran out of their budget (steplib.adaptive_steps);
    hs[H_FAIL] says which (budget.py).
    """
    hs = W.hs
    hs[K.H_FAIL] = K.FAIL_NONE
    if n > MAX_SUBSTEPS:     # refused before it starts (budget.py)
        hs[K.H_FAIL], hs[K.H_FAIL_DONE], hs[K.H_FAIL_H] = K.FAIL_LONG, h * n, h
        return False
    Y[Y_PL] += P[P_VP] * (h * n)     # the plunge: the held plunge speed's exact integral
    # every integrator behind one call: steps(Y, P, drive, h, n, W, NW) -> finished
    if P[P_INTEGRATOR] == INT_DEFAULT:
        if P[P_BEARING] != BEAR_RESOLVED:
            return ga_steps(Y, P, drive, h, n, W, NW)
        if NW is not None:    # (always, here; the test lets numba drop it from the others)
            return bdf2_steps(Y, P, drive, h, n, W, NW)
        return True
    if P[P_INTEGRATOR] >= INT_ADAPTIVE:
        return adaptive_run(Y, P, drive, h, n, W, NW)
    return fixed_steps(Y, P, drive, h, n, W, NW)


@njit
def roller_outputs(Y, P, drive, out, W, NW):
    """The output vector out (layout's O_ slots) at the state Y: forces on the groove (minus
    those on the roller), contact point, slip, spin, whirl angle, plunge."""
    L, res = W.L, W.res
    line_kinematics(Y[Y_X], drive.w, drive.theta, P, L)
    # (the outputs' slip at the offset's place: its ramp's rate left out, as it always was)
    c, v, wr, e1, e2 = roller_motion(Y, drive.x0, 0.0, L, P[P_BEARING] != BEAR_IDEAL)
    groove_contact(c, v, wr, P, res)
    if NW is not None:   # needle loads at the output instant (diagnostics)
        resolved_forces(Y, P, NW, drive.theta, Y[Y_X], 0.0, L, e1, e2, False)
    out[O_FX] = -res[R_FX]
    out[O_FY] = -res[R_FY]
    out[O_FZ] = -res[R_FZ]
    out[O_CY] = res[R_PY]
    out[O_CZ] = res[R_PZ]
    out[O_SLIP] = res[R_SLIP]
    out[O_SPIN] = Y[Y_OM]
    out[O_FN] = res[R_FN]
    out[O_X] = Y[Y_X]
    out[O_PL] = Y[Y_PL]


@njit
def resolved_drive(P, T, OP, F_was, n, ramped, cache):
    """The needle-resolved bearing's drive for a step at OP's operating point (derived): the
    pressing offset x0 [m] at its load (roller_setup.pressing_offset: the row's static offset,
    which oppoint.derive leaves to the model) and, where ``ramped`` and the load changed from
    F_was [N] (NaN: no step before), the rate [m/s] that moves the offset there over the
    step's n substeps: a jump drove the trunnion into the row at infinite speed
    (docs/integrators.md).  T: the table's values; cache: (x0, its load, set), kept between
    steps (about 0.2 ms an offset).  Returns (x0, rate)."""
    F = OP[OP_F]
    was_cached = cache[2] != 0.0 and cache[1] == F_was
    x_was = cache[0]
    if not (cache[2] != 0.0 and cache[1] == F):
        cache[0] = _pressing_offset(P, T, F)
        cache[1] = F
        cache[2] = 1.0
    x0 = cache[0]
    rate = 0.0
    if n > 0 and ramped and F_was == F_was and F_was != F:
        if not was_cached:
            x_was = _pressing_offset(P, T, F_was)
        rate = (x0 - x_was) / OP[OP_DT]
    return x0, rate


# --- the step as a C function (the native layer's) ---


@inline
def _put(dst, base, vals):
    """vals into dst from base on where every one is finite; whether they were (nothing is
    written otherwise)."""
    for v in vals:
        if not math.isfinite(v):
            return False
    for i in range(len(vals)):
        dst[base + i] = vals[i]
    return True


@njit
def outputs_into(o, F_press, dst):
    """The FMU's outputs (OUTPUT_NAMES) of one roller from the kernel's output vector o.
    Returns whether all are finite
    (nothing is written otherwise)."""
    Fx = o[K.O_FX]
    Fz_mod = _fz_mod(Fx, o[K.O_FZ], F_press)
    vals = (Fx, o[K.O_FY], o[K.O_FZ], Fz_mod, Fx - F_press, o[K.O_CY], o[K.O_CZ], o[K.O_SLIP],
            o[K.O_SPIN], o[K.O_FZ], 0.0, 0.0, o[K.O_X])
    for v in vals:
        if not math.isfinite(v):
            return False
    if not math.isfinite(o[K.O_PL]):
        return False
    for i in range(len(vals)):
        dst[i] = vals[i]
    dst[OUT_PLUNGE] = o[K.O_PL]
    return True


@njit
def joint_into(out, n, s, F, dst):
    """The joint's outputs after roller 1's: the other
    rollers' forces and contact points (0 where absent), the joint on the housing at the
    contact radii s + contact_y [m], the pressing load per roller F [N].  Returns whether all
    are finite (nothing is written otherwise)."""
    two, three = n > 1, n > 2
    fx2 = out[1, K.O_FX] if two else 0.0
    fy2 = out[1, K.O_FY] if two else 0.0
    cy2 = out[1, K.O_CY] if two else 0.0
    cz2 = out[1, K.O_CZ] if two else 0.0
    fx3 = out[2, K.O_FX] if three else 0.0
    fy3 = out[2, K.O_FY] if three else 0.0
    cy3 = out[2, K.O_CY] if three else 0.0
    cz3 = out[2, K.O_CZ] if three else 0.0
    X, Y, T = _housing(out[0, K.O_FX], out[0, K.O_FY], s + out[0, K.O_CY], fx2, fy2, s + cy2,
                       fx3, fy3, s + cy3)
    return _put(dst, OUT_FX_2, (fx2, fy2, cy2, cz2, fx3, fy3, cy3, cz3, X, Y, T, F))


@njit
def _roller(Y, P, OP, W, out, jump):
    """One roller's step at the inputs in its OP, its operating point derived (oppoint.derive:
    jump), W its work arrays (layout.Work).  False: the step ran out of its budget
    (run_substeps)."""
    inputs_moved(P, W.hs, jump)
    return run_substeps(Y, P, K.Drive(OP[OP_THETA], OP[OP_W], OP[OP_X0], 0.0), OP[OP_H],
                        0 if OP[OP_NOSTEP] > 0.0 else int(OP[OP_N]), out, W, None)


@njit
def step_roller(Y, P, OP, W, out, dst):
    """One roller's communication step at the inputs in its own OP (lifecycle.step: one roller): W its
    work arrays (layout.Work), out its output vector, dst the FMU's outputs (N_OUT).  Returns
    step's codes."""
    if not _roller(Y, P, OP, W, out, derive_op(P, OP)):
        return 3
    if not outputs_into(out, OP[OP_F], dst):
        return 2
    return 1   # (joint_into then, at the caller's hand: it takes the output vector as a row)


@njit
def spider_into(out, n, theta, s, F, head, free, dst):
    """The spider's outputs: its centre in the housing frame (Eq. (5)'s orbit at roller 1's
    whirl angle and theta [rad], s [m]; a free spider's pose off it in the header row head) and
    the pressing load each trunnion carries [N] (prescribed: F where a roller is; free: the
    spider's balance).  Returns whether all are finite (nothing is written otherwise)."""
    X, Y = spider.orbit(s, theta, out[0, K.O_X])
    F1, F2, F3 = F, (F if n > 1 else 0.0), (F if n > 2 else 0.0)
    if free:
        X += head[K.OP_SP_QX]
        Y += head[K.OP_SP_QY]
        F1, F2, F3 = head[K.OP_SP_F1], head[K.OP_SP_F2], head[K.OP_SP_F3]
    return _put(dst, OUT_SPIDER_X, (X, Y, F1, F2, F3))


@njit
def joint_operating_points(n, P, OP):
    """Each roller's OP row (under the header row) takes the header's inputs and its operating
    point: the first derived (oppoint.derive), the others copied (the rollers share their
    parameters, JointModel: one derive serves them all).  Returns derive's jump."""
    head = OP[0]
    jump = -1.0
    for i in range(n):
        row = OP[i + 1]
        for j in (OP_THETA, OP_W, OP_FP, OP_TQ, OP_DT, OP_VP):
            row[j] = head[j]
        if i == 0:
            jump = derive_op(P[0], row)
        else:
            copy_op(P[0], OP[1], P[i], row)
    return jump


@njit
def step_joint(n, Y, P, OP, Wn, out, dst):
    """A joint of n rollers in one call (lifecycle.step: a joint): OP a header row, whose inputs
    every roller takes, over the rollers' own rows; every other array the rollers' arrays as
    rows (Wn: their layout.Work, each array one row a roller).  The outputs are roller 1's and
    the joint's.  Returns lifecycle.step's codes."""
    if P[0, K.P_SPIDER] == SPIDER_FREE:
        return step_free_spider(n, Y, P, OP, Wn, out, dst)
    jump = joint_operating_points(n, P, OP)
    total = 0.0   # left to right, as lifecycle.joint_outputs
    for i in range(n):
        if not _roller(Y[i], P[i], OP[i + 1], K.Work(Wn.L[i], Wn.res[i], Wn.Y1[i], Wn.Y2[i],
                                                      Wn.G[i], Wn.A[i], Wn.b[i], Wn.hs[i],
                                                      Wn.GW[i]), out[i], jump):
            return 3
        total += out[i, K.O_FZ]
    if not math.isfinite(total) or not outputs_into(out[0], OP[1, OP_F], dst):
        return 2
    if not joint_into(out, n, P[0, K.P_S], OP[1, OP_F], dst):
        return 2
    if not spider_into(out, n, OP[1, OP_THETA], P[0, K.P_S], OP[1, OP_F], OP[0], False, dst):
        return 2
    dst[OUT_FZ_JOINT] = total
    dst[OUT_FZ_2] = out[1, K.O_FZ] if n > 1 else 0.0
    dst[OUT_FZ_3] = out[2, K.O_FZ] if n > 2 else 0.0
    return 1


# the free spider's joint step (spider = 1), which step_joint hands a joint to: imported last,
# as it steps the rollers with this module's functions
from .free_spider import step_free_spider  # noqa: E402
