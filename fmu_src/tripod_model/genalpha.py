"""Integrator 4 with the ideal or lumped bearing: the generalized-alpha method (Chung & Hulbert
1993) with Newton on the roller's velocity unknowns, and its restarts when a master's inputs
jump (docs/integrators.md).
"""

import math

from .jit import inline, njit
from .linalg import solve_small
from .contact import (groove_contact, groove_stiffness_x, line_kinematics, roller_motion,
    row_damping, row_lever, row_load, row_load_moment, row_play, row_rolling_resistance,
    row_sliding_friction, row_stiffness, row_stroke, tilt_drag)
from .oppoint import JUMP_FULL, JUMP_RELAX, JUMP_STEP, LOAD_RELAX
from .steplib import adaptive_steps
from .layout import (BEAR_LUMPED, H_ACC, H_FACC, H_FALLBACK, H_GA, H_JUMPW, H_RING, H_TAKEN, L_AAX, L_AAY,
    L_AAZ, L_AX, L_AY, L_AZ, L_QZDD, L_SPIN, L_VAX, NV, P_BEARING, P_DF, P_FRICTION_NEEDLE, P_HFREE,
    P_IS, P_IT, P_M_ROLLER, P_QSUM, P_R_ROLLER, P_RINGA, P_ROLLING_RESISTANCE, P_TRAVERSE,
    P_VST_OP, RING_OPEN, RING_QUIET, R_FX, R_FY, R_FZ, R_MX, R_MY, R_MZ, V_POS, V_ROT, V_VEL, W_A,
    W_A0, W_AT, W_D, W_M, W_R, W_RT, W_S, Y_B1, Y_B1D, Y_B2, Y_B2D, Y_E, Y_ED, Y_OM, Y_U, Y_UD,
    Y_W, Y_WD, Y_X)


# generalized-alpha step (integrator 4, ideal and lumped bearing): Chung & Hulbert (1993)
RHO_GA = 0.8   # spectral radius at infinity; 1 (no numerical damping) lets the stick mode
               # ring: order 3 off by 40-200 % at 25-100 us, while 0.6-0.9 all stay below
               # 0.02 % at 25-50 us (paper's scene, ideal bearing)
# Newton stops at velocity increments below GA_NTOL x v_st.  A looser stop (1e-3) gives the same
# order 3 to 5e-6, but where to stop is a choice a last bit can flip: on the floating spider,
# whose lumped rows start each substep from their forces, one ulp of an input grows to 1e-4 of
# Fz_joint there; at 1e-5 it stays below 1e-11, or 2.4e-8 where a flip of the stop leaves a
# step untaken (the lumped row's friction around the loaded arc: at most 3 GA_NTOL of mu f_n;
# 1e-6 with 30 iterations removed that but broke the floating spider's lumped grid, not
# examined further) (docs/integrators.md, "Newton stops at 1e-5")
GA_NTOL = 1e-5
GA_MAXIT = 12


def _ga_coefficients(rho):
    """(alpha_m, alpha_f, gamma, beta) from the spectral radius at infinity rho (Chung &
    Hulbert: second order, maximal damping at infinity for the given rho)."""
    am, af = (2.0 * rho - 1.0) / (rho + 1.0), rho / (rho + 1.0)
    return am, af, 0.5 - am + af, 0.25 * (1.0 - am + af) ** 2


GA_STEP = _ga_coefficients(RHO_GA)


# The step right after the inputs jumped (hs[H_GA] = -1).  The method weighs the forces at
# t_{n+1-alpha_f}, the velocities there (1 - af) v1 + af v0; v0 equilibrated with the old inputs,
# so where friction pins the slip to the new inputs' value within far less than a step, v1
# overshoots that value by af / (1 - af) of the jump (0.8 at rho 0.8) and rings down at -rho a
# step: the one-sample spikes and, with a master that moves the inputs every step, a bias of up
# to 10 % in order 3.  With rho = 0 (af = 0) the forces are taken at t_{n+1}: the slip lands on
# the new value, still second order, at the cost of the same one step.
GA_RESTART = _ga_coefficients(0.0)


