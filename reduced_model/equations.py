"""The reduced model's equations as scalar functions over flat arrays: the operating point at
the inputs (O_* slots; coast as the drive scene whose turn it is), Eqs. (18)-(27) at a whirl
angle, the traverse model's T1-T6 (traverse.py's header) and the slide stepped in time (the
march).  One source for traverse.Traverse, the analytic FMU's model as Python and its binary
(kernel.py compiles these with its lifecycle: c_functions).  T: the analytic FMU's parameters
in PARAM_NAMES' order; O: an operating point; a march row: R_* slots.  Scalar libm math
throughout, so compiled and Python give the same bits.
"""
import math

from .friction import V_ST_FLOOR, spin_moment, tanh_clipped
from .hertz import hertz_point
from .needle_row import ROW_CARRY, needle_lag, row_arc, row_constants, row_offset, sum_row
from .scene import params_for, pressing_load
from .thrust import fz_mod

TWO_PI = 6.283185307179586   # math.tau
N_PER_CYCLE = 360          # the table's points a whirl cycle; the march's longest substep

# --- the parameters T (the table's, inputs left out) -----------------------------------------
PARAM_NAMES = tuple(p.name for p in params_for("analytic") if p.causality != "input")
(DRIVE_BY_ANGLE, N_ROLLERS, MU_GROOVE, V_ST, PITCH, YAW, ROLL, AXIAL, S, R_ROLLER, R_GROOVE,
 R_BORE, M_ROLLER, SPIN_INERTIA, TRAVERSE, SPIN_MOMENT, E, NU) = map(PARAM_NAMES.index, (
    "drive_by_angle", "n_rollers", "mu_groove", "v_st", "pitch", "yaw", "roll", "axial", "s",
    "r_roller", "r_groove", "r_bore", "m_roller", "spin_inertia", "traverse", "spin_moment",
    "E", "nu"))
(NEEDLE_ROW, MU_NEEDLE, MU_ROLLING, FRICTION_NEEDLE, ROLLING_RESISTANCE, L_NEEDLE,
 NEEDLE_CLEARANCE, N_NEEDLES, NEEDLE_AXIAL_CLEARANCE) = map(PARAM_NAMES.index, (
    "needle_row", "mu_needle", "mu_rolling", "friction_needle", "rolling_resistance",
    "l_needle", "needle_clearance", "n_needles", "needle_axial_clearance"))
T_LEN = len(PARAM_NAMES)

# the operating point: the scene's constants at the inputs of its key, for the scene the reduced
# model runs (coast: drive at the opposite whirl, turned about the trunnion axis)
(O_W, O_TH, O_T, O_KR, O_S, O_R, O_F, O_MU, O_VST, O_K, O_A1, O_CLEAR, O_RHO, O_VP, O_SM, O_I,
 O_HELD, O_MIRROR, O_A, O_B, O_KT, O_MUF, O_THP, O_VPP, O_KSPIN, O_LOAD,
 # the needle row (needle_row = true; row_point): on, mu_needle q, mu_rolling q r_bore, the tilt
 # stiffness about e2, the lever, r_bore, the row's tanh slope, e (Eq. 7), tan(theta) (Eq. 3),
 # the row's load, the tilt stiffness about e1, the needles' length, their axial play (-1:
 # the row's friction off, the needles ride the stops), where across the load the loaded
 # needles meet the bore (needle_row.row_arc), the row's stiffness along the load (T5 in series);
 # kept from one derivation to the next (row_point): the row's constants with the needles'
 # count and length they are for, and the roller's offset on the row with the load it carries
 O_ROW, O_MQ, O_MR, O_KT2, O_LEVER, O_RB, O_KROW, O_EAX, O_TYAW, O_CRF, O_KT1, O_LN, O_PLAY,
 O_ARC, O_KRR,
 O_RN, O_RL, O_RC1, O_RKR, O_RA, O_RAF,
 O_LEN) = range(48)


# a roller's march row: slide slip s [m/s], p [1], the outputs (Fz, Fz_mod, Fx, Fy [N], slip
# speed [m/s]), whether s and the outputs exist yet (the march starts at rest)
# and, with the needle row, the roller's tilt b2 [rad] on it, its rate [rad/s], the groove
# contact's slip across the slide t [m/s] (the next step's Newton starts from them), the rate
# of its tilt about e1 over the last step [rad/s] (the needles' friction takes it a step late)
# and the slide slip's rate over the last step [m/s^2] (the next Newton starts from it carried on)
(R_S, R_P, R_FZ, R_FZ_MOD, R_FX, R_FY, R_SLIP, R_HAS_S, R_HAS_OUT, R_B2, R_B2D, R_T, R_B1D,
 R_SD, R_LEN) = range(15)

# --- the scene's constants --------------------------------------------------------------------
def transition_velocity(v_st, s, r, w, th, vp, pitch, roll):
    """v_st [m/s] in use: the scene's, or the automatic sqrt(A^2 + B^2 + Vp^2) / 4, at least
    V_ST_FLOOR (friction.v_st_auto), with A = s w th^2 / 2 (Eq. 19), B = -r w (1 - cos th) /
    cos th (Eq. 20), Vp = |v_p| sin th (the plunge's sliding); pitch and roll switch A, Vp and
    B."""
    if v_st > 0:
        return v_st
    A = 0.5 * s * w * (th * th) if pitch else 0.0
    B = 0.0
    if roll:
        c = math.cos(th)
        B = -r * w * (1.0 - c) / c
    h = math.sqrt(A * A + B * B)
    Vp = abs(vp) * math.sin(th) if pitch else 0.0
    if Vp != 0.0:
        h = math.sqrt(h * h + Vp * Vp)
    return max(h / 4.0, V_ST_FLOOR)


