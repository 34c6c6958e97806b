"""The shared step library: the linearly implicit Euler substep over assembly.roller_system
(integrator 0; integrator 2, explicit, is its P switch), its Richardson extrapolation to second
order (integrator 1) and the adaptive substeps on that extrapolation's error (integrator 3).
L-stable one-step methods, which the other integrators (genalpha.py, bdf2.py) call for their
hard steps: the substeps right after a step input, and where their own method does not settle.
Those import this library and nothing of each other, as scipy's ODE methods import only their
shared base.
"""
import math

from .jit import inline, njit
from .linalg import solve_small
from .budget import ADAPT_FLOOR, ADAPT_TRIES_MIN, ADAPT_TRIES_PER
from .assembly import advance_roller, hold_slide, lumped_radial_step, lumped_row_terms, resolved_row_terms, roller_system
from .contact import groove_stiffness_x, row_damping, tilt_drag
from .layout import (BEAR_IDEAL, BEAR_LUMPED, BEAR_RESOLVED, FAIL_ESTIMATE, FAIL_FLOOR, FAIL_NONE,
    FAIL_TRIES, H_FAIL, H_FAIL_DONE, H_FAIL_H, H_REJECTED, H_SUB, H_TAKEN, H_USE_FLOOR,
    H_USE_TRIES, INT_EXTRAPOLATED, P_BEARING, P_HMAX, P_INTEGRATOR, P_IT, P_M_ROLLER, P_R_ROLLER, P_STEP_TOLERANCE, P_TRAVERSE,
    P_VST_OP, R_FX, Y_B1D, Y_B2D, Y_ED, Y_OM, Y_UD, Y_WD, Y_X)


@njit
def substep(Y, P, drive, h, W, NW):
    """One linearly implicit Euler substep of h [s] on the state Y (in place).

    Velocities v = (ud, om[, wd, b1d, b2d][, ed]): (M - h J + h^2 K) dv = h (Q - h K v), with J
    the friction Jacobian (the friction slope mu f_n / v_st against the roller's mass and
    inertia is the stiff part) and K the needle row's stiffness; positions then move with the
    new velocities; the driving motion is taken at the end of the substep (backward in the
    driving terms, so the rolling target is not lagged by a whole substep).
    W: the work arrays (layout.Work; L, res, G, A, b here).
    """
    L, res, A, b = W.L, W.res, W.A, W.b
    m = P[P_M_ROLLER]
    lumped = P[P_BEARING] == BEAR_LUMPED
    resolved = P[P_BEARING] == BEAR_RESOLVED
    sixdof = lumped or resolved
    x = Y[Y_X] + h * drive.w
    Y[Y_X] = x
    nv = 6 if resolved else 5 if lumped else 2
    c, e1, e2 = roller_system(Y, P, drive, x, h, W, sixdof, resolved, nv, False)
    It = P[P_IT]
    drag1 = drag2 = kh = Fr = kr = 0.0
    if sixdof:
        drag1, drag2 = tilt_drag(It, L, e1, e2)
        kh = groove_stiffness_x(P, res, c)
    if lumped:
        Fr, kr = lumped_row_terms(Y, P, L, h, It, drag1, drag2, A, b)
    if resolved:
        resolved_row_terms(Y, P, NW, drive.theta, x, h, W, (e1, e2), kh, (drag1, drag2), False)
    trav = P[P_TRAVERSE] > 0.5
    if not trav:
        hold_slide(A, b, nv)
    for i in range(nv):
        b[i] *= h
    solve_small(A, b, nv)
    advance_roller(Y, b, h, trav, sixdof, resolved, NW)
    if lumped:
        lumped_radial_step(Y, h, m, res[R_FX] + Fr, kh + kr, row_damping(P, kh + kr, m))


@inline
def _whole_and_halves(Yh, Y1, P, drive, h, W, NW):
    """One linearly implicit Euler step of h [s] on Y1 and two of h/2 on Yh (both start from
    the same state): the two estimates of one extrapolated step."""
    substep(Y1, P, drive, h, W, NW)
    substep(Yh, P, drive, 0.5 * h, W, NW)
    substep(Yh, P, drive, 0.5 * h, W, NW)


@inline
def _richardson(Y, Yh, Y1):
    """Y = 2 Yh - Y1: the two halves' result extrapolated against the whole step's, which
    cancels the first-order error of both (second order, still L-stable)."""
    for i in range(Y.shape[0]):
        Y[i] = 2.0 * Yh[i] - Y1[i]


@njit
def extrapolated_step(Y, P, drive, h, W, NW):
    """One substep of h [s] extrapolated (Richardson) from one linearly implicit Euler step of
    h (in W.Y1) and two of h/2: second order, L-stable (integrator 1)."""
    Y1 = W.Y1
    for i in range(Y.shape[0]):
        Y1[i] = Y[i]
    _whole_and_halves(Y, Y1, P, drive, h, W, NW)
    _richardson(Y, Y, Y1)


