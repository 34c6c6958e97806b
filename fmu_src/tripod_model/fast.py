"""The contact model's communication step as a C function, for the FMU's native layer: a step
after the first (at any inputs in range and any step size: its operating point is derived
again when they change) runs without entering Python, so a doStep costs what the kernel costs
(the contact FMU near the bare FMI boundary).  Ideal and lumped bearing, one roller or a joint
of three (JointModel: the rollers' arrays as rows of one array each); the needle-resolved
bearing steps through Python.

ContactModel.step (model.py) keeps the operating point in OP and publishes the addresses of
the arrays (at layout's FA_ places); the slave offers ``step`` with them as a slavekit.FastStep, the
native layer (fmu_src/native/fmi2_python.c) calls it, and the slave (TripodRoller.py)
reconciles its counters when Python is next entered.
"""
import math

from numba import carray, cfunc, types

from . import layout as K
from .kernel import copy_op, derive_op, inputs_moved, run_substeps
from .jit import njit

from .layout import (OP_DT, OP_F, OP_FP, OP_H, OP_LEN, OP_N, OP_NOSTEP, OP_NROLL, # noqa: F401
    OP_THETA, OP_TQ, OP_VP, OP_W, OP_X0, N_OUT, OUT_FX_2, OUT_FZ_2, OUT_FZ_3,
    OUT_FZ_JOINT, OUT_PLUNGE)
from reduced_model.housing import housing_forces
from reduced_model.thrust import fz_mod

_housing = njit(housing_forces)
_fz_mod = njit(fz_mod)

# int32_t step(double **args): args[K.FA_Y] the state's address, ... (layout's FA_ places)
SIGNATURE = types.int32(types.CPointer(types.CPointer(types.float64)))


@njit
def outputs_into(o, F_press, dst):
    """The FMU's outputs (OUTPUT_NAMES) of one roller from the kernel's output vector o, as
    ContactModel.outputs and JointModel.step compute them.  Returns whether all are finite
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
    """The joint's outputs after roller 1's (JointModel.step, model._joint_outputs): the other
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
    vals = (fx2, fy2, cy2, cz2, fx3, fy3, cy3, cz3, X, Y, T, F)
    for v in vals:
        if not math.isfinite(v):
            return False
    for i in range(len(vals)):
        dst[OUT_FX_2 + i] = vals[i]
    return True


@njit
def _roller(Y, P, OP, W, out, jump):
    """One roller's step at the inputs in its OP, its operating point derived (oppoint.derive:
    jump), W its work arrays (layout.Work)."""
    inputs_moved(P, W.hs, jump)
    run_substeps(Y, P, K.Drive(OP[OP_THETA], OP[OP_W], OP[OP_X0]), OP[OP_H],
                 0 if OP[OP_NOSTEP] > 0.0 else int(OP[OP_N]), out, W, None)


@cfunc(SIGNATURE, nopython=True, cache=True)
def step(args):
    """One communication step at the inputs in OP (their operating point derived again when
    they changed: oppoint.derive); 1: outputs written to OUT, 2: a non-finite output (nothing
    written; the state has moved, as in the Python step).  args: the arrays' addresses in
    layout's FA_ places.

    OP[OP_NROLL] = n > 0: a joint of n rollers (JointModel.fast_arrays).  OP is then a header
    row, whose inputs (where the native layer writes a master's values) every roller takes,
    over the n rollers' own OP rows; every other array holds the rollers' arrays one after the
    other.  The outputs are roller 1's and the joint's (JointModel.step)."""
    pY, pP, pOP, pOUT = args[K.FA_Y], args[K.FA_P], args[K.FA_OP], args[K.FA_OUT]
    pL, pres, pY1, pY2 = args[K.FA_L], args[K.FA_RES], args[K.FA_Y1], args[K.FA_Y2]
    pG, pA, pb, phs = args[K.FA_G], args[K.FA_A], args[K.FA_B], args[K.FA_HS]
    pGW, pout = args[K.FA_GW], args[K.FA_OUTV]
    head = carray(pOP, (OP_LEN,))
    n = int(head[OP_NROLL])
    dst = carray(pOUT, (N_OUT,))
    if n == 0:
        out = carray(pout, (K.O_LEN,))
        W = K.Work(carray(pL, (K.L_LEN,)), carray(pres, (K.R_LEN,)), carray(pY1, (K.Y_LEN,)),
                   carray(pY2, (K.Y_LEN,)), carray(pG, (K.NV, 3)), carray(pA, (K.NV, K.NV)),
                   carray(pb, (K.NV,)), carray(phs, (K.H_LEN,)), carray(pGW, (K.NV + 8, K.NV)))
        P1 = carray(pP, (K.P_LEN,))
        _roller(carray(pY, (K.Y_LEN,)), P1, head, W, out, derive_op(P1, head))
        if not outputs_into(out, head[OP_F], dst):
            return 2
        # (the same output array seen as one row: no reshape, whose helper the prebuilt
        # library does not carry)
        return 1 if joint_into(carray(pout, (1, K.O_LEN)), 1, P1[K.P_S],
                               head[OP_F], dst) else 2
    OP = carray(pOP, (n + 1, OP_LEN))
    Y, P = carray(pY, (n, K.Y_LEN)), carray(pP, (n, K.P_LEN))
    L, res = carray(pL, (n, K.L_LEN)), carray(pres, (n, K.R_LEN))
    Y1, Y2 = carray(pY1, (n, K.Y_LEN)), carray(pY2, (n, K.Y_LEN))
    G, A = carray(pG, (n, K.NV, 3)), carray(pA, (n, K.NV, K.NV))
    b, hs = carray(pb, (n, K.NV)), carray(phs, (n, K.H_LEN))
    GW, out = carray(pGW, (n, K.NV + 8, K.NV)), carray(pout, (n, K.O_LEN))
    total = 0.0   # left to right, as JointModel.step
    jump = -1.0
    for i in range(n):
        row = OP[i + 1]
        for j in (OP_THETA, OP_W, OP_FP, OP_TQ, OP_DT, OP_VP):
            row[j] = head[j]
        # the rollers share their parameters (JointModel): one derive serves them all
        if i == 0:
            jump = derive_op(P[0], row)
        else:
            copy_op(P[0], OP[1], P[i], row)
        _roller(Y[i], P[i], row, K.Work(L[i], res[i], Y1[i], Y2[i], G[i], A[i], b[i], hs[i], GW[i]),
                out[i], jump)
        total += out[i, K.O_FZ]
    if not math.isfinite(total) or not outputs_into(out[0], OP[1, OP_F], dst):
        return 2
    if not joint_into(out, n, P[0, K.P_S], OP[1, OP_F], dst):
        return 2
    dst[OUT_FZ_JOINT] = total
    dst[OUT_FZ_2] = out[1, K.O_FZ] if n > 1 else 0.0
    dst[OUT_FZ_3] = out[2, K.O_FZ] if n > 2 else 0.0
    return 1