@inline
def _restart_coefficients(w):
    """The coefficients of a restart step of weight w in (0, 1] (hs[H_JUMPW]): GA_RESTART at 1,
    below it those of the spectral radius RHO_GA (1 - w), GA_STEP's as w falls to 0: a small
    change of the inputs changes the step by as little (inputs_jumped)."""
    if w >= 1.0:
        return GA_RESTART
    rho = RHO_GA * (1.0 - w)
    am, af = (2.0 * rho - 1.0) / (rho + 1.0), rho / (rho + 1.0)
    return am, af, 0.5 - am + af, 0.25 * (1.0 - am + af) ** 2
GA_RELAX = -2.0        # hs[H_GA]: the next substep by the adaptive substeps (a jump above
                       # oppoint.JUMP_RELAX)
GA_STEP_IN = -3.0      # hs[H_GA]: a step input (above oppoint.JUMP_STEP or LOAD_RELAX): the
                       # communication steps of the next GA_IN_TIME so, at least GA_IN_STEPS;
                       # GA_STEP_IN minus their number at the first, one up at each after
# With the lumped row's friction on the roller's tilt (its lever and line) the slide and the
# tilt about e2 ring together after a step input for about 0.4 ms: the generalized-alpha step
# restarted at 0.2 ms missed the reference by 5-7 % of order 3 (omega +10 %, theta -10 %,
# 10 Hz), at 0.3 ms by 1.4-1.7 %, at 0.4 ms by 0.6-0.7 %, at 0.6 ms by 0.2-0.3 %.
GA_IN_TIME = 4e-4      # [s]
GA_IN_STEPS = 2
# hs[H_GA] after a restart step: the next regular step takes its accelerations from the forces
# at the restart's end (GA_RESTART puts the forces at t_{n+1}: its last Newton evaluation, or
# what its converged equation implies there, kept in hs[H_FACC:]; GA_AFTER_RESTART_AFRESH where
# the drive has moved since: anew)
GA_AFTER_RESTART = 3.0
GA_AFTER_RESTART_AFRESH = 2.0
# hs[H_RING]: the roller's ring (its slide rocking across the groove, oppoint.ring_step), which
# the paper's contact law leaves undamped while the slip saturates the tanh.  RING_OPEN (at the
# start and after a step input: the slip's amplitude moved by more than JUMP_RELAX v_st or
# the load by more than LOAD_RELAX): the substeps resolve it.  Each communication step of
# generalized-alpha steps ends with a verdict: RING_QUIET when the slide's acceleration stayed
# below P_RINGA in every step (the friction has rung it down), else RING_OPEN; quiet, the next
# one takes the free substep P_HFREE (a launch's 45 kN at 10 Hz: 51 us against the ring's
# 9 us).  The free steps are judged too: a ring that a master's small moves or the friction's
# reversals excite shows in the slide's acceleration before the coarser step damps it
# (docs/integrators.md)


