"""The reduced traverse model's settled table: the periodic solution of T4 over one whirl cycle
(the trapezoidal rule, its start by a secant on the cycle map), its interpolation, and the
regime it shows.  Scalar functions over flat arrays (D: the derivation's work, T: the table,
SS, PS: the settled cycle's slip and p), as equations.py: one source for traverse.Traverse and
the analytic FMU (kernel.py).
"""
import math

from .equations import (N_PER_CYCLE, O_F, O_HELD, O_MU, O_ROW, O_VST, O_W, TWO_PI, beta_at,
                        drive_at, groove_forces, inclination_slip, normal_force, p_at,
                        row_advance, row_at, row_groove_forces, row_rates, row_tilt_e1, t4_rho,
                        t4_rhs, thrust_at, trapezoid_step)

# --- the reduced traverse model's table -------------------------------------------------------
PERIODIC_TOL = 1e-7        # the secant's target: |s(2 pi) - s(0)| <= PERIODIC_TOL x v_st
SETTLED_TOL = 1e-5         # periodic enough: the tanh friction moves by <= 3 SETTLED_TOL of
                           # mu f_n over the mismatch, far below compare's 0.1 % settling
STALL = 3                  # cycles without a better one: the secant is in the map's noise
MAX_CYCLES = 60            # cycles of the cycle map the secant may run
MICRO_SLIP_G = 0.95        # friction never above 95 % of mu_s f_n: the roller never slides across
FULL_SLIP_REL = 0.05       # order 3 within 5 % (complex) of Eq. (27): Eqs. 18-27 hold
REGIME_FULL_SLIP, REGIME_TRAVERSE, REGIME_MICRO_SLIP = 0, 1, 2   # scene.REGIME_CODES


# per table point: driven slip V, T2's inertia part bi, dphi, spin, phi, xi; the cycle run and
# the best one (slip s, p, the roller's tilt b2 on the row)
(D_V, D_BI, D_DPHI, D_SPIN, D_PHI, D_XI, D_SS, D_PS, D_B2, D_BEST_SS, D_BEST_PS, D_BEST_B2,
 D_COUNT) = range(13)

# --- the periodic solution: the settled table -------------------------------------------------
# D (work, n + 1 values a row, rows D_*): the driving motion at the table's n + 1 points, the
# cycle run and the best one; T: the table (n + 1 rows of Fz, Fz_mod, Fx, Fy [N], slip speed
# [m/s]); SS, PS: the settled cycle's slide slip s [m/s] and p [1] at the table's points
def drive_table(O, D, n):
    """The driving motion at the table's points (whirl angles 2 pi i / n) into D."""
    m = n + 1
    for i in range(m):
        phi, xi, V, dphi, spin, bi = drive_at(O, 2.0 * math.pi * i / n)
        D[D_V * m + i] = V
        D[D_BI * m + i] = bi
        D[D_DPHI * m + i] = dphi
        D[D_SPIN * m + i] = spin
        D[D_PHI * m + i] = phi
        D[D_XI * m + i] = xi
        D[D_B2 * m + i] = 0.0


def table_p(O, D, n, i, s):
    """p at table point i for the slide slip s [m/s]."""
    m = n + 1
    return p_at(O, s, D[D_BI * m + i], D[D_DPHI * m + i], D[D_SPIN * m + i], 0.0, False)


def table_row_at(O, D, n, i, s, b2d, b1d):
    """row_at at table point i: (p, fa, f_n, beta, row) for the slide slip s [m/s] and the
    tilt rates b2d, b1d [rad/s]."""
    m = n + 1
    vax, yaw, dax = row_rates(O, 2.0 * math.pi * i / n)
    return row_at(O, s, b2d, D[D_V * m + i], vax, yaw, dax, D[D_BI * m + i], D[D_DPHI * m + i],
                  D[D_SPIN * m + i], b1d)


def table_tilt_e1(O, D, n, k, p):
    """row_tilt_e1 at table point k (taken modulo n: point n is point 0) with p there."""
    m = n + 1
    k = k % n
    return row_tilt_e1(O, p, normal_force(O, p), D[D_DPHI * m + k], D[D_SPIN * m + k])


def table_b1_rate(O, D, n, i, ps, h):
    """The tilt rate about e1 [rad/s] the step into table point i takes (the step before's,
    as the march has it), from the p of row ps (D_PS or D_BEST_PS) over the cycle."""
    return (table_tilt_e1(O, D, n, i - 1, D[ps + (i - 1) % n])
            - table_tilt_e1(O, D, n, i - 2, D[ps + (i - 2) % n])) / h


