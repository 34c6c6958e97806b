"""The operating point of a communication step: what the inputs (theta, omega, pressing load)
and the step size set before any substep - the transition velocity v_st, the substep and its
count, the largest adaptive substep, the pressing offset of the trunnion axis.

Plain Python over the parameter vector P and the operating-point vector OP (layout.py), so the
model derives it without numba (its log, the needle-resolved bearing), and numba compiles the
same functions into the communication step (kernel.derive_op, by jit.compiled_copies), which derives it
itself when a master sets new inputs (lifecycle.step): one
implementation for both.
"""
import math

from reduced_model.friction import v_st_auto
from reduced_model.needle_row import row_offset, sum_row
from reduced_model.scene import pressing_load
from reduced_model.sliding import amplitude_A, amplitude_B, amplitude_plunge

from .layout import (BEAR_LUMPED, BEAR_RESOLVED, INT_DEFAULT, OP_DT, OP_F, OP_FP, OP_H, OP_KEY,
    OP_N, OP_THETA, OP_TQ, OP_VP, OP_W, OP_X0, P_BEARING, P_NEEDLE_CLEARANCE, P_DF,
    P_FRICTION_GROOVE, P_FRICTION_NEEDLE, P_HMAX, P_MAX_SUBSTEP, P_INTEGRATOR, P_K, P_KN,
    P_M_ROLLER, P_MU_GROOVE, P_MU_NEEDLE, P_NEWTON_PASSES, P_PITCH, P_FLANK, P_HFREE, P_QSUM,
    P_RINGA, P_R_ROLLER, P_R_GROOVE, P_ROLL, P_S, P_TRAVERSE, P_VP, P_VST_OP, P_V_ST, P_NROW,
    P_KN1, P_TOLERANCE)


# The fewest substeps a whirl cycle: about 2000, a resolution floor for the driven motion.
# 1960, not 2000: a scene that sits on it (the default, 10 Hz at 1e-4 s steps: 2 substeps)
# keeps its count while a master moves omega up by up to 2 %; with 2000 a rise of 1e-3 took a
# third substep, 1.5 times the cost.
CYCLE_SUBSTEPS = 1960.0
# The roller's ring counts as quiet when its force on the slide, m |u''|, stays below this
# fraction of the pressing load over a communication step (genalpha.ga_steps): a ring of
# 3e-4 rho (60-90 nm).  At 1e-3 one roller at 300 N m and 10 Hz, whose steady running keeps
# its ring alive, let it go quiet by spells: up to 0.83 % of order 3 off the reference after
# an input step, 0.65 % with none (at 3e-4 0.45 % and 0.35 %, as with the ring always
# resolved); docs/integrators.md
RING_QUIET_FORCE = 3e-4
# The BDF2 substep with the needle-resolved bearing takes at most this whirl angle [rad]
# (10 Hz: 8 us, not binding; 40 Hz: 2 us).  Measured with one-pass BDF2 (newton_passes = 1),
# which linearizes once a substep, the needles' friction by its
# secant: the linearization error grows with speed, one roller's order 1 at 300 N m and 8 deg
# read 1 % high at 25 Hz and 4.5 % at 40 and 80 Hz at the row's 2.9 us (a second linear solve
# at the corrected state, or half the substep, removes it).  At this bound 0.7 % at 40 Hz and
# 0.4 % at 80 Hz, means over three realizations against h/4 to h/8 (docs/integrators.md).
# Kept with the default's second pass (not measured whether that allows a longer bound)
ROW_WHIRL_STEP = 5e-4


def amplitudes(P, theta, omega):
    """(A, B) [m/s], Eqs. (19)-(20) with pitch and roll on."""
    return amplitude_A(P[P_S], omega, theta, True), amplitude_B(P[P_R_ROLLER], omega, theta, True)