@njit
def ga_forces(Y, P, drive, L, res, Q, M):
    """Generalized forces Q [N, N m] and masses M [kg, kg m^2] of the roller's unknowns at the
    state Y (whirl angle Y[Y_X]), the equations of steplib.substep: ideal bearing (2 unknowns:
    m u'' = F.a - m (Q''.a + u a''.a), I_s om' = M.a) or lumped (6: also the slide across the
    load w, the tilts b1, b2 and the radial offset e, with the row's forces).  Returns nv."""
    lumped = P[P_BEARING] == BEAR_LUMPED
    line_kinematics(Y[Y_X], drive.w, drive.theta, P, L)
    c, v, wr, e1, e2 = roller_motion(Y, drive.x0, drive.x0_rate, L, lumped)
    groove_contact(c, v, wr, P, res)
    ax, ay, az = L[L_AX], L[L_AY], L[L_AZ]
    fx, fy, fz, mx, my, mz = res[R_FX], res[R_FY], res[R_FZ], res[R_MX], res[R_MY], res[R_MZ]
    m = P[P_M_ROLLER]
    u = Y[Y_U]
    Q[0] = fx * ax + fy * ay + fz * az - m * (L[L_QZDD] * az + u * (L[L_AAX] * ax + L[L_AAY] * ay + L[L_AAZ] * az))
    Q[1] = mx * ax + my * ay + mz * az
    M[0] = m
    M[1] = P[P_IS]
    nv = 2
    if lumped:
        nv = 6
        It = P[P_IT]
        drag1, drag2 = tilt_drag(It, L, e1, e2)
        e1x, e1y, e1z = e1
        e2x, e2y, e2z = e2
        Fr, kr, kw, q, arc = row_load(P, Y[Y_E])
        stroke = row_stroke(Y, P, drive.theta, ax)
        lag, series = row_play(P, Y[Y_X], drive.w, drive.theta, stroke)
        f1 = f2 = 0.0
        if P[P_FRICTION_NEEDLE] > 0.5 and q > 0.0:
            fa, f1, f2, _j, _j, _j, _j, _j, _j = row_sliding_friction(
                P, q, Y[Y_UD], L[L_VAX], Y[Y_B1D], Y[Y_B2D], row_lever(P, Fr, q), arc, 0.0, series)
            Q[0] -= fa
        if P[P_ROLLING_RESISTANCE] > 0.5 and q > 0.0:
            Q[1] -= row_rolling_resistance(P, q, Y[Y_OM], L[L_SPIN], 0.0)[0]
        kw, kt1, kt2 = row_stiffness(P, kr, kw)
        kx = kr + groove_stiffness_x(P, res, c)     # radial: the row and the groove
        Q[2] = (fx * e2x + fy * e2y + fz * e2z - kw * Y[Y_W]
                - row_damping(P, kw, m) * Y[Y_WD])
        Q[3] = (mx * e1x + my * e1y + mz * e1z - kt1 * Y[Y_B1] - drag1
                - row_damping(P, kt1, It) * Y[Y_B1D] - f1)
        Q[4] = (mx * e2x + my * e2y + mz * e2z - kt2 * Y[Y_B2] - drag2
                - row_damping(P, kt2, It) * Y[Y_B2D] - f2
                + row_load_moment(P, Fr, stroke, lag))
        Q[5] = fx + Fr - row_damping(P, kx, m) * Y[Y_ED]
        M[2] = m
        M[3] = It
        M[4] = It
        M[5] = m
    if P[P_TRAVERSE] < 0.5:
        Q[0] = 0.0
    return nv


@njit
def _ga_residual(Y, Yf, P, drive, h, GW, ra, rr, L, res, Q, co):
    """Residual M ((1 - am) a1 + am a0) - Q(t_f, q_f, v_f) of the generalized-alpha equations at
    the trial accelerations GW[ra] into GW[rr]; GW[W_A0] holds a0, GW[W_M] the masses; co the
    coefficients (GA_STEP or GA_RESTART); the state at t_f into Yf, the forces into Q (the
    work arrays W.Y1, W.b; ga_step); L, res as in ga_forces."""
    am, af, ga, be = co
    nv = 6 if P[P_BEARING] == BEAR_LUMPED else 2
    for i in range(nv):
        a0 = GW[W_A0, i]
        a1 = GW[ra, i]
        iv = V_VEL[i]
        v = Y[iv]
        Yf[iv] = (1.0 - af) * (v + h * ((1.0 - ga) * a0 + ga * a1)) + af * v
        ip = V_POS[i]
        if ip >= 0:
            q = Y[ip]
            Yf[ip] = (1.0 - af) * (q + h * v + h * h * ((0.5 - be) * a0 + be * a1)) + af * q
    Yf[Y_X] = Y[Y_X] + (1.0 - af) * h * drive.w
    ga_forces(Yf, P, drive, L, res, Q, GW[W_M])
    for i in range(nv):
        GW[rr, i] = GW[W_M, i] * ((1.0 - am) * GW[ra, i] + am * GW[W_A0, i]) - Q[i]
    if P[P_TRAVERSE] < 0.5:
        GW[rr, 0] = 0.0


@inline
def _ga_jacobian(Y, Yf, P, drive, h, GW, nv, L, res, Q, co):
    """GW[0:nv, 0:nv]: the residual's Jacobian in the accelerations, column j by a finite
    difference of 1e-4 v_st in unknown j's velocity."""
    vs, r, ga = P[P_VST_OP], P[P_R_ROLLER], co[2]
    for j in range(nv):
        d = 1e-4 * vs / (ga * h) / (r if V_ROT[j] > 0.0 else 1.0)
        for i in range(nv):
            GW[W_AT, i] = GW[W_A, i]
        GW[W_AT, j] += d
        _ga_residual(Y, Yf, P, drive, h, GW, W_AT, W_RT, L, res, Q, co)
        for i in range(nv):
            GW[i, j] = (GW[W_RT, i] - GW[W_R, i]) / d


