"""The needle row as one body, Eq. (17) summed over its needles: its load, stiffness and summed
needle loads at an offset of the roller from the trunnion axis, and the offset at a load.  One
source for the contact model's lumped row (fmu_src/tripod_model/oppoint.py, roller_setup.py)
and the reduced model's row terms (equations.py).  Scalar functions, SI units; numba compiles
them into both models' binaries.
"""
import math

# where the row's load acts along the trunnion, as a fraction of the trunnion's axial stroke
# relative to the roller: with the row's friction on, the needles roll between a race that
# strokes (the trunnion) and one that stays (the bore) and go half its way; off, they ride the
# trunnion's stops (the whole)
ROW_CARRY = 0.5


def needle_lag(stroke, E, play, rising):
    """How far the needles lag the trunnion [m] at its axial stroke relative to the roller
    `stroke` [m], and whether a stop carries them: they go ROW_CARRY of the stroke's way between
    a race that strokes and one that stays, lagging by the rest, until the lag reaches their
    axial play `play` [m] either way.  The stroke runs between -E and E [m] (Eq. 7's ends);
    rising: it is moving from -E (else from E).  This play operator, closed-form over the
    stroke's cycle: the lag changes by the rest of the stroke's travel from the stop the
    needles left at the last end (none reached where the rest of the whole stroke fits in the
    play: centred there)."""
    k = 1.0 - ROW_CARRY
    if k * E <= play:
        return k * stroke, False
    if rising:
        lag = -play + k * (stroke + E)
        if lag >= play:
            return play, True
    else:
        lag = play - k * (E - stroke)
        if lag <= -play:
            return -play, True
    return lag, False


def needle_line_stiffness(l_needle):
    """Needle line contact, Eq. (17) / Table 1: delta = 3.8e-5 (N_s f)^0.9 / l^0.8 [mm, N].

    Returns C_line [N/m^(10/9)] with the force on the whole needle f_needle = C_line delta^(10/9)
    (the N_s spheres of one needle share the line contact).
    """
    l_mm = l_needle * 1e3
    # whole-needle force P = N_s f: delta_mm = 3.8e-5 P^0.9 / l^0.8  ->  P = (delta_mm l^0.8/3.8e-5)^(1/0.9)
    c_mm = (l_mm ** 0.8 / 3.8e-5) ** (1.0 / 0.9)            # N / mm^(10/9)
    return c_mm * (1e3) ** (10.0 / 9.0)                     # N / m^(10/9)


def row_constants(n, l_needle):
    """(C1, K_row, q_sum) of a row of n needles of length l_needle [m] without clearance:
    a needle's coefficient across its two races in series, C1 = C_line 2^(-10/9) [N/m^(10/9)]
    (a needle squeezed by g carries C1 g^(10/9)); the row's, F_r = K_row g^(10/9) with the
    needles at 2 pi j / n from the pressing direction, the loaded half summed; and the sum of
    the needle loads over F_r [1]."""
    s19 = s10 = 0.0
    for j in range(n):
        c = math.cos(2.0 * math.pi * j / n)
        if c > 1e-12:
            s19 += c ** (19.0 / 9.0)
            s10 += c ** (10.0 / 9.0)
    c1 = needle_line_stiffness(l_needle) * 2.0 ** (-10.0 / 9.0)
    return c1, c1 * s19, s10 / s19


def sum_row(c, n, c1, a):
    """The row with the roller a >= 0 [m] off the trunnion axis: Eq. (17) on each of its n
    needles at psi_j = 2 pi j / n from the pressing direction, squeezed by a cos(psi_j) - c (c
    the row's radial clearance [m]) across its two races in series (c1: row_constants).
    Returns the radial load |F_r| [N], its tangent stiffness along the load k_r and across it
    k_w [N/m], the sum of the needle loads q [N] (more than |F_r|: the load fans out over
    the row, by 6 % at 4.5 kN and 16 % at 45 kN on the default row) and that sum with each
    load times sin^2(psi_j), q_s [N] (how far across the pressing direction it fans: row_arc)."""
    if not a > c:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    dc, ds = math.cos(2.0 * math.pi / n), math.sin(2.0 * math.pi / n)
    cj, sj = 1.0, 0.0
    f = k = kw = q = qs = 0.0
    # needle j and n - j alike: from the pressing direction outwards while they are loaded
    for j in range(n // 2 + 1):
        ap = a * cj - c
        if not ap > 0.0:
            break
        w = 1.0 if j == 0 or 2 * j == n else 2.0
        g9 = math.exp(math.log(ap) / 9.0)   # ap^(1/9); pow costs more
        g = w * ap * g9
        q += g
        qs += g * sj * sj
        f += g * cj
        k += w * g9 * cj * cj
        kw += w * g9 * sj * sj
        cj, sj = cj * dc - sj * ds, sj * dc + cj * ds   # the next needle's angle
    return c1 * f, 10.0 / 9.0 * c1 * k, 10.0 / 9.0 * c1 * kw, c1 * q, c1 * qs


def row_arc(r_bore, q, qs):
    """Where across the pressing direction the loaded needles meet the bore [m]: r_bore [m]
    times the load-weighted rms of sin(psi_j), sqrt(q_s / q) (sum_row's q, q_s [N]).  The
    needles' sliding friction acts around that arc, not at one point: a tilt rate about the
    pressing direction slides the bore along the trunnion by +-row_arc times it on the arc's two
    sides (docs/model.md, "The needles' friction around the loaded arc")."""
    return r_bore * math.sqrt(qs / q) if q > 0.0 else 0.0


def row_offset(c, n, c1, k_row, F, a_near, F_near):
    """The roller's offset a > c [m] from the trunnion axis where the row's load (sum_row) is
    |F| [N] > 0: Newton from above (the load is convex in the offset), started where every
    needle of the half row would be as loaded as the first (k_row: row_constants), or, where
    a_near > c and F_near > 0, from a_near [m], the offset at the load F_near [N] (a step
    before's)."""
    if a_near > c and F_near > 0.0:
        # each needle's load rises at least as (a - c)^(10/9), so a - c at most as the load:
        # scaled by the loads' ratio where the load rose, a_near stays above the root
        a = c + (a_near - c) * max(abs(F) / F_near, 1.0)
    else:
        a = c + (abs(F) / k_row) ** 0.9 + 2.0 * c
    while sum_row(c, n, c1, a)[0] < abs(F):
        a = c + 2.0 * (a - c)
    for _ in range(60):
        f, k, _kw, _q, _qs = sum_row(c, n, c1, a)
        da = (f - abs(F)) / k
        a -= da
        if not da > 1e-15 * a:
            break
    return a


# the functions the models' binaries compile (callees first)
COMPILED = ("needle_line_stiffness", "sum_row", "row_constants", "row_offset",
            "needle_lag", "row_arc")