def row_cycle(O, D, n, s0):
    """cycle with the needle row: the roller's tilt b2 on the row stepped beside the slip
    (row_advance), from where the cycle run before ended (its b2 and b2'; 0 at the first).
    Returns s at the cycle's end."""
    m = n + 1
    h = 2.0 * math.pi / O[O_W] / n
    v, ss, ps, bs = D_V * m, D_SS * m, D_PS * m, D_B2 * m
    b2 = D[bs + n]
    b2d = (D[bs + n] - D[bs + n - 1]) / h
    # the tilt about e1 at the cycle run before's last step, and its rate into it
    b1 = table_tilt_e1(O, D, n, n - 1, D[ps + n - 1])
    b1d = (b1 - table_tilt_e1(O, D, n, n - 2, D[ps + n - 2])) / h
    s, t = s0, 0.0
    p0 = table_row_at(O, D, n, 0, s, b2d, b1d)[0]
    b11 = table_tilt_e1(O, D, n, 0, p0)
    b1d, b1 = (b11 - b1) / h, b11
    D[ss] = s
    D[ps] = p0
    D[bs] = b2
    g0 = inclination_slip(O, 0.0)
    for i in range(n):
        j = i + 1
        g1 = inclination_slip(O, 2.0 * math.pi * j / n)
        rhs0 = t4_rhs(O, s, p0, D[v + i], D[v + j], g0, g1, h)
        g0 = g1
        b0 = b2
        s, t, b2, p0, _fa, _fn, _beta, _row = row_advance(O, rhs0, s, t, b2, b2d, h,
                                                          2.0 * math.pi * j / n, b1d)
        b2d = (b2 - b0) / h
        b11 = table_tilt_e1(O, D, n, j, p0)
        b1d, b1 = (b11 - b1) / h, b11
        D[ss + j] = s
        D[ps + j] = p0
        D[bs + j] = b2
    return s


def cycle(O, D, n, s0):
    """One whirl cycle of T4, rho_c dp/dt = s - V', by the trapezoidal rule in s (never
    singular: d(rho_c p - h s / 2)/ds <= -h / 2) from slide slip s0 [m/s]: s and p at every
    table point into D (D_SS, D_PS).  Returns s at the cycle's end."""
    if O[O_ROW] != 0.0:
        return row_cycle(O, D, n, s0)
    m = n + 1
    h = 2.0 * math.pi / O[O_W] / n
    v, ss, ps = D_V * m, D_SS * m, D_PS * m
    s = s0
    p0 = table_p(O, D, n, 0, s)
    D[ss] = s
    D[ps] = p0
    g0 = inclination_slip(O, 0.0)
    for i in range(n):
        j = i + 1
        g1 = inclination_slip(O, 2.0 * math.pi * j / n)
        rhs0 = t4_rhs(O, s, p0, D[v + i], D[v + j], g0, g1, h)
        g0 = g1
        s = trapezoid_step(O, rhs0, s, h, D[D_BI * m + j], D[D_DPHI * m + j],
                           D[D_SPIN * m + j], 0.0, False, t4_rho(O, g1, h))
        p0 = table_p(O, D, n, j, s)
        D[ss + j] = s
        D[ps + j] = p0
    return s


def keep_best(D, n):
    """The cycle just run (D_SS, D_PS) as the best one."""
    m = n + 1
    for i in range(m):
        D[D_BEST_SS * m + i] = D[D_SS * m + i]
        D[D_BEST_PS * m + i] = D[D_PS * m + i]
        D[D_BEST_B2 * m + i] = D[D_B2 * m + i]


def periodic(O, D, n):
    """The slide slip over one cycle with s(2 pi) = s(0): secant on the cycle map; the best
    cycle run into D (D_BEST_SS, D_BEST_PS).  Returns (cycles run, |s(2 pi) - s(0)| [m/s]).
    The cycle map carries the rounding of n inner solves, amplified where the slip crosses the
    tanh's knee (up to about 1e-5 v_st, measured): where the secant wanders in that noise (no
    better cycle in STALL tries) and the best cycle is within SETTLED_TOL, it stops there."""
    vst = O[O_VST]
    tol = PERIODIC_TOL * vst
    a = 0.0
    ga = cycle(O, D, n, a) - a
    b = a + ga
    gb = cycle(O, D, n, b) - b
    best = abs(gb)
    keep_best(D, n)
    stall = 0
    used = 2
    while abs(gb) > tol and gb != ga and used < MAX_CYCLES:
        a, ga, b = b, gb, b - gb * (b - a) / (gb - ga)
        gb = cycle(O, D, n, b) - b
        used += 1
        if abs(gb) < best:
            best, stall = abs(gb), 0
            keep_best(D, n)
        else:
            stall += 1
            if stall >= STALL and best <= SETTLED_TOL * vst:
                break
    return used, best