@inline
def _ga_jacobian_to(GW, nv, co, to):
    """GW[0:nv, 0:nv], the residual's Jacobian under the coefficients co, made the one under
    the coefficients `to` as far as the forces move with the velocities: J = M (1 - am) -
    (1 - af) h (gamma dQ/dv + h beta dQ/dq), the second term scaled by the ratio of (1 - af)
    gamma (a restart step's, for the regular step after it)."""
    c = (1.0 - to[1]) * to[2] / ((1.0 - co[1]) * co[2])
    for i in range(nv):
        for j in range(nv):
            GW[i, j] = c * GW[i, j]
        GW[i, i] += GW[W_M, i] * ((1.0 - to[0]) - c * (1.0 - co[0]))


@inline
def _ga_newton_direction(GW, nv, trav, A, Q):
    """Newton direction GW[W_D] = -J^-1 R (the slide's row held when traverse is off); returns
    the residual's scaled size max |R_i| S_i."""
    for i in range(nv):
        for j in range(nv):
            A[i, j] = GW[i, j]
        Q[i] = -GW[W_R, i]
    if not trav:   # the slide is held: its acceleration stays as it is
        for j in range(nv):
            A[0, j] = 0.0
            A[j, 0] = 0.0
        A[0, 0] = 1.0
        Q[0] = 0.0
    solve_small(A, Q, nv)
    n0 = 0.0
    for i in range(nv):
        GW[W_D, i] = Q[i]
        n0 = max(n0, abs(GW[W_R, i]) * GW[W_S, i])
    return n0


@inline
def _ga_step_size(GW, nv, hga, r):
    """The largest change [m/s] the Newton step GW[W_D] makes to a velocity (a rotation's at
    the radius r [m]; hga = h gamma [s], times the line search's factor for the step it
    took)."""
    e = 0.0
    for i in range(nv):
        e = max(e, abs(hga * GW[W_D, i]) * (r if V_ROT[i] > 0.0 else 1.0))
    return e


@inline
def _ga_converged(size, last, stale, vs):
    """Newton's convergence test, before a step and after one, on a step of `size` [m/s]
    (_ga_step_size) after one of `last`: at most GA_NTOL v_st (vs [m/s]); with a Jacobian
    kept from the step before (stale), contracting by at least 1/2 a step too, so that what is
    left, rate / (1 - rate) times the step, is within it."""
    return size <= GA_NTOL * vs and not (stale and size > 0.5 * last)


@inline
def _ga_line_search(Y, Yf, P, drive, h, GW, nv, n0, L, res, Q, co):
    """The Newton step halved (up to 8 times) until the scaled residual falls below n0 (the
    tanh friction is steep over v_st); trial point in GW[W_AT], its residual in GW[W_RT].
    Returns the step fraction."""
    lam = 1.0
    for _ in range(8):
        for i in range(nv):
            GW[W_AT, i] = GW[W_A, i] + lam * GW[W_D, i]
        _ga_residual(Y, Yf, P, drive, h, GW, W_AT, W_RT, L, res, Q, co)
        n1 = 0.0
        for i in range(nv):
            n1 = max(n1, abs(GW[W_RT, i]) * GW[W_S, i])
        if n1 < n0:
            break
        lam *= 0.5
    return lam


@inline
def _ga_accept(Y, GW, h, w, nv, hs, co, Q, wr):
    """Newmark update of the unknowns' positions and velocities from a0 (GW[W_A0]) and the
    converged a1 (GW[W_A]); a1 kept in hs[H_ACC:] for the next step.  Q: the forces at the
    converged a1 (of the last residual evaluation, or those the converged equation implies:
    ga_step); wr: the restart's weight (0: a regular step)."""
    ga, be = co[2], co[3]
    for i in range(nv):
        a0 = GW[W_A0, i]
        a1 = GW[W_A, i]
        iv = V_VEL[i]
        v = Y[iv]
        ip = V_POS[i]
        if ip >= 0:
            Y[ip] = Y[ip] + h * v + h * h * ((0.5 - be) * a0 + be * a1)
        Y[iv] = v + h * ((1.0 - ga) * a0 + ga * a1)
        hs[H_ACC + i] = a1
    Y[Y_X] += h * w
    hs[H_TAKEN] += 1.0
    # whose history the accelerations are: a restart step's serve a restart at the next jump,
    # a regular step takes its own from the forces after it (ga_step).  A full restart step's
    # equation holds at t_f = t_{n+1} (alpha_f = 0), the state just written: the regular step
    # takes the forces there (Q, GA_AFTER_RESTART) instead of evaluating them again; one of
    # weight wr < 1 (its t_f before t_{n+1}) leaves a1 and those forces' accelerations
    # blended by wr; and its Jacobian made the regular step's, for the next step's Newton
    if wr == 0.0:
        hs[H_GA] = 1.0
    else:
        for i in range(nv):
            hs[H_FACC + i] = (1.0 - wr) * GW[W_A, i] + wr * (Q[i] / GW[W_M, i])
        hs[H_GA] = GA_AFTER_RESTART
        _ga_jacobian_to(GW, nv, co, GA_STEP)


