"""The reduced model's equations as scalar functions over flat arrays: the operating point at
the inputs (O_* slots; coast as the drive scene whose turn it is), Eqs. (18)-(27) at a whirl
angle, the traverse model's T1-T6 (traverse.py's header) and the slide stepped in time (the
march).  One source for traverse.Traverse, the analytic FMU's model as Python and its binary
(kernel.py compiles these with its lifecycle: c_functions).  T: the analytic FMU's parameters
in PARAM_NAMES' order; O: an operating point; a march row: R_* slots.  Scalar libm math
throughout, so compiled and Python give the same bits.
"""
import math

from .friction import V_ST_FLOOR, spin_moment
from .hertz import hertz_point
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
T_LEN = len(PARAM_NAMES)

# the operating point: the scene's constants at the inputs of its key, for the scene the reduced
# model runs (coast: drive at the opposite whirl, turned about the trunnion axis)
(O_W, O_TH, O_T, O_KR, O_S, O_R, O_F, O_MU, O_VST, O_K, O_A1, O_CLEAR, O_RHO, O_VP, O_SM, O_I,
 O_HELD, O_MIRROR, O_A, O_B, O_KT, O_MUF, O_THP, O_VPP, O_KSPIN, O_LOAD, O_LEN) = range(27)


# a roller's march row: slide slip s [m/s], p [1], the outputs (Fz, Fz_mod, Fx, Fy [N], slip
# speed [m/s]), whether s and the outputs exist yet (the march starts at rest)
R_S, R_P, R_FZ, R_FZ_MOD, R_FX, R_FY, R_SLIP, R_HAS_S, R_HAS_OUT, R_LEN = range(10)

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


def normal_force(O, p):
    """T5: f_n [N] at p [1]."""
    d = O[O_RHO] / math.sqrt(1.0 - p * p) - O[O_CLEAR]
    return O[O_K] * d ** 1.5 if d > 0 else 0.0


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


def trapezoid_step(O, rhs0, s, h, bi, dphi, spin, p0, guess):
    """s1 [m/s] of one trapezoidal step of T4 from slip s over h [s]: the root of f(z) = rho_c
    p(z) - h/2 z - rhs0, p at the step's end point.  Newton: f falls with slope <= -h/2 and
    |p| <= mu, so its root lies in [lo, hi]; a Newton step that leaves the bracket (it
    overshoots on the tanh's knee and can cycle there) is a bisection instead.  guess (the
    march): p's fixed point starts from p0, then from the last p found."""
    rho, mu, vst = O[O_RHO], O[O_MU], O[O_VST]
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


def slip_step(O, rhs0, s, h, bi, dphi, spin, p0):
    """(settled, s1 [m/s], p1 [1]) of one trapezoidal step of T4 from slip s and p0 over h [s],
    the march's first choice: T3 and T4 together as Newton on the slip vector (s, t), t >= 0
    across the slide, where trapezoid_step nests T3's inversion (and T2's fixed point) inside
    its Newton and costs three to four times as much.  The friction mu tanh(k |v|) v / |v| (k =
    3 / v_st) gives p = -mu g s / |v| and |f_b| / f_n = mu g t / |v|; the residuals are T4,
    rho_c p - h/2 s - rhs0, and T2's demand, mu g t / |v| - |beta(p)| (capped as share caps
    it), with the friction's Jacobian exact and beta's weak dependence on p left out of it.
    Not settled within 30 iterations to 1e-9 v_st (the start from rest, some steps after a
    jump: about one step in 200 over random scenes): the caller takes trapezoid_step.  Where T3
    determines the slip the two agree within 2e-6 of v_st, mu and the thrust over 2000 steps
    (tests/test_traverse.py; measured 1e-11 to 2e-8)."""
    rho, mu, k = O[O_RHO], O[O_MU], 3.0 / O[O_VST]
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


# --- the slide stepped in time (inputs that move) ---------------------------------------------
def march(O, X, r, x, dt):
    """The slide of the roller whose march row starts at X[r] stepped in time at O from whirl
    angle x [rad] over dt [s] (T4 is an ODE in time; the table is its periodic solution), by the
    table's trapezoidal rule in substeps of at most the table's spacing (each by slip_step, or
    trapezoid_step where that does not settle); the row's outputs at the end (T5, T2, T6).  From
    rest (no slip yet): on the groove bottom, p = 0.  Returns x at the end.  The caller checks
    the substeps' count (steps_of)."""
    n, h = steps_of(O, dt)
    wh = O[O_W] * h
    V0 = drive_at(O, x)[2]
    s, p = X[r + R_S], X[r + R_P]
    if X[r + R_HAS_S] == 0.0:
        s, p = V0, 0.0
    phi = xi = bi = dphi = spin = 0.0
    for i in range(n):
        phi, xi, V1, dphi, spin, bi = drive_at(O, x + wh * (i + 1))
        if O[O_HELD] != 0.0:
            rhs0 = O[O_RHO] * p + 0.5 * h * (s - V0 - V1)
            ok, s1, p1 = slip_step(O, rhs0, s, h, bi, dphi, spin, p)
            if ok:
                s, p = s1, p1
            else:
                s = trapezoid_step(O, rhs0, s, h, bi, dphi, spin, p, True)
                p = p_at(O, s, bi, dphi, spin, p, True)
        V0 = V1
    if O[O_HELD] == 0.0:
        s, p = V0, 0.0
    fn = normal_force(O, p) if O[O_F] > 0 else 0.0
    beta = beta_at(O, p, fn, bi, dphi, spin) if fn > 0 else 0.0
    Fz, Fx, Fy, Fzm = groove_forces(fn, p, beta, phi, xi, O[O_F])
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
COMPILED = ("transition_velocity", "operating_point", "thrust_at", "drive_at",
            "normal_force", "beta_at", "share", "p_at", "trapezoid_step", "slip_step",
            "groove_forces", "substeps", "steps_of", "march")