def operating_point(T, theta, omega, F_press, torque, vp, O):
    """O: the constants of the scene the reduced model runs at these inputs (theta [rad], omega
    [rad/s], F_press [N], torque [N m], plunge speed vp [m/s]): Traverse's (T1-T6) and Eqs.
    (18)-(27)'s.  Coast (a negative pressing load) runs as drive at the opposite whirl and
    plunge speed, turned 180 deg about the trunnion axis (docs/model.md): O_MIRROR."""
    s, r = T[S], T[R_ROLLER]
    load = pressing_load(F_press, torque, s)
    mirror = load < 0
    if mirror:    # (-tq) / (3 s) is -(tq / (3 s)) to the bit
        omega, F_press, torque, vp = -omega, -F_press, -torque, -vp
    F = pressing_load(F_press, torque, s)
    pitch, roll = T[PITCH] != 0.0, T[ROLL] != 0.0
    O[O_W] = omega
    O[O_TH] = theta
    O[O_T] = math.tan(theta) if pitch else 0.0
    O[O_KR] = (1.0 - math.cos(theta)) / (2.0 * math.cos(theta)) if roll else 0.0   # e / s
    O[O_S] = s
    O[O_R] = r
    O[O_F] = F
    O[O_LOAD] = load
    O[O_MIRROR] = 1.0 if mirror else 0.0
    mu = T[MU_GROOVE]
    O[O_MU] = mu
    vst = transition_velocity(T[V_ST], s, r, omega, theta, vp, pitch, roll)
    O[O_VST] = vst
    K, a1, _ = hertz_point(r, T[R_GROOVE], T[E], T[NU])
    O[O_K] = K
    O[O_A1] = a1
    clear = T[R_GROOVE] - r
    O[O_CLEAR] = clear
    O[O_RHO] = clear + (F / K) ** (2.0 / 3.0) if F > 0 else clear
    O[O_VP] = vp
    O[O_SM] = 1.0 if T[SPIN_MOMENT] != 0.0 else 0.0
    # the roller's spin inertia as a thick ring, m (r^2 + r_bore^2) / 2 (0: the spin-inertia
    # thrust switched off)
    inertia = 0.5 * T[M_ROLLER] * (r * r + T[R_BORE] * T[R_BORE])
    O[O_I] = inertia if T[SPIN_INERTIA] != 0.0 else 0.0
    O[O_HELD] = 1.0 if (F > 0 and mu > 0 and vst > 0) else 0.0   # else nothing holds the roller
    # Eqs. (18)-(27): V = A sin 2x + B cos 2x (Eq. 24), ft = mu F tanh(3 V / v_st)
    O[O_A] = 0.5 * s * omega * (theta * theta) if pitch else 0.0
    if roll:
        c = math.cos(theta)
        O[O_B] = -r * omega * (1.0 - c) / c
    else:
        O[O_B] = 0.0
    O[O_KT] = 3.0 / vst if vst > 0 else 1e300         # Coulomb at v_st = 0
    O[O_MUF] = mu * F                                  # Eq. (11)
    th = theta if pitch else 0.0
    O[O_THP] = th                                      # Eq. (2): phi = theta sin x
    O[O_VPP] = vp if pitch else 0.0                    # the plunge's part of dz/dt in v1
    # the spin inertia's thrust (I / r^2) d2z/dt2, d2z/dt2 = -w^2 s theta sin x
    O[O_KSPIN] = -inertia / (r * r) * omega * omega * (s * th) \
        if (T[SPIN_INERTIA] != 0.0 and pitch) else 0.0
    row_point(T, O)


def row_point(T, O):
    """The needle row's constants at O (docs/model.md, "The row's terms in the reduced model"),
    from Eq. (17) summed over the row at the pressing load F (needle_row.py): the needle loads'
    sum q [N], the row's stiffness along the load k_r [N/m] and the lever r_bore F / q [m] at
    which the loaded needles meet the bore.  Off (O_ROW = 0) with needle_row false, the
    traverse model off, or nothing holding the roller."""
    on = T[NEEDLE_ROW] != 0.0 and T[TRAVERSE] != 0.0 and O[O_HELD] != 0.0
    O[O_ROW] = 1.0 if on else 0.0
    for k in (O_MQ, O_MR, O_KT2, O_LEVER, O_RB, O_KROW, O_EAX, O_TYAW, O_CRF, O_KT1, O_LN,
              O_PLAY, O_ARC, O_KRR):
        O[k] = 0.0
    if not on:
        return
    n, c, ln = int(T[N_NEEDLES]), T[NEEDLE_CLEARANCE], T[L_NEEDLE]
    if not (O[O_RN] == n and O[O_RL] == ln):     # (a master moves the inputs, not the needles)
        O[O_RC1], O[O_RKR], _ = row_constants(n, ln)
        O[O_RN], O[O_RL], O[O_RA], O[O_RAF] = n, ln, 0.0, 0.0
    c1 = O[O_RC1]
    a = row_offset(c, n, c1, O[O_RKR], O[O_F], O[O_RA], O[O_RAF])
    O[O_RA], O[O_RAF] = a, abs(O[O_F])
    Fr, kr, kw, q, qs = sum_row(c, n, c1, a)
    rb = T[R_BORE]
    O[O_MQ] = T[MU_NEEDLE] * q if T[FRICTION_NEEDLE] != 0.0 else 0.0
    O[O_MR] = T[MU_ROLLING] * q * rb if T[ROLLING_RESISTANCE] != 0.0 else 0.0
    O[O_KT2] = kr * ln * ln / 12.0                  # the lumped row's tilt stiffness about e2
    O[O_KT1] = kw * ln * ln / 12.0                  # and about e1 (across the load)
    O[O_KRR] = kr                                   # along the load, in series with T5
    O[O_LN] = ln
    O[O_LEVER] = rb * Fr / q
    O[O_ARC] = row_arc(rb, q, qs)
    O[O_RB] = rb
    O[O_KROW] = 1.5 / O[O_VST]        # half the slip at each of a needle's two contacts
    th = O[O_TH]
    O[O_EAX] = O[O_S] * (1.0 - math.cos(th)) / (2.0 * math.cos(th)) if T[AXIAL] != 0.0 else 0.0
    O[O_TYAW] = math.tan(th) if T[YAW] != 0.0 else 0.0
    # the row's load acts where its needles are along the trunnion (row_moment)
    O[O_CRF] = O[O_F]
    O[O_PLAY] = T[NEEDLE_AXIAL_CLEARANCE] if T[FRICTION_NEEDLE] != 0.0 else -1.0


# --- Eqs. (18)-(27) ---------------------------------------------------------------------------
def thrust_at(O, x):
    """(Fz, ft, V, phi) at whirl angle x [rad]: Eqs. (2), (18)-(26) and the spin inertia's
    thrust; N, N, m/s, rad."""
    sx = math.sin(x)
    V = O[O_A] * math.sin(2.0 * x) + O[O_B] * math.cos(2.0 * x)   # Eq. (24)
    phi = O[O_THP] * sx                                            # Eq. (2)
    if O[O_VPP] != 0.0:                                            # plunging: v_p sin(phi)
        V = V + O[O_VPP] * math.sin(phi)
    ft = O[O_MUF] * math.tanh(O[O_KT] * V)                         # Eqs. (11), (25), Fig. 8
    return ft * math.sin(phi) + O[O_KSPIN] * sx, ft, V, phi       # Eq. (26)


# --- the traverse model, T1-T6 (traverse.py's header) -----------------------------------------
def drive_at(O, x):
    """The driving motion at whirl angle x [rad], exact Eqs. (1), (5) (z = s tan(phi), Eq. 18):
    phi, xi [rad], V [m/s] (T4's driven slip), dphi [rad/s], spin [rad/s] (rolling along the
    groove), bi [N] (T2's inertia part of f_b)."""
    w, tn, k, r = O[O_W], O[O_T], O[O_KR], O[O_R]
    tz = tn * math.sin(x)
    phi = math.atan(tz)
    dphi = tn * w * math.cos(x) / (1.0 + tz * tz)
    q = k * math.sin(2.0 * x)
    xi = math.asin(q)
    dxi = 2.0 * w * k * math.cos(2.0 * x) / math.sqrt(1.0 - q * q)
    zd = O[O_S] * tn * w * math.cos(x)
    if O[O_VP] != 0.0:                                  # the plunge: travel along z
        zd = zd + O[O_VP]
    zdd = -O[O_S] * tn * w * w * math.sin(x)
    v1 = zd * math.sin(phi)                             # Eq. (19), exact
    v2 = -r * dxi                                       # Eq. (20), exact
    V = v1 + v2 * (1.0 + O[O_RHO] / r)                  # T4
    return phi, xi, V, dphi, zd / r, -O[O_I] * zdd / (r * r)