@njit
def ga_step(Y, P, drive, h, W, reuse):
    """One generalized-alpha step of h [s] on Y (ideal or lumped bearing; Chung & Hulbert
    1993).  Newton on the accelerations, its Jacobian by finite differences (refreshed when
    convergence is slow), each Newton step halved until the residual falls (the tanh friction
    is steep over v_st).  reuse: GW[0:nv, 0:nv] holds the Jacobian of the step before, of
    the same h, for this step's coefficients (ga_steps; a restart step leaves its own so,
    _ga_accept): Newton starts from it (modified Newton) and takes a fresh one where that
    converges slowly.  hs[H_ACC:] carry the algorithmic accelerations from step to step
    (hs[H_GA] = 1 when valid; GA_AFTER_RESTART, GA_AFTER_RESTART_AFRESH after a restart step;
    0: first step or after a fallback, from the forces; -1: the inputs jumped at this
    communication point, this step a restart of weight hs[H_JUMPW], inputs_jumped).
    Returns False and leaves Y untouched when Newton does not converge.  W: the work arrays
    (layout.Work), taken apart once here: the Newton loop passes the arrays themselves (each
    access to a record's array costs a reference count: 9 % of this step's time, measured,
    when the helpers took the record)."""
    Yf, A, GW, hs, Q, L, res = W.Y1, W.A, W.GW, W.hs, W.b, W.L, W.res
    vs, r = P[P_VST_OP], P[P_R_ROLLER]
    trav = P[P_TRAVERSE] > 0.5
    for i in range(Y.shape[0]):
        Yf[i] = Y[i]
    regular = hs[H_GA] >= 0.0
    wr = 0.0 if regular else hs[H_JUMPW]     # a restart's weight (inputs_jumped)
    co = GA_STEP if regular else _restart_coefficients(wr)
    # accelerations from the forces: at the first step, after a fallback, and for a regular
    # step after a restart step (the history belongs to the other coefficients; the slip is on
    # the new inputs' value by now): those the restart step left, with the inputs moved since
    # blended with anew by the move's weight (inputs_jumped)
    nv = 6 if P[P_BEARING] == BEAR_LUMPED else 2
    if regular and hs[H_GA] >= GA_AFTER_RESTART_AFRESH:
        for i in range(nv):
            hs[H_ACC + i] = hs[H_FACC + i]
    if hs[H_GA] == 0.0 or (hs[H_GA] == GA_AFTER_RESTART_AFRESH and hs[H_JUMPW] > 0.0):
        ga_forces(Y, P, drive, L, res, Q, GW[W_M])
        f = 1.0 if hs[H_GA] == 0.0 else hs[H_JUMPW]
        for i in range(nv):
            a = Q[i] / GW[W_M, i]
            hs[H_ACC + i] = a if f >= 1.0 else (1.0 - f) * hs[H_ACC + i] + f * a
    ga = co[2]
    for i in range(nv):
        GW[W_A0, i] = hs[H_ACC + i]
        GW[W_A, i] = hs[H_ACC + i]
    _ga_residual(Y, Yf, P, drive, h, GW, W_A, W_R, L, res, Q, co)
    for i in range(nv):   # residual -> the velocity change it would cause, against the tolerance
        GW[W_S, i] = h * ga / (GW[W_M, i] * GA_NTOL * vs) * (r if V_ROT[i] > 0.0 else 1.0)
    fresh = stale = reuse
    last = math.inf      # the size of the step before (_ga_step_size)
    for it in range(GA_MAXIT):
        if not fresh:
            _ga_jacobian(Y, Yf, P, drive, h, GW, nv, L, res, Q, co)
            fresh = True
            stale = False
        n0 = _ga_newton_direction(GW, nv, trav, A, Q)
        if _ga_converged(_ga_step_size(GW, nv, h * ga, r), last, stale, vs):
            # the Newton step from here is below the tolerance: take it and stop, without the
            # forces at its end (evaluating them only to find the step small was a fifth of
            # the step's work); there the equation holds to second order in that step, so the
            # forces are M ((1 - am) a1 + am a0) (what a restart step keeps for the next)
            am = co[0]
            for i in range(nv):
                GW[W_A, i] = GW[W_A, i] + GW[W_D, i]
                if not regular:     # (only a restart step keeps them)
                    Q[i] = GW[W_M, i] * ((1.0 - am) * GW[W_A, i] + am * GW[W_A0, i])
            _ga_accept(Y, GW, h, drive.w, nv, hs, co, Q, wr)
            return True
        lam = _ga_line_search(Y, Yf, P, drive, h, GW, nv, n0, L, res, Q, co)
        for i in range(nv):
            GW[W_A, i] = GW[W_AT, i]
            GW[W_R, i] = GW[W_RT, i]
        size = _ga_step_size(GW, nv, h * ga * lam, r)
        if _ga_converged(size, last, stale, vs):
            _ga_accept(Y, GW, h, drive.w, nv, hs, co, Q, wr)
            return True
        if lam < 1.0 or size > 0.5 * last or it % 6 == 5:
            fresh = False   # slow: a Jacobian here (a fresh one's steps contract at 1e-3-0.2)
        last = size
    return False


