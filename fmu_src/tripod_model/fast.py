"""The contact model's communication step as a C function, for the FMU's native layer: a step
at unchanged inputs (the same inputs and step size as the last one) runs without entering
Python, so a doStep costs what the kernel costs (issue 13: the contact FMU near the bare FMI
boundary).  Ideal and lumped bearing, one roller; everything else steps through Python.

ContactModel.step (model.py) keeps the operating point in OP and publishes the addresses of
the arrays; the native layer (fmu_src/native/fmi2_python.c, fast_step) calls ``step`` with
them; the slave (TripodRoller.py) reconciles its counters when Python is next entered.
"""
import math

from numba import carray, cfunc, types

from . import kernel as K
from .jit import njit

from .layout import (OP_F, OP_H, OP_LEN, OP_N, OP_NOSTEP, OP_THETA, OP_W,  # noqa: F401
                     OP_X0, N_OUT, OUTPUT_NAMES)

_d = types.CPointer(types.float64)
SIGNATURE = types.int32(*([_d] * 14))


@njit
def outputs_into(o, F_press, dst):
    """The FMU's outputs (OUTPUT_NAMES) of one roller from the kernel's output vector o, as
    ContactModel.outputs and JointModel.step compute them.  Returns whether all are finite
    (nothing is written otherwise)."""
    Fx = o[K.O_FX]
    Fz_mod = o[K.O_FZ] * F_press / Fx if Fx > 1e-9 * max(F_press, 1.0) else 0.0
    vals = (Fx, o[K.O_FY], o[K.O_FZ], Fz_mod, Fx - F_press, o[K.O_CY], o[K.O_CZ], o[K.O_SLIP],
            o[K.O_SPIN], o[K.O_FZ], 0.0, 0.0)
    for v in vals:
        if not math.isfinite(v):
            return False
    for i in range(N_OUT):
        dst[i] = vals[i]
    return True


@cfunc(SIGNATURE, nopython=True, cache=True)
def step(pY, pP, pOP, pOUT, pL, pres, pY1, pY2, pG, pA, pb, phs, pGW, pout):
    """One communication step at the inputs in OP (their operating point derived again when
    they changed: oppoint.derive); 1: outputs written to OUT, 2: a non-finite output (nothing
    written; the state has moved, as in the Python step)."""
    Y = carray(pY, (K.Y_LEN,))
    P = carray(pP, (K.P_LEN,))
    OP = carray(pOP, (OP_LEN,))
    out = carray(pout, (K.O_LEN,))
    K.derive_op(P, OP)
    K.run_substeps(Y, P, OP[OP_THETA], OP[OP_W], OP[OP_F], OP[OP_X0], OP[OP_H],
                   0 if OP[OP_NOSTEP] > 0.0 else int(OP[OP_N]), out, carray(pL, (17,)), carray(pres, (19,)),
                   carray(pY1, (K.Y_LEN,)), carray(pY2, (K.Y_LEN,)),
                   carray(pG, (K.NV, 3)), carray(pA, (K.NV, K.NV)), carray(pb, (K.NV,)),
                   None, carray(phs, (5 + K.NV,)), carray(pGW, (K.NV + 8, K.NV)))
    return 1 if outputs_into(out, OP[OP_F], carray(pOUT, (N_OUT,))) else 2