def inclination_slip(O, x):
    """T4's g [m/s] at whirl angle x [rad]: the slip along the trunnion at the contact per unit
    p.  The contact sits r p off the groove's bottom along the groove's cross direction, and
    the trunnion's rotation moves the roller's material there along the trunnion by -r a_y'
    p, a_y = cos(xi) cos(phi) the trunnion axis's component across the groove (Eqs. 1, 5,
    exact): g = r (cos xi sin phi phi' + sin xi cos phi xi')."""
    w, tn, k, r = O[O_W], O[O_T], O[O_KR], O[O_R]
    tz = tn * math.sin(x)
    cp = 1.0 / math.sqrt(1.0 + tz * tz)
    dphi = tn * w * math.cos(x) * cp * cp
    q = k * math.sin(2.0 * x)
    cx = math.sqrt(1.0 - q * q)
    dxi = 2.0 * w * k * math.cos(2.0 * x) / cx
    return r * (cx * tz * cp * dphi + q * cp * dxi)


def t4_rhs(O, s0, p0, V0, V1, g0, g1, h):
    """The known side of T4's trapezoidal step over h [s] from slip s0 [m/s] and p0, the drive
    V0, V1 [m/s] and g0, g1 (inclination_slip) at its ends: rho_c p1 - h/2 s1 = rhs0 with
    t4_rho's coefficient in place of rho_c.  The g p term: implicit where g1 >= 0 (it holds the
    slide), from p0 where g1 < 0 (implicit, it would turn T4's residual non-monotone in s1
    where rho_c is small)."""
    return O[O_RHO] * p0 + 0.5 * h * (s0 - V0 - V1 - (g0 + min(g1, 0.0)) * p0)


def t4_rho(O, g1, h):
    """T4's coefficient of p1 [m] in its trapezoidal step over h [s] (t4_rhs): rho_c + h/2
    max(g1, 0)."""
    return O[O_RHO] + 0.5 * h * max(g1, 0.0)


def row_carried(O, p):
    """The needle row's load over the pressing load F per newton of the groove's normal force
    f_n [1/N]: T6's Fx / f_n without its p xi term, sqrt(1 - p^2) + p^2, over F.  The row's
    friction and rolling resistance scale with its load, as its needle loads do (the lumped
    row's q at its offset): f_n row_carried(p) times their values at F."""
    return (math.sqrt(1.0 - p * p) + p * p) / O[O_F]


def normal_force(O, p, start=0.0):
    """T5: f_n [N] at p [1].  With the needle row (O_KRR, its stiffness along the load at F)
    the row yields in series with the Hertz contact: the roller's centre, rho_c from the
    flank's centre at p = 0, gives way by the row's load beyond F over k_r, the load being
    f_n row_carried(p) F (T6's Fx), so f_n = K ((rho_c - (f_n h - F) / k_r) / sqrt(1 - p^2)
    - clearance)^1.5, solved by Newton from ``start`` [N] (a nearby solution: a Newton
    iteration's f_n, one or two iterations then instead of four or five), or from F where it
    is 0 (docs/model.md, "The row's load moves with the normal force")."""
    c = math.sqrt(1.0 - p * p)
    kr = O[O_KRR]
    if kr <= 0.0:
        d = O[O_RHO] / c - O[O_CLEAR]
        return O[O_K] * d ** 1.5 if d > 0 else 0.0
    F, K = O[O_F], O[O_K]
    hk = row_carried(O, p) * F / kr       # the roller's give per newton of f_n [m/N]
    f = F
    # a start where the contact still closes (T5's right side falls and is convex in f_n:
    # Newton from there stays where it closes)
    if start > 0.0 and (O[O_RHO] - start * hk + F / kr) / c > O[O_CLEAR]:
        f = start
    for _ in range(30):
        d = (O[O_RHO] - f * hk + F / kr) / c - O[O_CLEAR]
        if not d > 0.0:
            return 0.0
        sd = math.sqrt(d)
        df = (K * d * sd - f) / (1.5 * K * sd * hk / c + 1.0)
        f += df
        if abs(df) <= 1e-14 * F:
            break
    return f


def normal_slope(O, p, fn):
    """d f_n / dp [N] of normal_force at p [1], where it gives fn [N]."""
    c = math.sqrt(1.0 - p * p)
    kr = O[O_KRR]
    rho = O[O_RHO]
    if kr > 0.0:
        rho -= (fn * row_carried(O, p) * O[O_F] - O[O_F]) / kr
    d = rho / c - O[O_CLEAR]
    if not d > 0.0:
        return 0.0
    kh = 1.5 * O[O_K] * math.sqrt(d)        # the Hertz contact's tangent stiffness [N/m]
    if kr <= 0.0:
        return kh * rho * p / (c * c * c)
    dh = 2.0 * p - p / c                    # d(row_carried F) / dp
    give = kh * row_carried(O, p) * O[O_F] / (kr * c)
    return kh * (rho * p / (c * c * c) - fn * dh / (kr * c)) / (1.0 + give)


def beta_at(O, p, fn, bi, dphi, spin):
    """T2: f_b / f_n where the drive gives bi [N], dphi and spin [rad/s]; with the spin moment,
    Eqs. (14)-(16), against the spin w_n = dphi + spin p [rad/s]."""
    b = bi
    if O[O_SM] != 0.0:
        b -= spin_moment(O[O_MU], fn, O[O_A1], dphi + spin * p, O[O_VST]) * p / O[O_R]
    return b / fn


def share(O, s, B):
    """T3 inverted: p >= 0 [1] for the slide slip |s| [m/s] when the spin needs |f_b| / f_n = B:
    the slip vector (s, t) at angle a from the slide, mu tanh(3 |s| / (v_st cos a)) sin a = B,
    solved by bisection and Newton on a in [0, pi/2) (its left side rises from 0 to mu); then
    p = mu tanh(3 |v| / v_st) cos a."""
    mu, k = O[O_MU], 3.0 / O[O_VST]
    B = min(B, mu * (1.0 - 1e-9))
    s = abs(s)
    if B <= 0.0:
        return mu * math.tanh(k * s)
    if s == 0.0:
        return 0.0
    lo, hi = 0.0, 0.5 * math.pi
    a = min(math.asin(min(B / (mu * math.tanh(k * s) + 1e-300), 1.0)), 1.5)
    for _ in range(60):
        c, sn = math.cos(a), math.sin(a)
        th = math.tanh(k * s / c)
        f = mu * th * sn - B
        if f > 0:
            hi = a
        else:
            lo = a
        df = mu * (th * c + sn * (1.0 - th * th) * k * s * sn / (c * c))
        an = a - f / df if df > 0 else 0.5 * (lo + hi)
        if not lo < an < hi:
            an = 0.5 * (lo + hi)
        if abs(an - a) < 1e-10:
            a = an
            break
        a = an
    return mu * math.tanh(k * s / math.cos(a)) * math.cos(a)