def traverse_table(O, D, n, T, SS, PS, BS):
    """The settled table at O (O_W > 0) into T, SS, PS and, with the needle row, the roller's
    tilt b2 [rad] at the table's points into BS.  Returns (cycles of the cycle map run, mismatch
    |s(2 pi) - s(0)| [m/s], g_max: the largest groove friction over mu_s f_n [1])."""
    drive_table(O, D, n)
    m = n + 1
    bss, bps, bbs = D_BEST_SS * m, D_BEST_PS * m, D_BEST_B2 * m
    row = O[O_ROW] != 0.0
    h = 2.0 * math.pi / O[O_W] / n
    if O[O_HELD] == 0.0:            # no friction, or no slip to drive it: the roller slips by V
        for i in range(m):
            D[bss + i] = D[D_V * m + i]
            D[bps + i] = 0.0
        cycles, mismatch = 0, 0.0
    else:
        cycles, mismatch = periodic(O, D, n)
    g_max = 0.0
    for i in range(m):
        p = D[bps + i]
        if row:
            # b2' of the step into point i (the cycle's end's into its start)
            k = i if i > 0 else n
            p, fa, fn, beta, rw = table_row_at(O, D, n, i, D[bss + i],
                                               (D[bbs + k] - D[bbs + k - 1]) / h,
                                               table_b1_rate(O, D, n, i, bps, h))
            Fz, Fx, Fy, Fzm = row_groove_forces(fn, p, fa, beta, rw, D[D_PHI * m + i],
                                                D[D_XI * m + i], O[O_F])
            BS[i] = D[bbs + i]
        else:
            fa = p
            fn = normal_force(O, p) if O[O_F] > 0 else 0.0
            beta = beta_at(O, p, fn, D[D_BI * m + i], D[D_DPHI * m + i],
                           D[D_SPIN * m + i]) if fn > 0 else 0.0
            Fz, Fx, Fy, Fzm = groove_forces(fn, p, beta, D[D_PHI * m + i], D[D_XI * m + i],
                                            O[O_F])
            BS[i] = 0.0
        g = math.sqrt(fa * fa + beta * beta)
        if g > g_max:
            g_max = g
        T[5 * i] = Fz
        T[5 * i + 1] = Fzm
        T[5 * i + 2] = Fx
        T[5 * i + 3] = Fy
        T[5 * i + 4] = abs(D[bss + i])
        SS[i] = D[bss + i]
        PS[i] = p
    return cycles, mismatch, (g_max / O[O_MU] if O[O_MU] > 0 else 0.0)


def table_index(n, x):
    """(i, f): the table's interval and the fraction into it at whirl angle x [rad]."""
    u = (x % TWO_PI) * (n / TWO_PI)
    i = int(u)
    if i >= n:
        i = n - 1
    return i, u - i


def table_at(T, n, x, k):
    """Column k (0 Fz, 1 Fz_mod, 2 Fx, 3 Fy [N], 4 slip speed [m/s]) of the table at whirl
    angle x [rad]: linear interpolation."""
    i, f = table_index(n, x)
    a = T[5 * i + k]
    return a + f * (T[5 * (i + 1) + k] - a)


def table_state_at(SS, PS, n, x):
    """(slide slip s [m/s], p [1]) of the settled cycle at whirl angle x [rad]: linear
    interpolation, where the march starts when the inputs begin to move."""
    i, f = table_index(n, x)
    return SS[i] + f * (SS[i + 1] - SS[i]), PS[i] + f * (PS[i + 1] - PS[i])


def order3(T, n, O):
    """Whether the table's order 3 of Fz_mod lies within FULL_SLIP_REL (complex) of Eq.
    (27)'s at O: the sums of y_i exp(-3 j x_i) over the table's points, compared."""
    re_t = im_t = re_e = im_e = 0.0
    for i in range(n):
        x = 2.0 * math.pi * i / n
        c, sn = math.cos(3.0 * x), math.sin(3.0 * x)
        y = T[5 * i + 1]
        e = thrust_at(O, x)[0]
        re_t += y * c
        im_t -= y * sn
        re_e += e * c
        im_e -= e * sn
    d = math.sqrt((re_t - re_e) * (re_t - re_e) + (im_t - im_e) * (im_t - im_e))
    m = math.sqrt(re_e * re_e + im_e * im_e)
    return m > 0 and d <= FULL_SLIP_REL * m


def regime(g_max, T, n, O):
    """REGIME_MICRO_SLIP where the friction never reaches MICRO_SLIP_G of mu_s f_n (g_max [1]),
    else REGIME_FULL_SLIP where the table's order 3 is Eq. (27)'s within FULL_SLIP_REL, else
    REGIME_TRAVERSE."""
    if g_max < MICRO_SLIP_G:
        return REGIME_MICRO_SLIP
    return REGIME_FULL_SLIP if order3(T, n, O) else REGIME_TRAVERSE


# the functions kernel.py compiles (callees first)
COMPILED = ("drive_table", "table_p", "table_row_at", "table_tilt_e1", "table_b1_rate",
            "row_cycle", "cycle", "keep_best",
            "periodic", "traverse_table", "table_index", "table_at", "table_state_at", "order3",
            "regime")
