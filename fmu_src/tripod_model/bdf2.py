"""Integrator 4 with the needle-resolved bearing: linearly implicit variable-step BDF2, roller
and needle row in one system (rowsolve.coupled_solve).
"""

import math

from .jit import njit
from .assembly import hold_slide, resolved_row_terms, roller_system
from .contact import groove_stiffness_x, tilt_drag
from .oppoint import JUMP_RELAX, JUMP_STEP, LOAD_RELAX
from .steplib import extrapolated_step
from .rowsolve import coupled_solve
from .layout import (Drive, H_GA, H_PASSES, H_REJECTED, H_SUB, H_TAKEN, N_F, N_I1, N_I3, N_MN, N_N,
    N_RN, P_DF, P_IS, P_IT, P_M_ROLLER, P_NEWTON_PASSES, P_NEWTON_TOL, P_R_ROLLER, P_TRAVERSE,
    V_POS, V_ROT, V_VEL, Y_LEN, Y_X)

# A step input (what the ideal bearing's generalized-alpha step takes as one: the slip's
# amplitude moved by more than JUMP_STEP v_st, or the pressing load by more than
# LOAD_RELAX of itself): the history across the jump and the substep that resolves the
# row's steady running (about 3 us) leave the row's response to it 5-12 % of order 3 off a
# fine reference (one roller, 10 Hz: omega and theta +-10 %).  The row answers a step within
# about a millisecond, so the communication steps of the next BDF_FINE_TIME (at least
# BDF_FINE_STEPS of them) take substeps of h / BDF_FINE_SPLIT, the last h/2 (its first
# substep restarts BDF2 by the one-step start: a ratio above 2).  h/16, not h/4:
# at a launch's 45 kN the row's answer to a 10 % step in torque or theta missed
# the reference by 1.2-1.4 % of order 3 at h/4 (8 deg; at 25 deg theta by 9-12 %), 0.6-0.7 %
# (2.9 % and 0.8 %) at h/16 (one Newton pass).  A step input from JUMP_STEP on, not from
# JUMP_RELAX (0.02 v_st, an omega step of about 0.5 %), though with two Newton passes that
# takes omega +-1 % from 0.97 % to 0.09-0.13 % and theta +-1 % from 3-5 % to 0.6 %
# (docs/integrators.md): a master's 1 % noise, or a run-up at 1e-3 s at low speed, would make
# every step a step input (16x the substeps).  Those smaller jumps take BDF_RESTART instead.
# hs[H_GA]: BDF_STEP_IN from inputs_jumped, BDF_STEP_IN minus their number at the first of
# those steps, one up at each after; the last is at BDF_STEP_IN - 1.
BDF_STEP_IN = -3.0
BDF_FINE_TIME = 8e-4   # [s]
BDF_FINE_STEPS = 3
BDF_FINE_SPLIT = 16
# A smaller jump of the slip, above JUMP_RELAX v_st (an omega step of about 0.5 %; a master's
# ramp moves it by about 0.004 v_st a step), restarts BDF2 by one backward-Euler substep (the
# same step with no history, r = 0): the velocities from before the jump, carried across it, are
# a first-order error in the substep.  Omega +-1 % at 300 N m, single samples against h/20 (the
# default's passes): 0.89-0.99 % of order 3 with the history (sixteen realizations),
# 0.64-0.83 % restarted (five).
# hs[H_GA] = BDF_RESTART: the next substep restarts so.
BDF_RESTART = 2.0


@njit
def inputs_jumped(P, hs, jump):
    """The inputs changed at this communication point (oppoint.derive: ``jump`` the change of
    the slip's amplitude over v_st, -1 for none; P[P_DF] the pressing load's relative change):
    a step input takes the communication steps of the next BDF_FINE_TIME in finer substeps
    (BDF_STEP_IN), a smaller jump of the slip one backward-Euler substep first (BDF_RESTART)."""
    if hs[H_GA] != 0.0 and jump >= 0.0 and (jump > JUMP_STEP or P[P_DF] > LOAD_RELAX):
        hs[H_GA] = BDF_STEP_IN
    elif hs[H_GA] == 1.0 and jump > JUMP_RELAX:
        hs[H_GA] = BDF_RESTART


