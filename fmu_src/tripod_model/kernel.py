"""The contact model's step: n substeps of the integrator the parameters name
(layout.py names them), then the outputs.  Scalar math only so that numba compiles it (jit.py).

Frame (model.md): groove fixed, groove axis = z axis through the origin, x = pressing
direction, y = trunnion axis (nominal).  Forces are reported from the roller on the groove.
"""

from . import oppoint
from .jit import compiled_copies, njit
from .assembly import resolved_forces
from . import bdf2, genalpha
from .bdf2 import bdf2_steps
from .contact import groove_contact
from .euler import adaptive_steps, extrapolated_step, substep
from .genalpha import ga_steps
from .motion import line_kinematics, roller_motion
from .layout import (BEAR_IDEAL, BEAR_RESOLVED, H_TAKEN, INT_ADAPTIVE, INT_DEFAULT, INT_EXTRAPOLATED, O_CY, O_CZ,
    O_FN, O_FX, O_FY, O_FZ, O_PL, O_SLIP, O_SPIN, O_X, P_BEAR, P_INTEG, P_VP, R_FN, R_FX, R_FY,
    R_FZ, R_PY, R_PZ, R_SLIP, Y_OM, Y_PL, Y_X)


# the operating point at OP's inputs (oppoint.derive), compiled with the callees it names;
# oppoint itself stays plain Python (jit.compiled_copies leaves it untouched)
_op = compiled_copies(oppoint, oppoint.FUNCTIONS)
derive_op, copy_op = _op.derive, _op.copy_derived


@njit
def inputs_moved(P, hs, jump):
    """The inputs changed at this communication point (oppoint.derive's ``jump``): the default
    integrator takes it as its module says (genalpha.inputs_jumped, bdf2.inputs_jumped); the
    others are one-step methods that need nothing."""
    if P[P_INTEG] != INT_DEFAULT:
        return
    if P[P_BEAR] == BEAR_RESOLVED:
        bdf2.inputs_jumped(P, hs, jump)
    else:
        genalpha.inputs_jumped(P, hs, jump)


@njit
def run_substeps(Y, P, drive, h, n, out, W, NW):
    """Advance Y by n substeps of h [s] at the held inputs drive (layout.Drive); write the
    outputs at the end.  W: the roller's work arrays (layout.Work); NW: the needle work arrays
    (layout.NeedleWork) with the resolved bearing, else None.

    The integrator P[P_INTEG] names (layout.py): INT_EULER, INT_EXPLICIT: n plain
    substeps (euler.substep); INT_EXTRAPOLATED: each Richardson-extrapolated from one step of h
    and two of h/2 (second order, L-stable: the scheme of LIMEX/SEULEX with two stages);
    INT_ADAPTIVE: the same with its substep chosen by its own error estimate
    (euler.adaptive_steps); INT_DEFAULT: generalized-alpha with the ideal or lumped bearing
    (genalpha.ga_steps), BDF2 with the needle-resolved one (bdf2.bdf2_steps).
    """
    hs = W.hs
    Y[Y_PL] += P[P_VP] * (h * n)     # the plunge: the held plunge speed's exact integral
    if P[P_INTEG] == INT_DEFAULT and P[P_BEAR] != BEAR_RESOLVED:
        ga_steps(Y, P, drive, h, n, W, NW)
        n = 0
    elif P[P_INTEG] == INT_DEFAULT:   # the needle-resolved bearing: BDF2, roller and row in one system
        if NW is not None:    # (always, here; the test lets numba drop it from the others)
            bdf2_steps(Y, P, drive, h, n, W, NW)
        n = 0
    elif P[P_INTEG] >= INT_ADAPTIVE:
        adaptive_steps(Y, P, drive, h * n, h, W, NW)
        n = 0
    extrap = P[P_INTEG] == INT_EXTRAPOLATED
    for _ in range(n):
        if extrap:
            extrapolated_step(Y, P, drive, h, W, NW)
        else:
            substep(Y, P, drive, h, W, NW)
        hs[H_TAKEN] += 1.0   # substeps taken, as the adaptive ones count theirs
    # outputs at the end of the step (forces on the groove = minus those on the roller)
    L, res = W.L, W.res
    line_kinematics(Y[Y_X], drive.w, drive.theta, P, L)
    c, v, wr, e1, e2 = roller_motion(Y, drive.x0, L, P[P_BEAR] != BEAR_IDEAL)
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