def v_st(P, theta, omega, vp=0.0):
    """Transition velocity [m/s]: the parameter, or automatic sqrt(A^2+B^2+Vp^2)/4 (model.md;
    Vp the plunge's sliding at the plunge speed vp [m/s]) with its floor (friction.V_ST_FLOOR:
    a joint at rest or straight still needs one)."""
    if P[P_V_ST] > 0.0:
        return P[P_V_ST]
    A, B = amplitudes(P, theta, omega)
    return v_st_auto(A, B, amplitude_plunge(vp, theta, P[P_PITCH] > 0.5))


def _rate_amplitude(P, theta, omega):
    """sqrt(A^2 + B^2) [m/s] of the motions switched on."""
    A, B = amplitudes(P, theta, omega)
    return math.hypot(A if P[P_PITCH] > 0.5 else 0.0, B if P[P_ROLL] > 0.5 else 0.0)


def _accuracy_bound(P, theta, w, vst, n_transition):
    """The substep [s] accuracy asks for at whirl rate w >= 0 [rad/s]: at most 1e-4 s, at
    least CYCLE_SUBSTEPS a whirl cycle and, n_transition > 0, that many across the friction
    transition (V through +/- v_st at up to 2 w sqrt(A^2+B^2))."""
    h = 1e-4
    if w > 0:
        h = min(h, 2 * math.pi / w / CYCLE_SUBSTEPS)
        R = _rate_amplitude(P, theta, w) if n_transition > 0 else 0.0
        if R > 0:
            h = min(h, vst / (2 * w * R) / n_transition)
    return h


def ga_substeps(P):
    """Whether the substep is the generalized-alpha step's (integrator 4 with the ideal or
    lumped bearing, max_substep automatic)."""
    return (P[P_MAX_SUBSTEP] <= 0.0 and P[P_INTEGRATOR] == INT_DEFAULT
            and P[P_BEARING] != BEAR_RESOLVED)


def ga_step_size(P, theta, omega, F, vst):
    """Step of the generalized-alpha integrator [s] (integrator 4, ideal or lumped bearing):
    the smaller of ga_free_step and ring_step."""
    return max(min(ga_free_step(P, theta, omega, vst), ring_step(P, F)), 1e-7)


# The tolerance the automatic generalized-alpha substep h_a stands for.  At the paper's scene
# (1 ms communication steps) order 3's error falls as the substep squared below h_a / 5, 1.5e-4
# at 10 us and 3.6e-5 at 5 us: 3.75e-3 (h / h_a)^2; above, the roller's ring leaves it at 2e-4 to
# 1e-3 (docs/integrators.md).  Twice 3.75e-3: the tolerance then bounds the error with a factor
# of 2 to spare where the square law holds
TOL_AUTO = 7.5e-3


def tolerance_scale(P):
    """The generalized-alpha substep's factor for the tolerance P[P_TOLERANCE] [1]: sqrt(tolerance /
    TOL_AUTO) (the method is of second order), at most 4; 1 without a tolerance (0)."""
    if P[P_TOLERANCE] > 0.0:
        return min(math.sqrt(P[P_TOLERANCE] / TOL_AUTO), 4.0)
    return 1.0


def ga_free_step(P, theta, omega, vst):
    """Step of the generalized-alpha integrator [s] where the roller's ring is quiet
    (genalpha.ga_steps).  Implicit with Newton, it needs no substep for the stick mode; it
    must resolve the friction transition (V through +/- v_st at up to 2 w sqrt(A^2+B^2)) in
    20 steps and take at least CYCLE_SUBSTEPS steps a whirl cycle, and at most 1e-4 s.  The
    lumped row's own modes (radial about 12 kHz, tilt about 2 kHz) are left to the step's
    numerical damping: order 3 0.03 % off the reference at 50 us (measured)."""
    return max(_accuracy_bound(P, theta, abs(omega), vst, 20.0), 1e-7) * tolerance_scale(P)