@njit
def bdf2_steps(Y, P, drive, h, n, W, NW):
    """n BDF2 substeps of h [s] (bdf2_substep) with the needle-resolved bearing, after a step
    input h / BDF_FINE_SPLIT or h/2 instead (inputs_jumped); W.Y2 carries the previous state
    and hs[H_SUB] the previous substep from call to call, hs[H_GA] whether they are valid (0:
    not; 1, BDF_RESTART or a step input's countdown: valid), hs[H_TAKEN] counts substeps.
    drive.x0 is the pressing offset at the step's end; with drive.x0_rate it ramps there over
    the n substeps.  Returns True: it always finishes (the integrators' one call)."""
    ny = Y.shape[0]
    Y2, hs = W.Y2, W.hs
    if hs[H_GA] < 0.0:     # a step input's countdown (BDF_STEP_IN)
        if hs[H_GA] == BDF_STEP_IN:   # the first: how many steps make BDF_FINE_TIME
            hs[H_GA] = BDF_STEP_IN - max(BDF_FINE_STEPS,
                                         math.ceil(BDF_FINE_TIME / (h * n) - 1e-6))
        else:
            hs[H_GA] += 1.0
        last = hs[H_GA] > BDF_STEP_IN - 1.5
        k = 2 if last else BDF_FINE_SPLIT
        if last:     # then the steady substep
            hs[H_GA] = 1.0
        h = h / k
        n = n * k
    ramp = drive
    for i in range(n):
        if ramp.x0_rate != 0.0:   # the offset's ramp after a load change: at the substep's end
            drive = Drive(ramp.theta, ramp.w, ramp.x0 - ramp.x0_rate * ((n - 1 - i) * h),
                          ramp.x0_rate)
        if hs[H_GA] == 0.0 or h > 2.0 * hs[H_SUB]:
            # no history yet (or a step more than twice the last, where variable-step BDF2
            # nears its stability limit): one extrapolated split step (re)starts it
            for i in range(ny):
                Y2[i] = Y[i]
            extrapolated_step(Y, P, drive, h, W, NW)
            hs[H_GA] = 1.0
        elif hs[H_GA] == BDF_RESTART:    # the slip jumped: no history across it
            bdf2_substep(Y, P, drive, h, math.inf, W, NW)
            hs[H_GA] = 1.0
        else:
            bdf2_substep(Y, P, drive, h, hs[H_SUB], W, NW)
        hs[H_SUB] = h
        hs[H_TAKEN] += 1.0
    return True


@njit
def bdf2_substep(Y, P, drive, h, hp, W, NW):
    """One linearly implicit BDF2 step of h [s] (the previous step hp; inf: backward Euler) with
    the needle-resolved bearing: Y = y_n -> y_{n+1}, Yp = W.Y2 = y_{n-1} -> y_n, YL = W.Y1 work.

    y_{n+1} - a1 y_n + a2 y_{n-1} = g f(y_{n+1}) (variable-step BDF2, g = beta h), linearized
    at the predicted state y_L: velocities extrapolated linearly, positions
    q_L = a1 q_n - a2 q_{n-1} + g v_L (the BDF2 position rule, so the correction e moves
    positions by g e_v and the stiffness needs no K v term): (M + g D + g^2 K) e_v =
    g F(y_L) - M (v_L - a1 v_n + a2 v_{n-1}).  One contact evaluation a pass; second order with
    any tangent (the linearization error is O(e^2) with e = O(h^2)).

    Up to P[P_NEWTON_PASSES] passes (newton_passes, default 2): each later one solves the same
    equation again, linearized at the state the pass before reached (Newton), where that pass's
    correction exceeded P[P_NEWTON_TOL] (newton_tol) and unless its own is larger (not contracting:
    then that pass's state stays; counted in hs[H_REJECTED]).  One pass leaves, at large joint
    angles and high loads, a period-2 oscillation of the roller's velocities from substep to
    substep (the step's own, not the model's) and makes the row's single samples depend on
    rounding; a second where the first moved the velocities by more than 3e-4 m/s (a third of
    the substeps in the paper's scene, half at 300 N m, nearly all at 30-45 kN and 25 deg)
    removes both, its substep 36 % longer: 1.25 times one pass's run in the paper's scene
    (docs/integrators.md#needle-resolved-bearing)."""
    Yp, YL = W.Y2, W.Y1
    r = h / hp
    a1 = (1.0 + r) ** 2 / (1.0 + 2.0 * r)
    a2 = r * r / (1.0 + 2.0 * r)
    g = (1.0 + r) / (1.0 + 2.0 * r) * h
    n = int(NW.NP[N_N])
    _bdf2_predict(Y, Yp, YL, r, a1, a2, g, n)
    YL[Y_X] = Y[Y_X] + h * drive.w
    limit = math.inf
    for k in range(max(1, int(P[P_NEWTON_PASSES]))):
        if k > 0:
            if limit <= P[P_NEWTON_TOL]:   # the linearization's error, O(e^2), is small enough
                break
            W.hs[H_PASSES] += 1.0
        e = _bdf2_pass(Y, Yp, YL, P, drive, g, (a1, a2), W, NW, n, limit)
        if e < 0.0:      # not contracting: Newton would go astray; keep the pass before
            W.hs[H_REJECTED] += 1.0
            break
        limit = e
    for i in range(Y.shape[0]):
        Yp[i] = Y[i]
        Y[i] = YL[i]