@njit
def step_error(Y, Y1, P):
    """Scaled error estimate of one extrapolated step: the difference between the two half
    steps (Y) and the whole step (Y1) in the roller's velocities, against tol x v_st (slides)
    and tol x v_st / r (turns): what sets the friction's direction and so the thrust."""
    vs = P[P_STEP_TOLERANCE] * P[P_VST_OP]
    vr = vs / P[P_R_ROLLER]
    e = abs(Y[Y_OM] - Y1[Y_OM]) / vr
    if P[P_TRAVERSE] > 0.5:
        e = max(e, abs(Y[Y_UD] - Y1[Y_UD]) / vs)
    if P[P_BEARING] != BEAR_IDEAL:
        e = max(e, abs(Y[Y_WD] - Y1[Y_WD]) / vs, abs(Y[Y_ED] - Y1[Y_ED]) / vs,
                abs(Y[Y_B1D] - Y1[Y_B1D]) / vr, abs(Y[Y_B2D] - Y1[Y_B2D]) / vr)
    return e


@njit
def adaptive_steps(Y, P, drive, T, h0, W, NW):
    """Advance Y by T [s] with extrapolated substeps chosen by their own error estimate
    (step_error <= 1; up to P[P_HMAX]); hs[H_SUB] carries the substep from call to call (h0 [s]
    the first), hs[H_TAKEN] counts accepted, hs[H_REJECTED] rejected substeps.

    Returns False when the span cannot be finished within the budget (ADAPT_FLOOR,
    ADAPT_TRIES_*): hs[H_FAIL] says why (FAIL_ESTIMATE, FAIL_FLOOR, FAIL_TRIES), hs[H_FAIL_DONE]
    and hs[H_FAIL_H] where; Y is then where the last accepted substep left it."""
    ny = Y.shape[0]
    Y1, Y2, hs = W.Y1, W.Y2, W.hs
    hmax = P[P_HMAX]
    floor = ADAPT_FLOOR * hmax
    budget = ADAPT_TRIES_MIN + ADAPT_TRIES_PER * math.ceil(T / hmax)
    tries = 0.0
    t = 0.0
    hc = hs[H_SUB] if hs[H_SUB] > 0.0 else h0
    hs[H_FAIL] = FAIL_NONE
    while t < T * (1.0 - 1e-12):
        last = hc >= T - t
        hh = T - t if last else hc
        fail = FAIL_NONE
        if tries >= budget:
            fail = FAIL_TRIES
        elif not last and hh < floor:
            fail = FAIL_FLOOR
        if fail != FAIL_NONE:
            return _stopped(hs, fail, t / T, hh)
        tries += 1.0
        if not last:
            hs[H_USE_FLOOR] = max(hs[H_USE_FLOOR], floor / hh)
        for i in range(ny):
            Y1[i] = Y[i]
            Y2[i] = Y[i]
        _whole_and_halves(Y2, Y1, P, drive, hh, W, NW)
        err = step_error(Y2, Y1, P)
        if not math.isfinite(err):
            return _stopped(hs, FAIL_ESTIMATE, t / T, hh)
        fac = 0.9 / math.sqrt(max(err, 1e-12))   # local error of the whole step ~ h^2
        fac = min(4.0, max(0.2, fac))
        if err <= 1.0:
            _richardson(Y, Y2, Y1)
            t += hh
            hs[H_TAKEN] += 1.0
            if not last:            # a step cut short to land on T says nothing of hc
                hc = min(hc * fac, hmax)
        else:
            hs[H_REJECTED] += 1.0
            hc = hh * fac
    hs[H_SUB] = hc
    hs[H_USE_TRIES] = max(hs[H_USE_TRIES], tries / budget)
    return True


@njit
def adaptive_run(Y, P, drive, h, n, W, NW):
    """Integrator 3 behind the integrators' one call (kernel.advance): the span of n substeps
    of h [s] by adaptive_steps, from a first substep of h.  Returns whether it finished."""
    return adaptive_steps(Y, P, drive, h * n, h, W, NW)


@njit
def fixed_steps(Y, P, drive, h, n, W, NW):
    """Integrators 0, 1 and 2 behind the integrators' one call (kernel.advance): n substeps of
    h [s], each a substep or, with P[P_INTEGRATOR] = INT_EXTRAPOLATED, an extrapolated_step;
    hs[H_TAKEN] counts them, as the adaptive ones count theirs.  Returns True (finished)."""
    extrap = P[P_INTEGRATOR] == INT_EXTRAPOLATED
    for _ in range(n):
        if extrap:
            extrapolated_step(Y, P, drive, h, W, NW)
        else:
            substep(Y, P, drive, h, W, NW)
        W.hs[H_TAKEN] += 1.0
    return True


@inline
def _stopped(hs, why, done, h):
    """The adaptive substeps stopped short (adaptive_steps): why (FAIL_*), the share done, the
    substep [s]."""
    hs[H_FAIL], hs[H_FAIL_DONE], hs[H_FAIL_H] = why, done, h
    return False