def ring_step(P, F):
    """Step [s] that resolves the roller rocking across the groove at the pressing load F [N]
    (sliding along the trunnion, restored by the groove's curvature, undamped while the slip
    saturates the tanh): omega_g^2 = F / (m rho), rho the roller centre's distance from the
    groove axis; omega_g h <= 0.5 (measured at the paper's scene: 0.48 -> order 3 0.02 % off,
    0.96 -> 0.26 %; after an input step at a launch's 45 kN the period error of a larger step
    adds up over the ring, docs/integrators.md).  1e-4 s at F = 0 (no ring)."""
    F = abs(F)      # coast: the same ring
    if F > 0:
        rho = P[P_R_GROOVE] - P[P_R_ROLLER] + (F / P[P_K]) ** (2.0 / 3.0)
        return min(0.5 / math.sqrt(F / (P[P_M_ROLLER] * rho)), 1e-4) * tolerance_scale(P)
    return 1e-4 * tolerance_scale(P)


def substep(P, theta, omega, F, vst, stiff):
    """Substep [s]: max_substep if set; the generalized-alpha step (ga_step_size) with
    integrator 4 and the ideal or lumped bearing; the BDF2 step's (row_substep, ROW_WHIRL_STEP
    / w and the first two bounds below) with integrator 4 and the needle-resolved bearing; else
    from accuracy and stability estimates:

    - the friction transition: V swings through +/- v_st at up to 2 w sqrt(A^2+B^2); 80
      substeps across it keep order 3 converged to about 0.02 % (2nd-order integrator);
    - traverse: the roller's slide along the trunnion is locked by the friction slope
      3 mu F / v_st against its mass (groove, plus the needles' with the resolved bearing);
      the extrapolated step must stay near its asymptotic range: h * rate <= 1.5 keeps halving
      h below a 0.1 % change in order 3 (measured 0.07 % at 1.6, 0.06 % at 1.33);
    - at least CYCLE_SUBSTEPS substeps a whirl cycle.
    stiff = False: without the bounds that come from the stiff stick mode (the largest
    adaptive substep: the error estimate handles that mode).
    """
    if P[P_MAX_SUBSTEP] > 0:
        return P[P_MAX_SUBSTEP]
    if stiff and ga_substeps(P):
        return ga_step_size(P, theta, omega, F, vst)
    w, F = abs(omega), abs(F)      # reverse whirl and coast: the same bounds
    h = _accuracy_bound(P, theta, w, vst, 80.0 if stiff else 0.0)
    if stiff and P[P_INTEGRATOR] == INT_DEFAULT and P[P_BEARING] == BEAR_RESOLVED:
        h = min(h, row_substep(P, F))
        if w > 0:
            h = min(h, ROW_WHIRL_STEP / w)
        return max(h, 1e-7)
    if (stiff and P[P_TRAVERSE] > 0.5 and F > 0 and P[P_FRICTION_GROOVE] > 0.5
            and P[P_MU_GROOVE] > 0):
        mu = P[P_MU_GROOVE]
        if P[P_BEARING] == BEAR_RESOLVED and P[P_FRICTION_NEEDLE] > 0.5:
            # resolved needles hold the roller's slide with their own friction too: the
            # needle loads sum to QSUM x F_press (Eq. 17 over the row, about 1.3 F); with
            # only the groove's rate the bearing-2 order 3 was 3 % off, with both 0.6 %
            mu += P[P_MU_NEEDLE] * P[P_QSUM]
        rate = 3.0 * mu * F / (vst * P[P_M_ROLLER])
        h = min(h, 1.5 / rate)
    return max(h, 1e-7)


def row_substep(P, F):
    """Substep [s] of the BDF2 step with the needle-resolved bearing (integrator 4): h w <= 0.75
    with two Newton passes or more (newton_passes), 0.55 with one, for the roller's radial mode
    on the needle row, w = sqrt(k_r / m) with k_r the row's tangent stiffness at the pressing
    load F [N] (Eq. 17 over the row, as the lumped bearing; taken at 100 N below that: the
    stiffness vanishes with the load, the needles' impacts do not).  About 28 kHz in the
    paper's scene, nearly independent of the load (k_r grows as F^(1/10)): 3.9 us with two
    passes, 2.9 us with one.  One pass: order 3 within 0.2 % of 1 us at 3 us, 0.5 % at 3.3 us,
    1.5 % at 4 us; at 10 us runs change regime, at 20 us the roller is lost; at 5 kN 3 us is
    within 0.05 % of 0.6 us.  Two passes (settled order 3): 0.03 % off 1 us at
    4 us, 0.5 % at 5 us; at 45 kN and 25 deg 0.24 % off at 3.5 us (one pass 0.38 % at its
    2.6 us), against the converged 635.7 N."""
    Fe = max(abs(F), 100.0)
    g = (Fe / P[P_KN]) ** 0.9           # the row's approach beyond its clearance [m]
    kr = 10.0 / 9.0 * Fe / g
    return (0.75 if P[P_NEWTON_PASSES] > 1.5 else 0.55) / math.sqrt(kr / P[P_M_ROLLER])