def p_at(O, s, bi, dphi, spin, p0, guess):
    """T2, T3, T5: p for the slide slip s [m/s] where the drive gives bi, dphi, spin (beta
    depends weakly on p through f_n and the spin moment: fixed point), from p0 when guess and
    of p's sign (the march: a nearby point's p), else from beta = 0."""
    mu = O[O_MU]
    sign = -1.0 if s > 0 else 1.0
    p = sign * mu * math.tanh(3.0 * abs(s) / O[O_VST])
    if guess and p0 * sign > 0.0:
        p = p0
    for _ in range(6):
        q = sign * share(O, s, abs(beta_at(O, p, normal_force(O, p), bi, dphi, spin)))
        if abs(q - p) < 1e-11 * mu:
            return q
        p = q
    return p


def trapezoid_step(O, rhs0, s, h, bi, dphi, spin, p0, guess, rho):
    """s1 [m/s] of one trapezoidal step of T4 from slip s over h [s]: the root of f(z) = rho
    p(z) - h/2 z - rhs0 (rho: t4_rho), p at the step's end point.  Newton: f falls with slope
    <= -h/2 and |p| <= mu, so its root lies in [lo, hi]; a Newton step that leaves the bracket
    (it overshoots on the tanh's knee and can cycle there) is a bisection instead.  guess (the
    march): p's fixed point starts from p0, then from the last p found."""
    mu, vst = O[O_MU], O[O_VST]
    e = 1e-6 * vst              # finite-difference step of the Newton slope
    lo, hi = -2.0 * (rho * mu + rhs0) / h, 2.0 * (rho * mu - rhs0) / h
    z = min(max(s, lo), hi)
    g = p0
    for _ in range(200):
        p1 = p_at(O, z, bi, dphi, spin, g, guess)
        g = p1
        res = rho * p1 - 0.5 * h * z - rhs0
        if res > 0.0:
            lo = z
        elif res < 0.0:
            hi = z
        else:
            break
        d = (rho * (p_at(O, z + e, bi, dphi, spin, p1, guess) - p1)) / e - 0.5 * h
        dz = -res / d
        if not lo < z + dz < hi:
            dz = 0.5 * (lo + hi) - z
        z += dz
        if abs(dz) < 1e-9 * vst:
            break
    return z


def slip_step(O, rhs0, s, h, bi, dphi, spin, p0, rho):
    """(settled, s1 [m/s], p1 [1]) of one trapezoidal step of T4 from slip s and p0 over h [s],
    the march's first choice: T3 and T4 together as Newton on the slip vector (s, t), t >= 0
    across the slide, where trapezoid_step nests T3's inversion (and T2's fixed point) inside
    its Newton and costs three to four times as much.  The friction mu tanh(k |v|) v / |v| (k =
    3 / v_st) gives p = -mu g s / |v| and |f_b| / f_n = mu g t / |v|; the residuals are T4,
    rho p - h/2 s - rhs0 (rho: t4_rho), and T2's demand, mu g t / |v| - |beta(p)| (capped as
    share caps it), with the friction's Jacobian exact and beta's weak dependence on p left out
    of it.
    Not settled within 30 iterations to 1e-9 v_st (the start from rest, some steps after a
    jump: about one step in 200 over random scenes): the caller takes trapezoid_step.  Where T3
    determines the slip the two agree within 2e-6 of v_st, mu and the thrust over 2000 steps
    (tests/test_traverse.py; measured 1e-11 to 2e-8)."""
    mu, k = O[O_MU], 3.0 / O[O_VST]
    kt = 0.5 * h
    cap = mu * (1.0 - 1e-9)
    tol = 1e-9 * O[O_VST]
    t = 0.0
    if p0 != 0.0:   # the last step's slip angle
        t = abs(s * min(abs(beta_at(O, p0, normal_force(O, p0), bi, dphi, spin)), cap) / p0)
    for _ in range(30):
        v = math.sqrt(s * s + t * t)
        gv, dg, us, ut = k, k, 0.0, 0.0      # the friction's slope at v = 0
        if v > 0.0:
            g = math.tanh(k * v)
            gv, dg, us, ut = g / v, k * (1.0 - g * g), s / v, t / v
        p = -mu * gv * s
        B = min(abs(beta_at(O, p, normal_force(O, p), bi, dphi, spin)), cap)
        a11 = mu * (gv * (1.0 - us * us) + dg * us * us)
        a22 = mu * (gv * (1.0 - ut * ut) + dg * ut * ut)
        a12 = mu * (dg - gv) * us * ut
        r1 = rho * p - kt * s - rhs0
        r2 = mu * gv * t - B
        j11 = -rho * a11 - kt
        j12 = -rho * a12
        det = j11 * a22 - j12 * a12          # < 0: the friction's Jacobian is semi-definite
        if not det < 0.0:
            return False, s, 0.0
        ds = (j12 * r2 - a22 * r1) / det
        dt = (a12 * r1 - j11 * r2) / det
        s += ds
        t = abs(t + dt)
        if abs(ds) < tol and abs(dt) < tol:
            v = math.sqrt(s * s + t * t)
            return True, s, -mu * (math.tanh(k * v) / v if v > 0.0 else k) * s
    return False, s, 0.0


def groove_forces(fn, p, beta, phi, xi, F):
    """T6: (Fz, Fx, Fy, Fz_mod) [N] on the groove from the normal force fn [N], p, beta [1], the
    pitch phi and roll tilt xi [rad], F the pressing load [N].  T1 on the groove: the ideal
    bearing takes no force along the trunnion axis a = (sin xi, cos xi cos phi, cos xi sin phi),
    so F . a = 0 gives Fy."""
    Fz = -fn * (p * math.sin(phi) + beta * math.cos(phi))
    Fx = fn * (math.sqrt(1.0 - p * p) + p * p - p * xi)
    Fy = -(Fx * math.sin(xi) + Fz * math.cos(xi) * math.sin(phi)) / (math.cos(xi) * math.cos(phi))
    return Fz, Fx, Fy, fz_mod(Fx, Fz, F)