@njit
def _bdf2_pass(Y, Yp, YL, P, drive, g, a, W, NW, n, limit):
    """One linear solve of bdf2_substep's equation, linearized at YL (the predicted state, or
    the one the pass before reached), YL moved by its correction; a = (a1, a2).  Returns the
    correction's size (_correction_size) [m/s; 0 with one pass], or -1 without moving YL
    where it exceeds ``limit``."""
    A, b = W.A, W.b
    a1, a2 = a
    m = P[P_M_ROLLER]
    It = P[P_IT]
    NP = NW.NP
    x = YL[Y_X]
    # the groove friction and the spin moment implicit with their secants: saturated, the
    # friction's tangent is ~0 and the step applied it explicitly, h mu f_n r^2 / I_s on the
    # spin; above 11-15 kN (a third of a launch) that overshot the tanh's range and the spin
    # flipped every substep.  The secant (>= the tangent) cannot overshoot; the spin moment,
    # explicit, cost 1.9 % of order 3 at 45 kN (docs/integrators.md)
    c, e1, e2 = roller_system(YL, P, drive, x, g, W, True, True, 6, True)
    drag = tilt_drag(It, W.L, e1, e2)
    kh = groove_stiffness_x(P, W.res, c)
    resolved_row_terms(YL, P, NW, drive.theta, x, g, W, (e1, e2), kh, drag, True)
    mr = (m, P[P_IS], m, It, It, m)
    for i in range(6):
        vi = V_VEL[i]
        b[i] = g * b[i] - mr[i] * (YL[vi] - a1 * Y[vi] + a2 * Yp[vi])
    trav = P[P_TRAVERSE] > 0.5
    if not trav:
        hold_slide(A, b, 6)
    # the needles: the same rule on the ring (right-hand side h FN in ring_solve)
    FN, AN = NW.FN, NW.AN
    mn, I1, I3 = NP[N_MN], NP[N_I1], NP[N_I3]
    for j in range(n):
        q = Y_LEN + N_F * j
        mj = (mn, mn, mn, I1, I1, I3)
        for i in range(6):
            FN[j, i] -= mj[i] * (YL[q + 5 + i] - a1 * Y[q + 5 + i] + a2 * Yp[q + 5 + i]) / g
            AN[j, i, i] += mj[i]
    coupled_solve(A, b, NW, g, n, trav)
    # (one pass has no use for the size)
    e = _correction_size(b, FN, n, P[P_R_ROLLER], NP[N_RN]) if P[P_NEWTON_PASSES] > 1.5 else 0.0
    if e > limit:
        return -1.0
    _bdf2_correct(YL, b, FN, g, n)
    return e


@njit
def _correction_size(b, FN, n, r, rn):
    """Root sum of squares of a pass's velocity corrections [m/s]: b the roller's, FN each
    needle's, rotations [rad/s] times the roller's radius r or the needle's rn [m]."""
    s = 0.0
    for i in range(6):
        v = b[i] * (r if V_ROT[i] > 0.0 else 1.0)
        s += v * v
    for j in range(n):
        for i in range(6):
            v = FN[j, i] * rn if i >= 3 else FN[j, i]
            s += v * v
    return math.sqrt(s)


@njit
def _bdf2_predict(Y, Yp, YL, r, a1, a2, g, n):
    """bdf2_substep's predicted state YL: velocities extrapolated from y_n, y_{n-1} (step ratio
    r), positions by the BDF2 rule q_L = a1 q_n - a2 q_{n-1} + g v_L (needle tilts: t1' = w2,
    t2' = -w1)."""
    for i in range(6):
        vi, qi = V_VEL[i], V_POS[i]
        YL[vi] = Y[vi] + r * (Y[vi] - Yp[vi])
        if qi >= 0:
            YL[qi] = a1 * Y[qi] - a2 * Yp[qi] + g * YL[vi]
    for j in range(n):
        q = Y_LEN + N_F * j
        for i in range(5, 11):
            YL[q + i] = Y[q + i] + r * (Y[q + i] - Yp[q + i])
        for i in range(3):
            YL[q + i] = a1 * Y[q + i] - a2 * Yp[q + i] + g * YL[q + 5 + i]
        YL[q + 3] = a1 * Y[q + 3] - a2 * Yp[q + 3] + g * YL[q + 9]
        YL[q + 4] = a1 * Y[q + 4] - a2 * Yp[q + 4] - g * YL[q + 8]


@njit
def _bdf2_correct(YL, b, FN, g, n):
    """A pass's new state in YL: YL plus the velocity corrections (b: the roller's unknowns,
    FN: each needle's), positions moved by g times them."""
    for i in range(6):
        vi, qi = V_VEL[i], V_POS[i]
        YL[vi] += b[i]
        if qi >= 0:
            YL[qi] += g * b[i]
    for j in range(n):
        q = Y_LEN + N_F * j
        for i in range(6):
            YL[q + 5 + i] += FN[j, i]
        for i in range(3):
            YL[q + i] += g * FN[j, i]
        YL[q + 3] += g * FN[j, 4]
        YL[q + 4] -= g * FN[j, 3]