def groove_offset(P, F):
    """x position of the trunnion axis [m] that presses the roller at the groove bottom with F
    [N] (Hertz approach): the pressing offset of the ideal bearing, on the flank whose arc
    centre is P_FLANK off the mid-plane (contact.flank_centre).  F < 0 (coast) presses it on
    the other flank, at -x, running_clearance plus twice the approach away; F = 0 leaves it
    touching the drive flank."""
    x = P[P_FLANK] + P[P_R_GROOVE] - P[P_R_ROLLER] + (abs(F) / P[P_K]) ** (2.0 / 3.0)
    return -x if F < 0.0 else x


def row_sums(P, a):
    """The lumped row with the roller a >= 0 [m] off the trunnion axis (needle_row.sum_row
    over P's row, as the resolved row's start sums it: roller_setup.row_load): the radial
    load |F_r| [N], its tangent stiffness along the load k_r and across it k_w [N/m], the sum
    of the needle loads q [N] and that sum weighted by sin^2 of their angle q_s [N]."""
    return sum_row(P[P_NEEDLE_CLEARANCE], int(P[P_NROW]), P[P_KN1], a)


def lumped_offset(P, F):
    """Static x offset of the roller from the trunnion axis [m] under a radial load F [N],
    lumped bearing (needle_row.row_offset), against the load (negative in drive, positive in
    coast)."""
    c = P[P_NEEDLE_CLEARANCE]
    if F == 0.0:
        return -c
    e = row_offset(c, int(P[P_NROW]), P[P_KN1], P[P_KN], F, 0.0, 0.0)
    return e if F < 0.0 else -e


# What derive's jump (the driven slip amplitude's change over v_st) and the load's relative
# change (P_DF) mean to the integrators: above JUMP_RELAX the next substep by the adaptive
# substeps, above JUMP_STEP (or a load change above LOAD_RELAX) a step input
# (genalpha.inputs_jumped, bdf2.inputs_jumped)
JUMP_RELAX = 0.02
JUMP_STEP = 0.2
LOAD_RELAX = 0.02
# below JUMP_FULL (the jump plus, lumped bearing, the load's relative change) the
# generalized-alpha restart takes the change's share size / JUMP_FULL of itself
# (genalpha.inputs_jumped): the outputs follow the inputs continuously down to an ulp; the
# run-ups the tests hold step by 1.5e-4 to 1.5e-2, restarted in full as before
JUMP_FULL = 1e-4