# --- the needle row (needle_row = true) -------------------------------------------------------
# The row's terms in the traverse model (docs/model.md, "The row's terms in the reduced model"):
# the needles' sliding friction along the trunnion (T1), their rolling resistance (T2) and the
# roller's tilt b2 about the groove's axis, held quasi-statically by the row's tilt stiffness,
# k_t2 b2 = -r f_n fa + lever row, whose rate moves the groove contact along the trunnion by
# -r b2' and the bore by -lever b2'.
def row_groove_forces(fn, p, fa, beta, row, phi, xi, F):
    """T6 with the row: (Fz, Fx, Fy, Fz_mod) [N] on the groove, as groove_forces with the
    groove's friction along the trunnion fa f_n in place of p f_n, and F . a = -row [N] (the
    row takes the rest of T1's balance)."""
    Fz = -fn * (fa * math.sin(phi) + beta * math.cos(phi))
    Fx = fn * (math.sqrt(1.0 - p * p) + p * fa - fa * xi)
    Fy = -(row + Fx * math.sin(xi) + Fz * math.cos(xi) * math.sin(phi)) \
        / (math.cos(xi) * math.cos(phi))
    return Fz, Fx, Fy, fz_mod(Fx, Fz, F)


def row_rates(O, x):
    """(d' [m/s], psi' [rad/s], d [m]) at whirl angle x [rad]: the trunnion's axial stroke rate,
    Eq. (7) differentiated (sin xi = e sin 2x / s), its yaw rate, Eq. (3) differentiated, and
    its axial stroke, Eq. (7)."""
    w, e, tn, s = O[O_W], O[O_EAX], O[O_TYAW], O[O_S]
    vax = dax = 0.0
    if e != 0.0:
        sxi = e * math.sin(2.0 * x) / s
        cxi = math.sqrt(1.0 - sxi * sxi)
        vax = 2.0 * e * (math.sin(2.0 * x) + sxi / cxi * math.cos(2.0 * x)) * w
        dax = s - (e * math.cos(2.0 * x) + s * cxi)
    tc = tn * math.cos(x)
    return vax, -tn * math.sin(x) / (1.0 + tc * tc) * w, dax


def rolling_moment(O, spin, yaw):
    """The needles' rolling resistance, Eq. (12) [N m]: mu_rolling q r_bore tanh(3 v_r / v_st)
    against the roller's spin relative to the trunnion, v_r = (spin - psi') r_bore (spin, yaw:
    psi' [rad/s]).  It does not depend on p: taken once a step."""
    return O[O_MR] * tanh_clipped(3.0 * (spin - yaw) * O[O_RB] / O[O_VST])


def row_beta(O, p, fn, bi, dphi, spin, m_roll):
    """T2 with the needles' rolling resistance m_roll [N m] (rolling_moment): f_b / f_n."""
    return beta_at(O, p, fn, bi, dphi, spin) - m_roll / (O[O_R] * fn)


ROW_POINTS = 7      # the needles' line contact: points along it (the lumped row's ROW_LINE)


def row_moment(O, dax, p, vax):
    """The moment about e2 [N m] of the row's load acting where its needles are along the
    trunnion, off the roller's centre by the trunnion's stroke relative to the roller, dax -
    rho p (Eq. 7's d [m] less the slide), less the needles' lag behind the trunnion
    (needle_row.needle_lag: ROW_CARRY of the way within their axial play, the stroke rising
    where d' = vax [m/s] >= 0), the whole stroke with the row's friction off; and its slope in
    the stroke [N] (contact.row_load_moment, row_play)."""
    stroke = dax - O[O_RHO] * p
    if O[O_PLAY] < 0.0:         # the row's friction off: the needles ride the stops
        return O[O_CRF] * stroke, O[O_CRF]
    lag, stop = needle_lag(stroke, O[O_EAX], O[O_PLAY], vax >= 0.0)
    return O[O_CRF] * (stroke - lag), O[O_CRF] * (1.0 if stop else ROW_CARRY)


def row_slope(O, dax, vax):
    """The row's tanh slope [s/m] on the roller's slide (row_line): half the slip at each of a
    needle's two contacts (O_KROW), the whole at the bore where a stop carries the needles
    (needle_row.needle_lag at the trunnion's stroke dax [m], rising where vax >= 0; the
    roller's own slide, a few um, left out of where the stop is reached)."""
    if O[O_PLAY] < 0.0:
        return O[O_KROW]
    return 2.0 * O[O_KROW] if needle_lag(dax, O[O_EAX], O[O_PLAY], vax >= 0.0)[1] else O[O_KROW]