@njit
def inputs_jumped(P, hs, jump):
    """The inputs changed at this communication point (oppoint.derive: ``jump`` the change of
    the slip's amplitude over v_st, P[P_DF] the pressing load's relative change): the
    generalized-alpha step restarts.
    - A step input (the slip above JUMP_STEP, with the lumped bearing above JUMP_RELAX;
      or the load above LOAD_RELAX: the load sets the pressing offset, and the lumped
      row's, so the contact's spring force jumps): the communication steps of GA_IN_TIME by
      the adaptive substeps, which land on the new slip and let what the step set ringing
      decay (the lumped row's modes, about 2e4 Hz; the roller's slide); a generalized-alpha
      step restarted on them overshoots (docs/integrators.md).
    - A large jump of the slip (above JUMP_RELAX, ideal bearing): one substep by the
      adaptive substeps, its boundary layer.  (Taking two communication steps there too,
      the coupled launch of docs/driveline-example.md, whose jumps hover about that bound,
      switched between the paths from step to step and lost 0.65 % of its peak.)
    - A small one (a master's ramp, every step): one restart step; the lumped bearing takes
      a small load change so too (its row's offset moves with the load).  Its weight w
      (hs[H_JUMPW]) is the change's size over JUMP_FULL, at most 1: below 1 the step's
      coefficients (_restart_coefficients), the accelerations it starts from and those it
      leaves lie between the regular step's (w = 0) and the full restart's (w = 1), so that the
      outputs move with the inputs continuously: a change by an ulp (a host's last-bit
      rounding, FMPy's interpolation of a held input) moves them by about as little, where a
      full restart moved Fz_joint by 1e-4 of its scale.
    The first two also resolve the roller's ring again (hs[H_RING] = RING_OPEN); after a
    small one the step's verdict on the ring decides (ga_steps).  After a restart step, a
    change that restarts nothing takes the forces at the new inputs for the next step's
    accelerations with the change's weight (GA_AFTER_RESTART_AFRESH).
    (kernel.inputs_moved calls it for integrator 4 with the ideal or lumped bearing; BDF2
    has its own, bdf2.inputs_jumped; the other integrators are L-stable one-step methods that
    land on the new inputs' slip without overshoot.)"""
    if jump >= 0.0 and (P[P_DF] > LOAD_RELAX or jump > JUMP_RELAX):
        hs[H_RING] = RING_OPEN
    if hs[H_GA] <= 0.0 or jump < 0.0:
        return
    lumped = P[P_BEARING] == BEAR_LUMPED
    after = hs[H_GA] == GA_AFTER_RESTART    # the forces it kept were the old drive's
    if after:
        hs[H_GA] = GA_AFTER_RESTART_AFRESH
        hs[H_JUMPW] = min(1.0, (jump + P[P_DF]) / JUMP_FULL)
    w = min(1.0, (jump + (P[P_DF] if lumped else 0.0)) / JUMP_FULL)
    if P[P_DF] > LOAD_RELAX or jump > (JUMP_RELAX if lumped else JUMP_STEP):
        hs[H_GA] = GA_STEP_IN
    elif jump > JUMP_RELAX:
        hs[H_GA] = GA_RELAX
    elif w > 0.0:
        if after:   # the restart starts from between the regular step's a0 and its own
            for i in range(NV):
                hs[H_ACC + i] = (1.0 - w) * hs[H_FACC + i] + w * hs[H_ACC + i]
        hs[H_GA] = -1.0
        hs[H_JUMPW] = w