def derive(P, OP):
    """The operating point at OP's inputs and step OP[OP_DT] [s], when they differ from those it
    was last derived at (OP[OP_KEY:]): OP's pressing load, substep, substep count and pressing
    offset (ideal and lumped bearing; the resolved one's offset is the model's), P's v_st,
    largest adaptive substep, the generalized-alpha step where the roller's ring is quiet and
    the slide's acceleration that counts as quiet.  The pressing load per roller is torque / (3 s) when a torque
    [N m] is given (not 0; < 0 coast), else F_press (reduced_model/scene.py, pressing_load).  Returns -1 when
    the inputs did not move, else how far they moved the driven slip (its amplitude's change
    over v_st; 0 for a load change alone): kernel.inputs_moved restarts the integrator."""
    theta, omega, Fp, tq, dt = OP[OP_THETA], OP[OP_W], OP[OP_FP], OP[OP_TQ], OP[OP_DT]
    vp = OP[OP_VP]
    same = (theta == OP[OP_KEY] and omega == OP[OP_KEY + 1] and Fp == OP[OP_KEY + 2]
            and tq == OP[OP_KEY + 3] and vp == OP[OP_KEY + 5])
    if same and dt == OP[OP_KEY + 4]:
        return -1.0
    # how far the inputs moved the driven slip: its amplitude's change over the new v_st (-1:
    # they did not move; the first step, NaN key, is no jump)
    jump = -1.0
    if not same and OP[OP_KEY] == OP[OP_KEY]:
        jump = 0.0
    F = pressing_load(Fp, tq, P[P_S])
    vst = v_st(P, theta, omega, vp)
    h = substep(P, theta, omega, F, vst, True)
    n = max(1, int(math.ceil(min(dt / h - 1e-9, 2.0 ** 53))))   # (a host's huge dt: no overflow)
    # the load's relative change, from the key (a restored state carries the key, not OP_F)
    F0 = pressing_load(OP[OP_KEY + 2], OP[OP_KEY + 3], P[P_S])
    P[P_DF] = abs(F - F0) / max(abs(F), abs(F0), 1e-300) if jump >= 0.0 else 0.0
    OP[OP_F] = F
    OP[OP_N] = n
    OP[OP_H] = dt / n
    x0 = groove_offset(P, F)
    if P[P_BEARING] == BEAR_LUMPED:
        x0 -= lumped_offset(P, F)
    OP[OP_X0] = x0
    if jump == 0.0:
        R0 = _rate_amplitude(P, OP[OP_KEY], OP[OP_KEY + 1])
        jump = abs(_rate_amplitude(P, theta, omega) - R0) / vst
        # and the plunge's sliding
        jump += amplitude_plunge(vp - OP[OP_KEY + 5], theta, P[P_PITCH] > 0.5) / vst
    P[P_VST_OP] = vst
    P[P_VP] = vp
    P[P_HMAX] = substep(P, theta, omega, F, vst, False)
    # the generalized-alpha step where the roller's ring is quiet (genalpha.ga_steps), and the
    # slide's acceleration below which it counts as quiet
    P[P_HFREE] = ga_free_step(P, theta, omega, vst) if ga_substeps(P) else 0.0
    P[P_RINGA] = RING_QUIET_FORCE * abs(F) / P[P_M_ROLLER]
    OP[OP_KEY] = theta
    OP[OP_KEY + 1] = omega
    OP[OP_KEY + 2] = Fp
    OP[OP_KEY + 3] = tq
    OP[OP_KEY + 4] = dt
    OP[OP_KEY + 5] = vp
    return jump


# what derive writes: a roller whose parameters and inputs are another's takes them by
# copy_derived (a joint's rollers, kernel.step_joint: one derive a joint)
OP_DERIVED = (OP_F, OP_N, OP_H, OP_X0, OP_KEY, OP_KEY + 1, OP_KEY + 2, OP_KEY + 3, OP_KEY + 4,
              OP_KEY + 5)
P_DERIVED = (P_DF, P_VST_OP, P_VP, P_HMAX, P_HFREE, P_RINGA)


def copy_derived(P, OP, P_to, OP_to):
    """derive's results for P, OP into P_to, OP_to: what derive(P_to, OP_to) would write when
    P_to equals P and OP_to's inputs OP's (it reads nothing else)."""
    for i in P_DERIVED:
        P_to[i] = P[i]
    for i in OP_DERIVED:
        OP_to[i] = OP[i]


# what kernel.py compiles in this module's namespace (the reduced model's formulas too: one
# implementation of each)
FUNCTIONS = ("row_substep", "pressing_load", "amplitude_A", "amplitude_B", "amplitude_plunge", "v_st_auto", "amplitudes", "v_st",
             "_rate_amplitude", "_accuracy_bound", "ga_substeps", "ga_step_size", "tolerance_scale", "ga_free_step", "ring_step", "substep", "groove_offset", "sum_row", "row_sums", "row_offset", "lumped_offset",
             "derive", "copy_derived")