def row_line(O, u, b1d, kr):
    """The needles' sliding friction along the trunnion [N] and its slope in u [N s/m]: the
    tanh law on the 2-D slip of two line contacts along the needles (ROW_POINTS points each,
    the needles' load shared alike) on the loaded arc's two sides, +-row_arc across the
    pressing direction (O_ARC): there the slide u [m/s] along the trunnion less -+O_ARC times
    the roller's tilt rate about e1 b1d [rad/s], and across, b1d times the point's place along
    the needle (a needle cannot roll that away); kr [s/m]: the tanh's slope (row_slope).  The
    tilt's slip uses up friction the slide would meet (docs/model.md, the lumped row's line,
    "The needles' friction around the loaded arc")."""
    mq = O[O_MQ]
    if b1d == 0.0:      # every point alike (no spin moment, the march's first step): one tanh
        g = tanh_clipped(kr * u)
        return mq * g, mq * kr * (1.0 - g * g)
    f = df = 0.0
    for side in range(2):
        ua = u + (O[O_ARC] if side == 0 else -O[O_ARC]) * b1d
        for j in range(ROW_POINTS // 2 + 1):     # a point and its mirror about the middle alike
            w = 1.0 if 2 * j + 1 == ROW_POINTS else 2.0
            c = b1d * O[O_LN] * ((j + 0.5) / ROW_POINTS - 0.5)
            v = math.sqrt(ua * ua + c * c)
            g = tanh_clipped(kr * v)
            if v > 0.0:
                f += w * g * ua / v
                df += w * (kr * (1.0 - g * g) * ua * ua / (v * v) + g * c * c / (v * v * v))
            else:
                df += w * kr
    return mq * f / (2 * ROW_POINTS), mq * df / (2 * ROW_POINTS)


def row_tilt_e1(O, p, fn, dphi, spin):
    """The roller's tilt about the pressing direction e1 [rad] under the spin moment (Eq. 16,
    against the spin about the normal w_n = phi' + spin p), held by the row's tilt stiffness
    about e1 k_t1 = k_w l^2 / 12 (elastically: the needles' friction, which resists its rate,
    is left out of its balance)."""
    if O[O_SM] == 0.0 or O[O_KT1] <= 0.0 or fn <= 0.0:
        return 0.0
    return spin_moment(O[O_MU], fn, O[O_A1], dphi + spin * p, O[O_VST]) / O[O_KT1]


def row_at(O, s, b2d, V, vax, yaw, dax, bi, dphi, spin, b1d):
    """T1-T3, T5 with the row at the slide slip s [m/s] and tilt rate b2d [rad/s], where the
    drive gives V (T4's driven slip), vax, yaw, dax (row_rates), bi, dphi, spin, and the tilt
    about e1 moves at b1d [rad/s]: (p, fa, f_n [N], beta, row [N]).  fa: the groove's friction along
    the trunnion over f_n, against its contact's slip s - r b2d (T3 inverted); row: the needles'
    friction (row_line) against the roller's slide on the trunnion, u = s - V - d' - lever b2d,
    at the load the row carries (row_carried); T1: f_n p = f_n fa - row (fixed point in p)."""
    sg = s - O[O_R] * b2d
    row0 = row_line(O, s - V - vax - O[O_LEVER] * b2d, b1d, row_slope(O, dax, vax))[0]
    m_roll0 = rolling_moment(O, spin, yaw)
    sign = -1.0 if sg > 0 else 1.0
    p = fa = 0.0
    fn = normal_force(O, p)
    beta = row_beta(O, p, fn, bi, dphi, spin, m_roll0 * fn * row_carried(O, p))
    for _ in range(40):
        fa = sign * share(O, sg, abs(beta))
        pn = fa - row0 * row_carried(O, p)
        done = abs(pn - p) < 1e-14
        p = pn
        fn = normal_force(O, p)
        beta = row_beta(O, p, fn, bi, dphi, spin, m_roll0 * fn * row_carried(O, p))
        if done:
            break
    return p, fa, fn, beta, row0 * fn * row_carried(O, p)


def row_step(O, rhs0, s, t, b2, b2d, h, x, b1d):
    """(settled, s1, t1, b2_1, then row_at's p, fa, f_n, beta, row there) of one step with the
    row to whirl angle x [rad] (the drive there: drive_at, row_rates), Newton starting from
    slip s [m/s] (the step's own start is in rhs0), cross slip t >= 0 and tilt b2 [rad], over
    h [s], the tilt about e1 moving at b1d [rad/s] (the step before's): T4's trapezoidal
    rule, rho p - h/2 s1 = rhs0 (t4_rho, t4_rhs), with the tilt's
    balance k_t2 b2_1 + r f_n fa - lever row = 0 by backward Euler (b2' = (b2_1 - b2) / h), as
    Newton on (s1, t1, b2_1) in the way of slip_step: the groove's friction mu tanh(k |v|) v /
    |v| on its contact's slip vector (s - r b2', t), t across the slide; p = fa - row / f_n,
    with f_n's and beta's dependence on p in the Jacobian (beta's by a difference); a step is
    cut to move no slip by more than half of v_st or of the slip.  Settled where a step moved
    every slip by less than 1e-9 v_st, or where the steps contract fast enough that what is
    left, rate / (1 - rate) times the last step (Hairer and Wanner's estimate, rate the last
    step over the one before), is below that; not settled within 40 iterations: the caller
    takes row_trapezoid."""
    _phi, _xi, V, dphi, spin, bi = drive_at(O, x)
    vax, yaw, dax = row_rates(O, x)
    m_roll = rolling_moment(O, spin, yaw)
    rho, mu, k = O[O_RHO], O[O_MU], 3.0 / O[O_VST]
    r, lev, kt2 = O[O_R], O[O_LEVER], O[O_KT2]
    kr = row_slope(O, dax, vax)
    rho4 = t4_rho(O, inclination_slip(O, x), h)
    kt = 0.5 * h
    cap = mu * (1.0 - 1e-9)
    tol = 1e-9 * O[O_VST]
    arm = max(r, lev) / h
    b0 = b2
    b2 = b0 + h * b2d           # the last step's tilt rate carried on: the first iterate
    p = 0.0
    fn = O[O_F]      # (Newton's start for T5: the last iterate's f_n)
    sat = False
    last = 0.0       # the step before's size (how fast the steps contract)
    for _ in range(40):
        b2d = (b2 - b0) / h
        sg = s - r * b2d
        v = math.sqrt(sg * sg + t * t)
        gv, dg, us, ut = k, k, 0.0, 0.0      # the friction's slope at v = 0
        if v > 0.0:
            g = tanh_clipped(k * v)
            gv, dg, us, ut = g / v, k * (1.0 - g * g), sg / v, t / v
        if sat:     # the spin takes all the friction: none along the trunnion, t frozen
            gv, dg = 0.0, 0.0
        fa = -mu * gv * sg
        ur = s - V - vax - lev * b2d
        row0, dr0 = row_line(O, ur, b1d, kr)
        for _ in range(8):         # T1: p = fa - row / f_n, row proportional to f_n
            pn = fa - row0 * row_carried(O, p)
            done = abs(pn - p) < 1e-15
            p = pn
            if done:
                break
        fn = normal_force(O, p, fn)
        hq = row_carried(O, p)
        w = fn * hq
        row, dr = row0 * w, dr0 * w
        B = abs(row_beta(O, p, fn, bi, dphi, spin, m_roll * w))
        if B >= cap and not sat:
            # the spin's demand for friction is all the contact has (a fast whirl's spin
            # inertia): the slip runs across the slide without bound and the friction along
            # the trunnion vanishes (T3's share: 4.5e-5 mu at the cap); so it is taken as 0
            sat = True
            continue
        B = min(B, cap)
        a11 = mu * (gv * (1.0 - us * us) + dg * us * us)
        a22 = mu * (gv * (1.0 - ut * ut) + dg * ut * ut) if not sat else 1.0
        a12 = mu * (dg - gv) * us * ut
        r1 = rho4 * p - kt * s - rhs0
        r2 = mu * gv * t - B if not sat else 0.0
        mo, dmo = row_moment(O, dax, p, vax)
        r3 = kt2 * b2 + r * fn * fa - lev * row - mo
        # the Jacobian in (s1, t1, b2_1): d(sg)/d(b2_1) = -r / h, d(u)/d(b2_1) = -lever / h;
        # p's (dp1, dp2, dp3) = d(fa) - d(row) / f_n, and the tilt's moment r f_n fa with
        # f_n's rise with p (T5)
        q = math.sqrt(1.0 - p * p)
        fnp = normal_slope(O, p, fn)
        hqp = (2.0 * p - p / q) / O[O_F]
        c = 1.0 / (1.0 + row0 * hqp)
        dp1 = c * (-a11 - dr0 * hq)
        dp2 = -c * a12
        dp3 = c * (a11 * r + dr0 * hq * lev) / h
        mf = r * fa * fnp + dmo * rho - lev * row0 * (fnp * hq + fn * hqp)
        j11 = rho4 * dp1 - kt
        j12 = rho4 * dp2
        j13 = rho4 * dp3
        # beta's dependence on p (f_n, the spin moment), by a difference
        pe = p + 1e-7
        fne = normal_force(O, pe, fn)
        m_e = m_roll * fne * row_carried(O, pe)
        db_dp = (min(abs(row_beta(O, pe, fne, bi, dphi, spin, m_e)), cap)
                 - B) / 1e-7 if not sat else 0.0
        j21 = a12 - db_dp * dp1
        j22 = a22 - db_dp * dp2
        j23 = -a12 * r / h - db_dp * dp3
        j31 = -r * fn * a11 - lev * dr + mf * dp1
        j32 = -r * fn * a12 + mf * dp2
        j33 = kt2 + (r * fn * a11 * r + lev * dr * lev) / h + mf * dp3
        c11 = j22 * j33 - j23 * j32
        c12 = j23 * j31 - j21 * j33
        c13 = j21 * j32 - j22 * j31
        det = j11 * c11 + j12 * c12 + j13 * c13
        if not (det != 0.0 and math.isfinite(det)):
            return False, s, t, b2, 0.0, 0.0, 0.0, 0.0, 0.0
        # -J^-1 (r1, r2, r3) by the adjugate
        ds = -(c11 * r1 + (j13 * j32 - j12 * j33) * r2 + (j12 * j23 - j13 * j22) * r3) / det
        dt = -(c12 * r1 + (j11 * j33 - j13 * j31) * r2 + (j13 * j21 - j11 * j23) * r3) / det
        db = -(c13 * r1 + (j12 * j31 - j11 * j32) * r2 + (j11 * j22 - j12 * j21) * r3) / det
        # a step that moves a contact's slip by more than half of v_st or of the slip itself
        # is cut to that: the full step overshoots where a friction saturates and can cycle
        # between its two sides
        big = max(abs(ds), abs(db) * arm) / (0.5 * max(O[O_VST], abs(sg), abs(ur)))
        if big > 1.0:
            ds, dt, db = ds / big, dt / big, db / big
        # t at most doubles (and v_st / 2): where the spin takes nearly all the friction the
        # cross slip runs far out along the tanh's flat top
        dt = min(dt, t + 0.5 * O[O_VST])
        s += ds
        t = abs(t + dt)
        b2 += db
        if not (abs(s) < 1e3 and t < 1e3):      # run away (no slip reaches 1 km/s)
            return False, s, t, b2, 0.0, 0.0, 0.0, 0.0, 0.0
        e = max(abs(ds), abs(dt), abs(db) * arm)
        rate = e / last if last > 0.0 else 1.0
        last = e
        # (a step cut by ``big`` says nothing of the rate; a contraction above 1/2 is not
        # trusted to go on)
        if e < tol or (big <= 1.0 and rate < 0.5 and rate / (1.0 - rate) * e < tol):
            # the friction, p and beta where it settled
            b2d = (b2 - b0) / h
            sg = s - r * b2d
            v = math.sqrt(sg * sg + t * t)
            fa = -mu * (tanh_clipped(k * v) / v if v > 0.0 else k) * sg if not sat else 0.0
            row0 = row_line(O, s - V - vax - lev * b2d, b1d, kr)[0]
            p = fa - row0 * row_carried(O, p)
            fn = normal_force(O, p, fn)
            row = row0 * fn * row_carried(O, p)
            beta = row_beta(O, p, fn, bi, dphi, spin, m_roll * fn * row_carried(O, p))
            if sat and abs(beta) < cap * (1.0 - 1e-6):
                return False, s, t, b2, 0.0, 0.0, 0.0, 0.0, 0.0   # (it was not saturated)
            return True, s, t, b2, p, fa, fn, beta, row
    return False, s, t, b2, 0.0, 0.0, 0.0, 0.0, 0.0


def row_tilt_balance(O, s, b, b0, h, x, b1d):
    """The tilt's balance k_t2 b + r f_n fa - lever row - c F (d - rho_c p) [N m] at slide slip
    s [m/s] and tilt b [rad] (b2' = (b - b0) / h) at whirl angle x [rad] (the drive there:
    drive_at, row_rates; the tilt rate about e1 b1d [rad/s]), and p there: (balance, p)."""
    _phi, _xi, V, dphi, spin, bi = drive_at(O, x)
    vax, yaw, dax = row_rates(O, x)
    p, fa, fn, _beta, row = row_at(O, s, (b - b0) / h, V, vax, yaw, dax, bi, dphi, spin, b1d)
    return (O[O_KT2] * b + O[O_R] * fn * fa - O[O_LEVER] * row
            - row_moment(O, dax, p, vax)[0]), p


def row_tilt(O, s, b0, h, x, b1d):
    """b2_1 [rad] where the tilt's balance (row_tilt_balance) holds at slide slip s [m/s]
    (b2' = (b2_1 - b0) / h): it rises with b2_1 (the friction of both contacts opposes their
    slips, which b2' lowers), so regula falsi (Illinois) in the bracket where the two
    frictions are spent."""
    mu, rho = O[O_MU], O[O_RHO]
    dax = row_rates(O, x)[2]
    pmax = min(mu + 1.01 * O[O_MQ] / O[O_F], 0.9)
    fmax = normal_force(O, pmax)
    # the row's load's moment is within cm (|d| + rho p_max + extra) (row_moment): the stroke's
    # ROW_CARRY where the needles never reach a stop, the stroke and the play where they do
    cm, extra = O[O_CRF], 0.0
    if O[O_PLAY] >= 0.0:
        if (1.0 - ROW_CARRY) * O[O_EAX] <= O[O_PLAY]:
            cm = ROW_CARRY * O[O_CRF]
        else:
            extra = O[O_PLAY]
    m = 1.01 * (O[O_R] * fmax * mu + O[O_LEVER] * O[O_MQ] * 1.01 * fmax / O[O_F]
                + cm * (abs(dax) + rho * pmax + extra)) / O[O_KT2] + 1e-12
    lo, hi = -m, m
    flo = row_tilt_balance(O, s, lo, b0, h, x, b1d)[0]
    hi_f = row_tilt_balance(O, s, hi, b0, h, x, b1d)[0]
    side = 0
    b = 0.0
    for _ in range(200):
        b = (lo * hi_f - hi * flo) / (hi_f - flo) if hi_f != flo else 0.5 * (lo + hi)
        if not lo < b < hi:
            b = 0.5 * (lo + hi)
        f = row_tilt_balance(O, s, b, b0, h, x, b1d)[0]
        if f > 0.0:
            hi, hi_f = b, f
            if side == 1:
                flo *= 0.5
            side = 1
        elif f < 0.0:
            lo, flo = b, f
            if side == -1:
                hi_f *= 0.5
            side = -1
        else:
            break
        if hi - lo < 1e-13 * m:
            break
    return b


def row_t4(O, rhs0, rho, z, b0, h, x, b1d):
    """T4's trapezoidal residual rho p - h/2 z - rhs0 (rho: t4_rho) at slide slip z [m/s] with
    the tilt balanced (row_tilt), and that tilt [rad]: (residual, b2_1)."""
    b = row_tilt(O, z, b0, h, x, b1d)
    p = row_tilt_balance(O, z, b, b0, h, x, b1d)[1]
    return rho * p - 0.5 * h * z - rhs0, b


def row_trapezoid(O, rhs0, rho, s, b0, h, x, b1d):
    """(s1 [m/s], b2_1 [rad]) of one step with the row where row_step does not settle: T4's
    residual over s1, the tilt balanced at each (row_t4); it falls with s1 (slope <= -h/2)
    within the bracket |p| <= mu_groove + mu_needle q / f_n: regula falsi (Illinois)."""
    pmax = O[O_MU] + 1.01 * O[O_MQ] / O[O_F]
    lo, hi = -2.0 * (rho * pmax + rhs0) / h, 2.0 * (rho * pmax - rhs0) / h
    flo = row_t4(O, rhs0, rho, lo, b0, h, x, b1d)[0]
    hi_f = row_t4(O, rhs0, rho, hi, b0, h, x, b1d)[0]
    side = 0
    z = s
    b = b0
    for _ in range(200):
        z = (lo * hi_f - hi * flo) / (hi_f - flo) if hi_f != flo else 0.5 * (lo + hi)
        if not lo < z < hi:
            z = 0.5 * (lo + hi)
        f, b = row_t4(O, rhs0, rho, z, b0, h, x, b1d)
        if f > 0.0:
            lo, flo = z, f
            if side == -1:
                hi_f *= 0.5
            side = -1
        elif f < 0.0:
            hi, hi_f = z, f
            if side == 1:
                flo *= 0.5
            side = 1
        else:
            break
        if hi - lo < 1e-10 * O[O_VST]:
            break
    return z, b


def row_advance(O, rhs0, s, t, b2, b2d, h, x, b1d):
    """(s1, t1, b2_1, p, fa, f_n, beta, row) of one step with the row to whirl angle x [rad]
    (row_at's at its end):
    row_step, or row_trapezoid where it does not settle (t1 then 0: the next Newton starts
    across the slide afresh)."""
    res = row_step(O, rhs0, s, t, b2, b2d, h, x, b1d)
    if res[0]:
        return res[1], res[2], res[3], res[4], res[5], res[6], res[7], res[8]
    _phi, _xi, V, dphi, spin, bi = drive_at(O, x)
    vax, yaw, dax = row_rates(O, x)
    rho = t4_rho(O, inclination_slip(O, x), h)
    s1, b21 = row_trapezoid(O, rhs0, rho, s, b2, h, x, b1d)
    p, fa, fn, beta, row = row_at(O, s1, (b21 - b2) / h, V, vax, yaw, dax, bi, dphi, spin, b1d)
    return s1, 0.0, b21, p, fa, fn, beta, row


# --- the slide stepped in time (inputs that move) ---------------------------------------------
def march(O, X, r, x, dt):
    """The slide of the roller whose march row starts at X[r] stepped in time at O from whirl
    angle x [rad] over dt [s] (T4 is an ODE in time; the table is its periodic solution), by the
    table's trapezoidal rule in substeps of at most the table's spacing (each by slip_step, or
    trapezoid_step where that does not settle; with the needle row by row_advance, the tilt
    beside the slip, the tilt about e1 following p a step late: R_B1D, its Newton starting
    from the slip's last rate carried on: R_SD); the row's outputs at the end (T5, T2, T6).
    From rest (no slip yet): on the groove bottom, p = 0, no tilt.  Returns x at the end.  The
    caller checks the substeps' count (steps_of)."""
    n, h = steps_of(O, dt)
    wh = O[O_W] * h
    _phi, _xi, V0, dphi, spin, _bi = drive_at(O, x)
    g0 = inclination_slip(O, x)
    s, p, b2, bd, tt = X[r + R_S], X[r + R_P], X[r + R_B2], X[r + R_B2D], X[r + R_T]
    b1d, sd = X[r + R_B1D], X[r + R_SD]
    if X[r + R_HAS_S] == 0.0:
        s, p, b2, bd, tt, b1d, sd = V0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    row = O[O_ROW] != 0.0
    b1 = row_tilt_e1(O, p, normal_force(O, p), dphi, spin) if row else 0.0
    phi = xi = bi = dphi = spin = fa = fn = beta = rw = 0.0
    for i in range(n):
        x1 = x + wh * (i + 1)
        phi, xi, V1, dphi, spin, bi = drive_at(O, x1)
        g1 = inclination_slip(O, x1)
        if O[O_HELD] != 0.0:
            rhs0 = t4_rhs(O, s, p, V0, V1, g0, g1, h)
            if row:
                b20, s0 = b2, s
                # Newton starts from the slip's last rate carried on (at most v_st / 2 on): a
                # step fewer, where it started from the slip as it was
                ds = max(-0.5 * O[O_VST], min(0.5 * O[O_VST], h * sd))
                s, tt, b2, p, fa, fn, beta, rw = row_advance(O, rhs0, s + ds, tt, b2, bd, h, x1,
                                                             b1d)
                sd = (s - s0) / h
                bd = (b2 - b20) / h
                b11 = row_tilt_e1(O, p, fn, dphi, spin)
                b1d = (b11 - b1) / h
                b1 = b11
            else:
                rho = t4_rho(O, g1, h)
                ok, s1, p1 = slip_step(O, rhs0, s, h, bi, dphi, spin, p, rho)
                if ok:
                    s, p = s1, p1
                else:
                    s = trapezoid_step(O, rhs0, s, h, bi, dphi, spin, p, True, rho)
                    p = p_at(O, s, bi, dphi, spin, p, True)
        V0, g0 = V1, g1
    if O[O_HELD] == 0.0:
        s, p = V0, 0.0
    if row:
        Fz, Fx, Fy, Fzm = row_groove_forces(fn, p, fa, beta, rw, phi, xi, O[O_F])
    else:
        fn = normal_force(O, p) if O[O_F] > 0 else 0.0
        beta = beta_at(O, p, fn, bi, dphi, spin) if fn > 0 else 0.0
        Fz, Fx, Fy, Fzm = groove_forces(fn, p, beta, phi, xi, O[O_F])
    X[r + R_B2] = b2
    X[r + R_B2D] = bd
    X[r + R_T] = tt
    X[r + R_B1D] = b1d
    X[r + R_SD] = sd
    X[r + R_S] = s
    X[r + R_P] = p
    X[r + R_FZ] = Fz
    X[r + R_FZ_MOD] = Fzm
    X[r + R_FX] = Fx
    X[r + R_FY] = Fy
    X[r + R_SLIP] = abs(s)
    X[r + R_HAS_S] = 1.0
    X[r + R_HAS_OUT] = 1.0
    return x + wh * n


def substeps(O, dt):
    """The march's substeps over dt [s] (at most the table's spacing), before rounding up."""
    return abs(O[O_W]) * dt * N_PER_CYCLE / (2.0 * math.pi) - 1e-9


def steps_of(O, dt):
    """(n, h [s]): the march's substeps over dt [s]."""
    n = max(1, int(math.ceil(substeps(O, dt))))
    return n, dt / n


# the functions kernel.py compiles (callees first)
COMPILED = ("transition_velocity", "row_point", "operating_point", "thrust_at", "drive_at",
            "inclination_slip", "t4_rhs", "t4_rho", "row_carried", "normal_force",
            "normal_slope", "beta_at", "share", "p_at",
            "trapezoid_step", "slip_step", "groove_forces", "row_groove_forces", "row_rates",
            "rolling_moment", "row_beta", "row_moment", "row_slope", "row_line", "row_tilt_e1",
            "row_at", "row_step", "row_tilt_balance", "row_tilt", "row_t4", "row_trapezoid", "row_advance", "substeps",
            "steps_of", "march")