@njit
def ga_steps(Y, P, drive, h, n, W, NW):
    """n generalized-alpha steps of h [s] (ideal or lumped bearing), restarted where the
    inputs jumped (hs[H_GA], inputs_jumped): a step input by the adaptive substeps over the
    communication steps of GA_IN_TIME, a large jump over one substep, a small one by one
    GA_RESTART step; a step whose Newton fails by the adaptive substeps.  With the ring
    quiet (hs[H_RING]) the communication step h n in fewer steps of at most P_HFREE; with it
    open, whether the step's slide acceleration lets it close.  Returns False where the
    adaptive substeps ran out of their budget (steplib.adaptive_steps: hs[H_FAIL])."""
    hs = W.hs
    if hs[H_RING] == RING_QUIET and P[P_HFREE] > h:
        T = h * n
        nf = max(1, int(math.ceil(T / P[P_HFREE] - 1e-9)))
        if nf < n:
            n, h = nf, T / nf
    regular = True     # every step a generalized-alpha one (its accelerations the slide's)
    amax = 0.0
    # GW holds the Jacobian of the step before, of this h: the next step starts from it
    # (ga_step).  Never across calls: a communication step's result depends on its state and
    # inputs alone (a state a host restores, another instance)
    reuse = False
    for _ in range(n):
        if hs[H_GA] <= GA_STEP_IN:
            # a step input: the communication steps of GA_IN_TIME by the error-controlled
            # L-stable extrapolated substeps (the slip relaxing onto the new inputs' value,
            # and what the step set ringing), then the accelerations afresh from the forces
            if hs[H_GA] == GA_STEP_IN:    # the first: how many make GA_IN_TIME
                hs[H_GA] = GA_STEP_IN - max(GA_IN_STEPS,
                                            math.ceil(GA_IN_TIME / (h * n) - 1e-6))
            if not adaptive_steps(Y, P, drive, h * n, 0.25 * h, W, NW):
                return False
            hs[H_GA] = hs[H_GA] + 1.0 if hs[H_GA] < GA_STEP_IN - 1.5 else 0.0
            regular = False
            break
        if hs[H_GA] == GA_RELAX:
            # a large jump: its boundary layer (the slip relaxing onto the new inputs'
            # value) by the adaptive substeps over one substep
            if not adaptive_steps(Y, P, drive, h, 0.25 * h, W, NW):
                return False
            hs[H_GA] = 0.0    # then the accelerations afresh from the forces
            regular = False
            reuse = False
            continue
        if hs[H_GA] < 0.0:    # the inputs jumped: the restart step (GA_RESTART)
            reuse = ga_step(Y, P, drive, h, W, False)
            if reuse:
                amax = max(amax, abs(hs[H_ACC]))
                continue
            hs[H_GA] = 1.0    # its Newton did not converge: the regular step
        reuse = ga_step(Y, P, drive, h, W, reuse)
        if reuse:
            amax = max(amax, abs(hs[H_ACC]))
        else:
            # Newton did not converge (a very steep friction law): this step by the
            # error-controlled extrapolated substeps instead, then start afresh
            hs[H_FALLBACK] += 1.0
            if not adaptive_steps(Y, P, drive, h, 0.25 * h, W, NW):
                return False
            hs[H_GA] = 0.0
            regular = False
    if regular:
        hs[H_RING] = RING_QUIET if amax < P[P_RINGA] else RING_OPEN
    return True
