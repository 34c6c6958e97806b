"""Needle-resolved bearing (bearing = 2): every needle a 6-DOF rigid body of N_s spheres
(section 2.4.2, Fig. 10), contacts to the trunnion, the roller bore, the neighbouring needles,
the trunnion flange and the retainer.  Scalar math for numba (see jit.py).

Frame T (the trunnion frame): origin Q (trunnion axis at the groove mid-plane), e3 = a the
trunnion axis, e1 the pressing direction normal to a, e2 = a x e1.  Relative velocities of two
bodies are frame-independent, so contacts are evaluated with velocities relative to T; the
needles feel T's translational acceleration as an inertial force (its rotation, about
theta w = 11 rad/s, gives forces below 1e-3 of the needle loads and is neglected).

Needle j state, N_F = 11 floats from Y_LEN + 11 j: centre p1, p2, p3 [m], axis tilts t1, t2
(axis direction ~ (t1, t2, 1)), velocity v1..v3 [m/s], angular velocity w1..w3 [rad/s].

Integration, two ways.  The default (integrator 4, kernel.bdf2_substep): a linearly implicit
BDF2 step with the roller and every needle in one system: needle_forces with cpl adds the
roller-needle coupling blocks BN (needle rows, the roller's standard velocities; the friction's
from the moments PB, as for neighbouring needles) and leaves every tangent unscaled; the
roller borders the needles' ring (kernel.coupled_solve: block Cholesky along the open ring,
chain_forward / chain_backward, and the roller's 6 x 6 Schur complement; a closed ring by
ring_solve_m for seven right-hand sides).  One contact evaluation a substep,
linearized at a predicted state, which converges only because the system is the whole one.
The others (kernel.substep, integrators 0, 1, 3): one contact evaluation per substep gives
every body its forces and its implicit tangent (stiffness, contact damping, friction secant);
the needles step together in the ring (ring_solve), the roller on its own 6 velocities, split
from the needles with its and their tangents scaled so the split matrix dominates the coupled
one (C_ROLLER, C_NEEDLE; _contact).  Either way the implicit step damps the 300 kHz contact
modes of the needles (300 times lighter than the roller) instead of resolving them
(L-stable); the contact damping (_normal) takes the rebound out of free needles hitting a
race.

needle_forces' arguments: Y[y0:] the needle states; o, vo: roller centre and its velocity in T
[m, m/s]; ob: bore axis direction (unit); wr: roller angular velocity in T [rad/s]; e1x, ax:
global x in T (e1x e1 + ax e3); d_tr, dd_tr: trunnion material axial offset [m] and velocity
[m/s]; om_tr: trunnion spin about e3 [rad/s]; g1..g3: acceleration of the frame origin in T
[m/s^2]; hk: the step of the stiffness's K v term (h, or 0 from a predicted state); cpl: one
system (BN, PB filled) or split.  Scratch: SP (N x N_s x 3) sphere centres, MOM, PM (N x 10)
friction moments of each needle and each neighbour pair, RS (6 x 13) and MR (10) the
roller's system in its standard velocities and its friction moments, gn, gn2 (6), BN
(N x 6 x 6) and PB (N x 10) the roller-needle coupling and its friction moments.
"""
import math

from .jit import inline, njit

from .layout import (  # noqa: F401  (re-exported: NDL.N_F etc.)
    N_F, N_N, N_NS, N_RN, N_RT, N_RBR, N_LN, N_MN, N_I1, N_I3, N_CS, N_DC, N_ZAX, N_HW,
    N_MU, N_MUR, N_FRIC, N_ROLLR, N_LEN,
    D_BORE, D_TRUN, D_NEIGH, D_FLANGE, D_R1, D_R2, D_R3, D_LEN)

E10_9 = 10.0 / 9.0
C_ROLLER = 1.25   # implicit tangent factors of a roller-needle contact (eps = 0.25, _contact)
C_NEEDLE = 5.0


@inline
def _tanh(x):
    """tanh(x) from one exp: glibc's tanh takes about 2.4 times as long, and the row calls it
    about 1100 times an evaluation (13 % of the contacts' time).  Relative error below 3e-13
    (tests/test_needles.py); NaN stays NaN."""
    a = abs(x)
    if a >= 19.0:
        t = 1.0                      # exact in double precision
    elif a < 1e-4:
        t = a * (1.0 - a * a / 3.0)  # series: 1 - e would cancel
    else:
        e = math.exp(-2.0 * a)
        t = (1.0 - e) / (1.0 + e)
    return t if x >= 0.0 else -t


@inline
def _contact(F1, F2, F3, n1, n2, n3, r1, r2, r3, kp, coef, w, b, A, MOM, gn):
    """Add one contact to one body's linearly implicit system in its standard velocities
    (v1, v2, v3, w1, w2, w3 about its reference point; the contact point at r from it):
    b += (F, r x F) - kp g_n,  A += coef g_n g_n^T (its upper triangle),  MOM += w (1, r, r r^T),
    g_n = (n, r x n).

    With the contact's tangent stiffness k, damping cd and friction secant iso (each body's
    scale c, see C_ROLLER): kp = c h k (n . v_point), coef = c (h^2 k + h cd - h iso),
    w = c h iso.  The friction part sum_c w G G^T = w (G G^T) over the contacts is built once a
    substep from the moments MOM (_moment_block); only the rank-one normal part is per contact.
    """
    # g_n in registers (a tuple), stored to gn for the caller: read back from gn after each
    # store to A, it cost a load per product (numba cannot tell the arrays apart)
    g = (n1, n2, n3, r2 * n3 - r3 * n2, r3 * n1 - r1 * n3, r1 * n2 - r2 * n1)
    for i in range(6):
        gn[i] = g[i]
    b[0] += F1 - kp * g[0]
    b[1] += F2 - kp * g[1]
    b[2] += F3 - kp * g[2]
    b[3] += r2 * F3 - r3 * F2 - kp * g[3]
    b[4] += r3 * F1 - r1 * F3 - kp * g[4]
    b[5] += r1 * F2 - r2 * F1 - kp * g[5]
    if coef != 0.0:   # upper triangle only: A is symmetric (_mirror completes it)
        for i in range(6):
            ci = coef * g[i]
            for l in range(i, 6):
                A[i, l] += ci * g[l]
    if w != 0.0:
        _add_moments(MOM, w, r1, r2, r3)


@inline
def _mirror(A):
    """Lower triangle of a symmetric 6 x 6 A from its upper (_contact adds only that)."""
    for i in range(1, 6):
        for l in range(i):
            A[i, l] = A[l, i]


@inline
def _add_moments(MOM, w, r1, r2, r3):
    """MOM += w (1, r, r r^T): the weight, first and (symmetric) second moments of r."""
    MOM[0] += w
    MOM[1] += w * r1
    MOM[2] += w * r2
    MOM[3] += w * r3
    MOM[4] += w * r1 * r1
    MOM[5] += w * r2 * r2
    MOM[6] += w * r3 * r3
    MOM[7] += w * r1 * r2
    MOM[8] += w * r1 * r3
    MOM[9] += w * r2 * r3


@njit
def _moment_block(A, MOM, d1, d2, d3):
    """A += sum_c w_c G(r_c) G(R_c)^T from the moments MOM of r (MOM = (s0, s1, s2) as in
    _contact) with R = r + d.  G(r) rows: e_i and e_i x r.  d = 0 for a body's own block; the
    coupling block of two needles has d = p_j - p_jn."""
    s0 = MOM[0]
    if s0 == 0.0:
        return
    a1, a2, a3 = MOM[1], MOM[2], MOM[3]
    # T-T
    A[0, 0] += s0
    A[1, 1] += s0
    A[2, 2] += s0
    # T(i)-R(l): -[s1 + s0 d]x ;  R(i)-T(l): [s1]x
    c1, c2, c3 = a1 + s0 * d1, a2 + s0 * d2, a3 + s0 * d3
    A[0, 4] += c3
    A[0, 5] += -c2
    A[1, 3] += -c3
    A[1, 5] += c1
    A[2, 3] += c2
    A[2, 4] += -c1
    A[3 + 0, 1] += -a3
    A[3 + 0, 2] += a2
    A[3 + 1, 0] += a3
    A[3 + 1, 2] += -a1
    A[3 + 2, 0] += -a2
    A[3 + 2, 1] += a1
    # R-R: (tr s2 + s1.d) I - (s2 + d s1^T)
    xx, yy, zz, xy, xz, yz = MOM[4], MOM[5], MOM[6], MOM[7], MOM[8], MOM[9]
    tr = xx + yy + zz + a1 * d1 + a2 * d2 + a3 * d3
    A[3, 3] += tr - xx - d1 * a1
    A[4, 4] += tr - yy - d2 * a2
    A[5, 5] += tr - zz - d3 * a3
    A[3, 4] += -xy - d1 * a2
    A[3, 5] += -xz - d1 * a3
    A[4, 3] += -xy - d2 * a1
    A[4, 5] += -yz - d2 * a3
    A[5, 3] += -xz - d3 * a1
    A[5, 4] += -yz - d3 * a2


@njit
def _friction(f, s1, s2, s3, n1, n2, n3, mu, vst, on):
    """tanh friction on the slip s projected on the tangent plane of normal n.
    Returns (friction force on the body whose slip is s [N], the implicit coefficient iso
    [N s/m], the same in every tangential direction)."""
    sn = s1 * n1 + s2 * n2 + s3 * n3
    t1, t2, t3 = s1 - sn * n1, s2 - sn * n2, s3 - sn * n3
    vt = math.sqrt(t1 * t1 + t2 * t2 + t3 * t3)
    if not on or mu <= 0.0 or f <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    g = _tanh(3.0 * vt / vst)
    if vt > 1e-12:
        iv = 1.0 / vt
        iso = mu * f * g * iv
        t1, t2, t3 = t1 * iv, t2 * iv, t3 * iv
    else:
        iso = mu * f * 3.0 / vst
        t1 = t2 = t3 = 0.0
    # implicit part: the secant mu f g / |v_t| in every tangential direction, not the tangent.
    # Saturated, the tangent along the slip is ~0 and the step would apply the full friction
    # impulse explicitly: h mu f r_n / I_3 is about 500 rad/s a substep on a needle's spin,
    # which flips the slip every step.  The secant (>= the tangent for tanh) cannot overshoot.
    return -mu * f * g * t1, -mu * f * g * t2, -mu * f * g * t3, iso


@njit
def _normal(f, kn, m, sn):
    """Normal force [N] with contact damping: elastic f plus cd times the approach rate -sn,
    cd = 2 sqrt(kn m) (critical for mass m on the contact's tangent stiffness), never pulling.
    Returns (force, cd); cd = 0 once the damping would pull (the contact then only lets go)."""
    cd = 2.0 * math.sqrt(kn * m)
    ft = f - cd * sn
    if ft < 0.0:
        return 0.0, 0.0
    return ft, cd


@inline
def _clear_needle(j, y0, NP, Y, g1, g2, g3, SP, FN, AN, UN, ND, MOM, PM):
    """Clear needle j's system; its inertial force of the moving frame (its origin accelerating
    at g [m/s^2]) and its sphere centres SP (spheres evenly along its axis)."""
    ns = int(NP[N_NS])
    ln = NP[N_LN]
    mn = NP[N_MN]
    q = y0 + N_F * j
    for i in range(6):
        FN[j, i] = 0.0
        for k in range(6):
            AN[j, i, k] = 0.0
            UN[j, i, k] = 0.0
    for i in range(10):
        MOM[j, i] = 0.0
        PM[j, i] = 0.0
    for i in range(D_LEN):
        ND[j, i] = 0.0
    FN[j, 0] = -mn * g1
    FN[j, 1] = -mn * g2
    FN[j, 2] = -mn * g3
    t1, t2 = Y[q + 3], Y[q + 4]
    inv = 1.0 / math.sqrt(1.0 + t1 * t1 + t2 * t2)
    d1, d2, d3 = t1 * inv, t2 * inv, inv
    for k in range(ns):
        sk = ((k + 0.5) / ns - 0.5) * ln
        SP[j, k, 0] = Y[q] + sk * d1
        SP[j, k, 1] = Y[q + 1] + sk * d2
        SP[j, k, 2] = Y[q + 2] + sk * d3


@inline
def _clear_roller(RS, MR):
    for i in range(6):
        for k in range(13):
            RS[i, k] = 0.0
    for i in range(10):
        MR[i] = 0.0


# The contact laws below take and return scalars only: they run for every touching sphere,
# and an array argument costs reference counting (it doubled the row's cost).  needle_forces
# adds what they return to the bodies' systems (_contact).

@inline
def _sphere_approach(Cs, delta):
    """Needle sphere on a race or a neighbour: Table 1's line-contact law per sphere,
    f = C_s delta^(10/9) [N], and its tangent stiffness [N/m]."""
    f = Cs * math.exp(E10_9 * math.log(delta))   # delta^(10/9); pow costs 1.4x
    return f, E10_9 * f / delta


@inline
def _point_velocity(v1, v2, v3, w1, w2, w3, r1, r2, r3):
    """Velocity [m/s] of the body point at arm r from a reference point moving at v, w."""
    return v1 + w2 * r3 - w3 * r2, v2 + w3 * r1 - w1 * r3, v3 + w1 * r2 - w2 * r1


@inline
def _trunnion_law(P1, P2, P3, rho, delta, p1, p2, p3, v1, v2, v3, w1, w2, w3, c, fric, om_tr,
                  dd_tr):
    """A needle sphere (centre P, approach delta; needle at p moving v, w) on the trunnion,
    convex cylinder about e3 turning at om_tr and sliding at dd_tr: Table 1 normal force with
    contact damping (_normal), tanh friction (_friction), Eq. (12) rolling resistance (half of
    mu_r P D/2 at each race).  Returns the force on the needle F [N], n, arm r [m], the
    _contact coefficients kp, coef, w, the load f [N] and the rolling moment and its tangent.
    c: the row's constants (needle_forces)."""
    rn, Cs, ms, mu, mur, vst, h, hk = c
    ir = 1.0 / rho
    n1, n2 = P1 * ir, P2 * ir                    # onto the needle
    f, kn = _sphere_approach(Cs, delta)
    X1, X2, X3 = P1 - rn * n1, P2 - rn * n2, P3
    r1, r2, r3 = X1 - p1, X2 - p2, X3 - p3
    u1, u2, u3 = _point_velocity(v1, v2, v3, w1, w2, w3, r1, r2, r3)
    s1 = u1 + om_tr * X2                         # minus the trunnion's
    s2 = u2 - om_tr * X1
    s3 = u3 - dd_tr
    F1, F2, F3, iso = _friction(f, s1, s2, s3, n1, n2, 0.0, mu, vst, fric)
    fd, cd = _normal(f, kn, ms, s1 * n1 + s2 * n2)
    gr = _tanh(3.0 * rn * (w3 - om_tr) / vst)
    mr = 0.5 * mur * f * rn * gr
    cr = h * 0.5 * mur * f * rn * 3.0 * rn / vst * (1.0 - gr * gr)
    return (F1 + fd * n1, F2 + fd * n2, F3, n1, n2, r1, r2, r3, hk * kn * (u1 * n1 + u2 * n2),
            h * h * kn + h * cd - h * iso, h * iso, f, mr, cr)


@inline
def _bore_gap(P1, P2, P3, o1, o2, o3, ob1, ob2, ob3, hw, Rb, rn):
    """Sphere centre P against the roller bore (concave cylinder about the axis ob through o,
    radius Rb, only within the roller's half width hw): its offset q from the bore axis, |q|
    and the approach delta [m] (-1 outside the width)."""
    e1_, e2_, e3_ = P1 - o1, P2 - o2, P3 - o3
    al = e1_ * ob1 + e2_ * ob2 + e3_ * ob3
    if not abs(al) <= hw:   # (written so that NaN skips, like every test here)
        return 0.0, 0.0, 0.0, 1.0, -1.0
    q1, q2, q3 = e1_ - al * ob1, e2_ - al * ob2, e3_ - al * ob3
    q = q1 * q1 + q2 * q2 + q3 * q3
    lim = Rb - rn
    if q < lim * lim * (1.0 - 1e-12):   # clear by far more than rounding: no square root
        return 0.0, 0.0, 0.0, 1.0, -1.0
    rb = math.sqrt(q)
    return q1, q2, q3, rb, rb + rn - Rb


@inline
def _bore_law(P1, P2, P3, q1, q2, q3, rb, delta, p1, p2, p3, v1, v2, v3, w1, w2, w3,
              o1, o2, o3, vo1, vo2, vo3, wr1, wr2, wr3, c, fric):
    """A needle sphere (centre P, offset q from the bore axis; needle at p moving v, w) in the
    roller bore (roller centre o moving vo, wr): the same laws as _trunnion_law on the
    relative slip.  Returns the force on the needle F [N], n, the needle's and the roller's
    arms r, R [m], the tangent stiffness kn [N/m], both points' normal speeds [m/s], the
    shared coef and the secant iso (each body scales them, see C_NEEDLE), f [N] and the
    rolling moment and its tangent."""
    rn, Cs, ms, mu, mur, vst, h, hk = c
    ir = -1.0 / rb
    n1, n2, n3 = q1 * ir, q2 * ir, q3 * ir       # onto the needle
    f, kn = _sphere_approach(Cs, delta)
    X1, X2, X3 = P1 - rn * n1, P2 - rn * n2, P3 - rn * n3
    r1, r2, r3 = X1 - p1, X2 - p2, X3 - p3
    u1, u2, u3 = _point_velocity(v1, v2, v3, w1, w2, w3, r1, r2, r3)
    R1, R2, R3 = X1 - o1, X2 - o2, X3 - o3
    z1, z2, z3 = _point_velocity(vo1, vo2, vo3, wr1, wr2, wr3, R1, R2, R3)   # roller point
    F1, F2, F3, iso = _friction(f, u1 - z1, u2 - z2, u3 - z3, n1, n2, n3, mu, vst, fric)
    fd, cd = _normal(f, kn, ms, (u1 - z1) * n1 + (u2 - z2) * n2 + (u3 - z3) * n3)
    gr = _tanh(3.0 * rn * (w3 - wr3) / vst)
    mr = 0.5 * mur * f * rn * gr
    cr = h * 0.5 * mur * f * rn * 3.0 * rn / vst * (1.0 - gr * gr)
    return (F1 + fd * n1, F2 + fd * n2, F3 + fd * n3, n1, n2, n3, r1, r2, r3, R1, R2, R3,
            kn, u1 * n1 + u2 * n2 + u3 * n3, z1 * n1 + z2 * n2 + z3 * n3,
            h * h * kn + h * cd - h * iso, iso, f, mr, cr)


@inline
def _neighbour_law(P1, P2, P3, Q1, Q2, Q3, dist, delta, p1, p2, p3, v1, v2, v3, w1, w2, w3,
                   pn1, pn2, pn3, vn1, vn2, vn3, wn1, wn2, wn3, c, fric):
    """A sphere P of one needle (at p moving v, w) on the same sphere of the next needle (at
    pn moving vn, wn; Q = its sphere centre - P): the same laws, each needle damped with half
    the sphere's mass.  Returns the force on the first F [N], n, both arms r, R [m], kp, coef,
    w and f [N]."""
    rn, Cs, ms, mu, mur, vst, h, hk = c
    ir = -1.0 / dist
    n1, n2, n3 = Q1 * ir, Q2 * ir, Q3 * ir       # onto the first needle
    f, kn = _sphere_approach(Cs, delta)
    X1, X2, X3 = P1 + 0.5 * Q1, P2 + 0.5 * Q2, P3 + 0.5 * Q3
    r1, r2, r3 = X1 - p1, X2 - p2, X3 - p3
    u1, u2, u3 = _point_velocity(v1, v2, v3, w1, w2, w3, r1, r2, r3)
    R1, R2, R3 = X1 - pn1, X2 - pn2, X3 - pn3
    z1, z2, z3 = _point_velocity(vn1, vn2, vn3, wn1, wn2, wn3, R1, R2, R3)
    F1, F2, F3, iso = _friction(f, u1 - z1, u2 - z2, u3 - z3, n1, n2, n3, mu, vst, fric)
    vrel = (u1 - z1) * n1 + (u2 - z2) * n2 + (u3 - z3) * n3
    fd, cd = _normal(f, kn, 0.5 * ms, vrel)
    return (F1 + fd * n1, F2 + fd * n2, F3 + fd * n3, n1, n2, n3, r1, r2, r3, R1, R2, R3,
            hk * kn * vrel, h * h * kn + h * cd - h * iso, h * iso, f)


@inline
def _axial_stop_law(p3, v3, d_tr, dd_tr, zax, Cs, mn, h, hk):
    """The trunnion's flange (inner end) and retainer (outer end): axial stops of a needle
    (centre height p3 [m], speed v3) at +-zax about the trunnion's material offset d_tr,
    Table 1 with damping, no friction.  Returns the force along e3 [N] with its implicit
    part, the tangent added to the needle's e3 row and the load f [N] (0 when clear)."""
    z = p3 - d_tr
    over = abs(z) - zax
    if not over > 0.0:
        return 0.0, 0.0, 0.0
    f, kn = _sphere_approach(Cs, over)
    sg = -1.0 if z > 0.0 else 1.0
    fd, cd = _normal(f, kn, mn, sg * (v3 - dd_tr))
    return sg * fd - hk * kn * (v3 - dd_tr), h * h * kn + h * cd, f


@inline
def _coupling_block(B, M, d1, d2, d3):
    """A friction coupling block of two bodies from the moments M of the first's arms:
    B -= sum w G(r) G(r + d)^T, d the first's reference point less the second's (M is spent)."""
    for i in range(10):
        M[i] = -M[i]
    _moment_block(B, M, d1, d2, d3)


@inline
def _friction_blocks(Y, y0, n, AN, MOM, UN, PM, AR6, MR):
    """The friction parts of the systems from their moments: each needle's own block, each
    neighbour pair's coupling block (UN -= sum w G_j G_jn^T) and the roller's block."""
    for j in range(n):
        _mirror(AN[j])
        _moment_block(AN[j], MOM[j], 0.0, 0.0, 0.0)
        if PM[j, 0] != 0.0:
            jn = j + 1 if j + 1 < n else 0
            q, qn = y0 + N_F * j, y0 + N_F * jn
            _coupling_block(UN[j], PM[j], Y[q] - Y[qn], Y[q + 1] - Y[qn + 1], Y[q + 2] - Y[qn + 2])
    _mirror(AR6)
    _moment_block(AR6, MR, 0.0, 0.0, 0.0)


@inline
def _roller_unknowns(RS, e1x, ax, FR, AR):
    """The roller's system in its standard velocities (b in RS[:, 0], A in RS[:, 1:7]) mapped
    to its unknowns of kernel.substep: ud = t3, om = r3, wd = t2, b1d = r1, b2d = r2,
    ed = e1x t1 + ax t3 (rows of the map TM in RS[:, 7:13]); FR = TM b, AR = TM A TM^T."""
    bR = RS[:, 0]
    AR6 = RS[:, 1:7]
    TM = RS[:, 7:13]
    TM[0, 2] = 1.0
    TM[1, 5] = 1.0
    TM[2, 1] = 1.0
    TM[3, 3] = 1.0
    TM[4, 4] = 1.0
    TM[5, 0] = e1x
    TM[5, 2] = ax
    for a in range(6):
        acc = 0.0
        for k in range(6):
            acc += TM[a, k] * bR[k]
        FR[a] = acc
        for c in range(6):
            acc = 0.0
            for k in range(6):
                tak = TM[a, k]
                if tak != 0.0:
                    for l in range(6):
                        acc += tak * AR6[k, l] * TM[c, l]
            AR[a, c] = acc


@inline
def _clear_coupling(n, BN, PB):
    for j in range(n):
        for i in range(10):
            PB[j, i] = 0.0
        for i in range(6):
            for l in range(6):
                BN[j, i, l] = 0.0


@inline
def _sub_outer(B, kq, gn, gn2):
    """B -= kq gn gn2^T: a contact's coupling of two bodies (rows: the one with generalized
    normal gn, columns: gn2's)."""
    a = (gn[0], gn[1], gn[2], gn[3], gn[4], gn[5])       # in registers (see _contact)
    c = (gn2[0], gn2[1], gn2[2], gn2[3], gn2[4], gn2[5])
    for i in range(6):
        for l in range(6):
            B[i, l] -= kq * a[i] * c[l]


@inline
def _couple(B, M, kq, w, cr, r1, r2, r3, gn, gn2):
    """A bore contact's coupling of the needle (rows) and the roller (columns): the normal
    part, the rolling resistance's tangent cr on the two spins, and its friction's moments
    (weight w, the needle's arm r) into M (_coupling_friction)."""
    _sub_outer(B, kq, gn, gn2)
    B[5, 5] -= cr
    _add_moments(M, w, r1, r2, r3)


@inline
def _pair_blocks(Aj, Ajn, U, Mj, Mjn, PMj, d1, d2, d3):
    """A touching pair's blocks from U = S = sum kq g g^T over its contacts (upper triangle,
    g = (n, r x n) in needle j's arms): needle jn's g is T g, T = [[I, 0], [D, I]], D v = d x v,
    d = p_j - p_jn, so Aj += S, Ajn += T S T^T, U <- -S T^T (the coupling, as -sum kq g g_n^T),
    Mj += PMj and Mjn += PMj shifted by d (the friction moments in jn's arms, R = r + d).
    Once a pair instead of once a contact: a pair has up to N_s contacts."""
    _mirror(U)
    for i in range(6):
        for l in range(i, 6):
            Aj[i, l] += U[i, l]
    for i in range(6):   # X = S T^T: columns 3..5 += d x (columns 0..2)
        s0, s1, s2 = U[i, 0], U[i, 1], U[i, 2]
        U[i, 3] += d2 * s2 - d3 * s1
        U[i, 4] += d3 * s0 - d1 * s2
        U[i, 5] += d1 * s1 - d2 * s0
    for l in range(6):   # Ajn += T X (upper): rows 3..5 += d x (rows 0..2)
        x0, x1, x2 = U[0, l], U[1, l], U[2, l]
        Ajn[0, l] += x0
        if l >= 1:
            Ajn[1, l] += x1
        if l >= 2:
            Ajn[2, l] += x2
        if l >= 3:
            Ajn[3, l] += U[3, l] + d2 * x2 - d3 * x1
        if l >= 4:
            Ajn[4, l] += U[4, l] + d3 * x0 - d1 * x2
        if l >= 5:
            Ajn[5, l] += U[5, l] + d1 * x1 - d2 * x0
    for i in range(6):
        for l in range(6):
            U[i, l] = -U[i, l]
    s0, a1, a2, a3 = PMj[0], PMj[1], PMj[2], PMj[3]
    for i in range(10):
        Mj[i] += PMj[i]
    Mjn[0] += s0
    Mjn[1] += a1 + s0 * d1
    Mjn[2] += a2 + s0 * d2
    Mjn[3] += a3 + s0 * d3
    Mjn[4] += PMj[4] + 2.0 * a1 * d1 + s0 * d1 * d1
    Mjn[5] += PMj[5] + 2.0 * a2 * d2 + s0 * d2 * d2
    Mjn[6] += PMj[6] + 2.0 * a3 * d3 + s0 * d3 * d3
    Mjn[7] += PMj[7] + a1 * d2 + d1 * a2 + s0 * d1 * d2
    Mjn[8] += PMj[8] + a1 * d3 + d1 * a3 + s0 * d1 * d3
    Mjn[9] += PMj[9] + a2 * d3 + d2 * a3 + s0 * d2 * d3


@inline
def _bore_diagnostics(NDj, f, F1, F2, F3):
    """A bore contact's load f [N] and its force F on the needle, as on the roller [N]."""
    NDj[D_BORE] += f
    NDj[D_R1] -= F1
    NDj[D_R2] -= F2
    NDj[D_R3] -= F3


@inline
def _axial_stop(Fj, Aj, NDj, p3, v3, d_tr, dd_tr, zax, Cs, mn, h, hk):
    """A needle on its flange or retainer (_axial_stop_law) into its system and ND."""
    fz, kz, f = _axial_stop_law(p3, v3, d_tr, dd_tr, zax, Cs, mn, h, hk)
    if f > 0.0:
        Fj[2] += fz
        Aj[2, 2] += kz
        NDj[D_FLANGE] += f


@njit
def _coupling_friction(Y, y0, n, BN, PB, o1, o2, o3):
    """The friction's coupling blocks, BN[j] -= sum w G(r) G(R)^T from the moments PB[j]
    (the roller's arm R = r + p_j - o, o its centre)."""
    for j in range(n):
        if PB[j, 0] != 0.0:
            q = y0 + N_F * j
            _coupling_block(BN[j], PB[j], Y[q] - o1, Y[q + 1] - o2, Y[q + 2] - o3)


@njit
def needle_forces(Y, y0, NP, vst, h, hk, cpl, o1, o2, o3, vo1, vo2, vo3, ob1, ob2, ob3,
                  wr1, wr2, wr3, e1x, ax, d_tr, dd_tr, om_tr, g1, g2, g3,
                  SP, FN, AN, UN, FR, AR, ND, MOM, PM, RS, MR, gn, gn2, BN, PB):
    """Evaluate every needle contact once; fill each needle's system (FN, AN), the needles'
    coupling blocks UN (needle j to j+1) and the roller's system (FR, AR, in the roller's
    unknowns of kernel.substep) for a linearly implicit step of h [s] (h = 0: forces only), and
    ND diagnostics.  Arguments: see the module's docstring."""
    n = int(NP[N_N])
    _clear_roller(RS, MR)
    for j in range(n):
        _clear_needle(j, y0, NP, Y, g1, g2, g3, SP, FN, AN, UN, ND, MOM, PM)
    if cpl:
        _clear_coupling(n, BN, PB)
    _contacts(Y, y0, NP, vst, h, hk, cpl,
              (o1, o2, o3, vo1, vo2, vo3, ob1, ob2, ob3, wr1, wr2, wr3, d_tr, dd_tr, om_tr),
              (SP, FN, AN, UN, ND, MOM, PM, BN, PB), RS, MR, gn, gn2)
    _finish_systems(Y, y0, n, cpl, e1x, ax, o1, o2, o3, AN, MOM, UN, PM, RS, MR, FR, AR, BN,
                    PB)


@inline
def _finish_systems(Y, y0, n, cpl, e1x, ax, o1, o2, o3, AN, MOM, UN, PM, RS, MR, FR, AR, BN,
                    PB):
    """After every contact: the friction blocks from their moments, the roller's system in its
    unknowns and, with cpl, the friction's roller-needle coupling blocks."""
    _friction_blocks(Y, y0, n, AN, MOM, UN, PM, RS[:, 1:7], MR)
    _roller_unknowns(RS, e1x, ax, FR, AR)
    if cpl:
        _coupling_friction(Y, y0, n, BN, PB, o1, o2, o3)


@njit
def _contacts(Y, y0, NP, vst, h, hk, cpl, pose, arrays, RS, MR, gn, gn2):
    """Every needle's contacts (trunnion, bore, next needle jn, axial stops) into the needles'
    systems, UN[j], BN[j], PB[j] and the roller's (RS: b, A in columns 0, 1..6; MR).  pose:
    needle_forces' scalars o .. om_tr; arrays = (SP, FN, AN, UN, ND, MOM, PM, BN, PB) (tuples:
    needle_forces' systems are cleared and finished around this loop)."""
    (o1, o2, o3, vo1, vo2, vo3, ob1, ob2, ob3, wr1, wr2, wr3, d_tr, dd_tr, om_tr) = pose
    SP, FN, AN, UN, ND, MOM, PM, BN, PB = arrays
    bR, AR6 = RS[:, 0], RS[:, 1:7]
    n, ns = int(NP[N_N]), int(NP[N_NS])
    rn, Rt, Rb, hw, dc, zax = NP[N_RN], NP[N_RT], NP[N_RBR], NP[N_HW], NP[N_DC], NP[N_ZAX]
    Cs, mn, mu, mur, fric = NP[N_CS], NP[N_MN], NP[N_MU], NP[N_MUR], NP[N_FRIC] > 0.5
    ms = mn / ns   # the share of a needle's mass on one sphere: sets the contact damping
    rollr = NP[N_ROLLR] > 0.5 and mur > 0.0
    c = (rn, Cs, ms, mu, mur, vst, h, hk)   # one tuple argument: numba inlines calls of < 30
    cn = 1.0 if cpl else C_NEEDLE   # one system (cpl): no split, so no scaled tangents
    cr_ = 1.0 if cpl else C_ROLLER
    rt = Rt + rn   # square roots only within these bounds (1e-12 wider, beyond rounding)
    rt2, dc2 = rt * rt * (1.0 + 1e-12), dc * dc * (1.0 + 1e-12)
    for j in range(n):
        q = y0 + N_F * j
        p1, p2, p3, v1, v2, v3 = Y[q], Y[q + 1], Y[q + 2], Y[q + 5], Y[q + 6], Y[q + 7]
        w1, w2, w3 = Y[q + 8], Y[q + 9], Y[q + 10]
        jn = j + 1 if j + 1 < n else 0
        qn = y0 + N_F * jn
        Aj, Fj, Mj = AN[j], FN[j], MOM[j]
        pair = False   # j touches jn: UN[j] holds S = sum kq g g^T until _pair_blocks
        for k in range(ns):
            P1, P2, P3 = SP[j, k, 0], SP[j, k, 1], SP[j, k, 2]
            rho2 = P1 * P1 + P2 * P2
            rho = math.sqrt(rho2) if rho2 < rt2 else rt
            delta = rt - rho                                  # trunnion
            if delta > 0.0:
                F1, F2, F3, n1, n2, r1, r2, r3, kp, kq, wi, f, mr, cr = _trunnion_law(
                    P1, P2, P3, rho, delta, p1, p2, p3, v1, v2, v3, w1, w2, w3, c, fric, om_tr,
                    dd_tr)
                _contact(F1, F2, F3, n1, n2, 0.0, r1, r2, r3, kp, kq, wi, Fj, Aj, Mj, gn)
                if rollr:
                    Fj[5] -= mr
                    Aj[5, 5] += cr
                ND[j, D_TRUN] += f
            q1, q2, q3, rb, delta = _bore_gap(P1, P2, P3, o1, o2, o3, ob1, ob2, ob3, hw, Rb, rn)
            if delta > 0.0:                                   # roller bore
                (F1, F2, F3, n1, n2, n3, r1, r2, r3, R1, R2, R3, kn, un, zn, kq, iso, f, mr,
                 cr) = _bore_law(P1, P2, P3, q1, q2, q3, rb, delta, p1, p2, p3, v1, v2, v3, w1,
                                 w2, w3, o1, o2, o3, vo1, vo2, vo3, wr1, wr2, wr3, c, fric)
                _contact(F1, F2, F3, n1, n2, n3, r1, r2, r3, cn * hk * kn * un,
                         cn * kq, cn * h * iso, Fj, Aj, Mj, gn)
                _contact(-F1, -F2, -F3, n1, n2, n3, R1, R2, R3, cr_ * hk * kn * zn,
                         cr_ * kq, cr_ * h * iso, bR, AR6, MR, gn2)
                if rollr:
                    Fj[5] -= mr
                    Aj[5, 5] += cn * cr
                    bR[5] += mr
                    AR6[5, 5] += cr_ * cr
                if cpl:
                    _couple(BN[j], PB[j], kq, h * iso, cr if rollr else 0.0, r1, r2, r3, gn, gn2)
                _bore_diagnostics(ND[j], f, F1, F2, F3)
            Q1, Q2, Q3 = SP[jn, k, 0] - P1, SP[jn, k, 1] - P2, SP[jn, k, 2] - P3
            dist2 = Q1 * Q1 + Q2 * Q2 + Q3 * Q3
            dist = math.sqrt(dist2) if dist2 < dc2 else dc
            delta = dc - dist                                 # the next needle's sphere k
            if delta > 0.0 and jn != j:
                (F1, F2, F3, n1, n2, n3, r1, r2, r3, R1, R2, R3, kp, kq, wi,
                 f) = _neighbour_law(P1, P2, P3, Q1, Q2, Q3, dist, delta, p1, p2, p3, v1, v2,
                                     v3, w1, w2, w3, Y[qn], Y[qn + 1], Y[qn + 2], Y[qn + 5],
                                     Y[qn + 6], Y[qn + 7], Y[qn + 8], Y[qn + 9], Y[qn + 10],
                                     c, fric)
                # both needles' loads now (jn's: no block, no moments); their blocks once for
                # the pair from S = sum kq g g^T, gathered in UN[j] (_pair_blocks)
                _contact(F1, F2, F3, n1, n2, n3, r1, r2, r3, kp, kq, 0.0, Fj, UN[j], Mj, gn)
                _contact(-F1, -F2, -F3, n1, n2, n3, R1, R2, R3, -kp, 0.0, 0.0, FN[jn], AN[jn],
                         MOM[jn], gn2)
                _add_moments(PM[j], wi, r1, r2, r3)
                ND[j, D_NEIGH] += f
                ND[jn, D_NEIGH] += f
                pair = True
        if pair:
            _pair_blocks(Aj, AN[jn], UN[j], Mj, MOM[jn], PM[j], p1 - Y[qn], p2 - Y[qn + 1],
                         p3 - Y[qn + 2])
        _axial_stop(Fj, Aj, ND[j], p3, v3, d_tr, dd_tr, zax, Cs, mn, h, hk)


@njit
def _solve6(A, B, nc):
    """A X = B for a 6 x 6 A and nc columns of B, in place (B <- X); partial pivoting."""
    for k in range(6):
        piv = k
        for i in range(k + 1, 6):
            if abs(A[i, k]) > abs(A[piv, k]):
                piv = i
        if piv != k:
            for j in range(6):
                A[k, j], A[piv, j] = A[piv, j], A[k, j]
            for j in range(nc):
                B[k, j], B[piv, j] = B[piv, j], B[k, j]
        inv = 1.0 / A[k, k]
        for i in range(k + 1, 6):
            f = A[i, k] * inv
            if f != 0.0:
                for j in range(k + 1, 6):
                    A[i, j] -= f * A[k, j]
                for j in range(nc):
                    B[i, j] -= f * B[k, j]
    for k in range(5, -1, -1):
        inv = 1.0 / A[k, k]
        for j in range(nc):
            acc = B[k, j]
            for i in range(k + 1, 6):
                acc -= A[k, i] * B[i, j]
            B[k, j] = acc * inv


@njit
def _touching(U):
    """Whether a coupling block holds anything (the two needles touch or rub)."""
    for i in range(6):
        for l in range(6):
            if U[i, l] != 0.0:
                return True
    return False


@njit
def ring_solve(AN, UN, FN, h, n, CW, XW, S, T):
    """Solve the needles' coupled implicit system in place: block j has diagonal AN[j] (mass
    included), coupling UN[j] to block j+1 (mod n, the ring closes) and UN[j-1]^T to block
    j-1, right-hand side h FN[j]; the velocity increments replace FN.  CW (n x 6 x 6),
    XW (n x 6 x 7), S (6 x 6), T (6 x 13) are work arrays (ring_solve_m with one column)."""
    for j in range(n):
        for i in range(6):
            FN[j, i] *= h
    ring_solve_m(AN, UN, FN.reshape((n, 6, 1)), 1, n, CW, XW, S, T)


@njit
def needle_update(Y, y0, NP, h, FN, AN, UN, CW, XW, S, T):
    """Linearly implicit step of every needle's velocities and positions from needle_forces'
    system: (M + h D + h^2 K) dv = h (F - h K v) over the whole ring (ring_solve); positions
    move with the new velocities (tilts: t1' = w2, t2' = -w1)."""
    n = int(NP[N_N])
    mn, I1, I3 = NP[N_MN], NP[N_I1], NP[N_I3]
    for j in range(n):
        AN[j, 0, 0] += mn
        AN[j, 1, 1] += mn
        AN[j, 2, 2] += mn
        AN[j, 3, 3] += I1
        AN[j, 4, 4] += I1
        AN[j, 5, 5] += I3
    ring_solve(AN, UN, FN, h, n, CW, XW, S, T)
    for j in range(n):
        q = y0 + N_F * j
        for i in range(6):
            Y[q + 5 + i] += FN[j, i]
        Y[q] += h * Y[q + 5]
        Y[q + 1] += h * Y[q + 6]
        Y[q + 2] += h * Y[q + 7]
        Y[q + 3] += h * Y[q + 9]
        Y[q + 4] -= h * Y[q + 8]


@njit
def ring_solve_m(AN, UN, RHS, nr, n, CW, XW, S, T):
    """The ring's system (ring_solve) for nr right-hand sides at once (RHS[j, :, c],
    n x 6 x nr, replaced by the solutions): one elimination for all of them.

    Where two neighbours do not touch the ring is open: then a chain from the needle after that
    gap (_chain_solve_m).  A closed ring (every needle touching the next): block tridiagonal
    elimination bordered by the block that closes it (_closed_ring_solve_m).
    CW (n x 6 x 6), XW (n x 6 x (nr + 6)), S (6 x 6), T (6 x (nr + 12)) are work arrays.
    """
    for k in range(n):
        if not _touching(UN[k]):
            _chain_solve_m(AN, UN, RHS, nr, n, (k + 1) % n, CW, XW, S, T)
            return
    _closed_ring_solve_m(AN, UN, RHS, nr, n, CW, XW, S, T)


@njit
def _chain_solve_m(AN, UN, RHS, nr, n, j0, CW, XW, S, T):
    """The ring opened before needle j0 (UN[j0 - 1] = 0): block tridiagonal elimination along
    j0, j0 + 1, ... (mod n); a gap further on leaves its coupling column out (C_j = 0).  T's
    columns 0..nr-1 the right-hand sides, nr..nr+5 the coupling to the next needle.  About
    600 multiply-adds a touching needle and right-hand side, 150 a free one."""
    prev = -1   # the previous needle of the chain when it touches this one
    for m in range(n):
        j = (j0 + m) % n
        for i in range(6):
            for l in range(6):
                S[i, l] = AN[j, i, l]
            for c in range(nr):
                T[i, c] = RHS[j, i, c]
        if prev >= 0:   # subtract L C_prev and L X_prev, L = UN[prev]^T
            for i in range(6):
                for q in range(6):
                    lim = UN[prev, q, i]
                    if lim != 0.0:
                        for l in range(6):
                            S[i, l] -= lim * CW[prev, q, l]
                        for c in range(nr):
                            T[i, c] -= lim * XW[prev, q, c]
        nxt = m < n - 1 and _touching(UN[j])
        if nxt:
            for i in range(6):
                for l in range(6):
                    T[i, nr + l] = UN[j, i, l]
            _solve6(S, T, nr + 6)
        else:
            _solve6(S, T, nr)
        for i in range(6):
            for l in range(6):
                CW[j, i, l] = T[i, nr + l] if nxt else 0.0
            for c in range(nr):
                XW[j, i, c] = T[i, c]
        prev = j if nxt else -1
    # back substitution: x_j = X_j - C_j x_next (C_j = 0 at a gap, and after the chain's end)
    for m in range(n - 1, -1, -1):
        j = (j0 + m) % n
        jn = (j + 1) % n
        for c in range(nr):
            for i in range(6):
                acc = XW[j, i, c]
                if m < n - 1:
                    for l in range(6):
                        acc -= CW[j, i, l] * RHS[jn, l, c]
                RHS[j, i, c] = acc


@njit
def _closed_ring_solve_m(AN, UN, RHS, nr, n, CW, XW, S, T):
    """Every needle touches the next: block tridiagonal elimination on blocks 0..n-2 bordered
    by block n-1 (which closes the ring): x_j = y_j - Z_j x_{n-1}, then the border's 6 x 6
    system.  T's columns 0..5 the coupling C_k, 6..5+nr the right-hand sides, 6+nr..11+nr the
    border; XW[k] holds the right-hand sides' and the border's columns (nr + 6)."""
    M = n - 1
    nb = nr + 6
    for k in range(M):
        for i in range(6):
            for l in range(6):
                S[i, l] = AN[k, i, l]
            for l in range(6 + nb):
                T[i, l] = 0.0
            if k < M - 1:
                for l in range(6):
                    T[i, l] = UN[k, i, l]
            for c in range(nr):
                T[i, 6 + c] = RHS[k, i, c]
            if k == 0:                       # A[0][n-1] = UN[n-1]^T
                for l in range(6):
                    T[i, 6 + nr + l] += UN[n - 1, l, i]
            if k == M - 1:                   # A[n-2][n-1] = UN[n-2]
                for l in range(6):
                    T[i, 6 + nr + l] += UN[M - 1, i, l]
        if k > 0:   # subtract L_k C_{k-1} and L_k X_{k-1}, L_k = UN[k-1]^T
            for i in range(6):
                for m in range(6):
                    lim = UN[k - 1, m, i]
                    if lim != 0.0:
                        for l in range(6):
                            S[i, l] -= lim * CW[k - 1, m, l]
                        for l in range(nb):
                            T[i, 6 + l] -= lim * XW[k - 1, m, l]
        _solve6(S, T, 6 + nb)
        for i in range(6):
            for l in range(6):
                CW[k, i, l] = T[i, l]
            for l in range(nb):
                XW[k, i, l] = T[i, 6 + l]
    for k in range(M - 2, -1, -1):
        for i in range(6):
            for l in range(nb):
                acc = 0.0
                for m in range(6):
                    acc += CW[k, i, m] * XW[k + 1, m, l]
                XW[k, i, l] -= acc
    # border block n-1: A[n-1][0] = UN[n-1], A[n-1][n-2] = UN[n-2]^T
    for i in range(6):
        for l in range(6):
            S[i, l] = AN[n - 1, i, l]
        for c in range(nr):
            T[i, c] = RHS[n - 1, i, c]
        for m in range(6):
            a0 = UN[n - 1, i, m]
            a1 = UN[M - 1, m, i]
            for l in range(6):
                S[i, l] -= a0 * XW[0, m, nr + l] + a1 * XW[M - 1, m, nr + l]
            for c in range(nr):
                T[i, c] -= a0 * XW[0, m, c] + a1 * XW[M - 1, m, c]
    _solve6(S, T, nr)
    for i in range(6):
        for c in range(nr):
            RHS[n - 1, i, c] = T[i, c]
    for j in range(M):
        for i in range(6):
            for c in range(nr):
                acc = XW[j, i, c]
                for m in range(6):
                    acc -= XW[j, i, nr + m] * T[m, c]
                RHS[j, i, c] = acc


# The one-system step's ring solve (kernel.coupled_solve): the ring's matrix is symmetric
# positive definite (masses plus h^2 K + h D + the friction secant's G G^T, all symmetric
# positive semi-definite), so an open ring factors as a block Cholesky L L^T along the chain:
# the roller's Schur complement then needs only the forward sweep (Z = L^-1 B', U = Z^T Z)
# and one back substitution, half the work of eliminating seven columns both ways.

@inline
def _chol6(S, L):
    """Cholesky factor of the symmetric 6 x 6 S (its lower triangle read) into L's lower
    triangle, the diagonal holding the reciprocals 1 / L_kk.  False if S is not positive
    definite (a non-positive or NaN pivot)."""
    for k in range(6):
        for i in range(k, 6):
            acc = S[i, k]
            for p in range(k):
                acc -= L[i, p] * L[k, p]
            if i == k:
                if not acc > 0.0:
                    return False
                L[k, k] = 1.0 / math.sqrt(acc)
            else:
                L[i, k] = acc * L[k, k]
    return True


@inline
def _forward6(L, X, c0, nc):
    """X[:, c0:c0 + nc] <- L^-1 X[:, c0:c0 + nc] (L from _chol6)."""
    for c in range(c0, c0 + nc):
        for k in range(6):
            acc = X[k, c]
            for p in range(k):
                acc -= L[k, p] * X[p, c]
            X[k, c] = acc * L[k, k]


@inline
def _backward6(L, x):
    """x <- L^-T x (one column; L from _chol6)."""
    for k in range(5, -1, -1):
        acc = x[k]
        for p in range(k + 1, 6):
            acc -= L[p, k] * x[p]
        x[k] = acc * L[k, k]


@njit
def chain_forward(AN, UN, RH, ZF, n, j0, LW, CW):
    """Forward sweep of the open ring's block Cholesky, chain j0, j0 + 1, ... (mod n; the
    ring open before j0, UN[j0 - 1] = 0; a further gap leaves its coupling out): LW[j] the
    diagonal block's factor, CW[j] = L_j^-1 UN[j] (W_j, when j touches the next), RH[j, :, 0]
    <- the forward-solved right-hand side, RH[j, :, 1:7] <- Z_j = (L^-1 B')_j where needle j
    carries a coupling column (ZF[j] > 0 on entry: its own; on return: its own or filled in
    along the chain; elsewhere Z_j = 0 and left as is).  False if a block is not positive
    definite (LW, CW, RH and ZF then partly written: coupled_solve sets RH, ZF again)."""
    prev = -1
    for m in range(n):
        j = (j0 + m) % n
        L = LW[j]
        S = CW[j]    # scratch for the Schur-updated block until W_j is written over it
        for i in range(6):
            for l in range(i + 1):
                S[i, l] = AN[j, i, l]
        if prev >= 0:   # S -= W_prev^T W_prev, rhs -= W_prev^T Y_prev
            W = CW[prev]
            if ZF[prev] > 0.0:
                ZF[j] = 1.0
            nc = 7 if ZF[j] > 0.0 else 1
            for i in range(6):
                for l in range(i + 1):
                    acc = 0.0
                    for q in range(6):
                        acc += W[q, i] * W[q, l]
                    S[i, l] -= acc
                for c in range(nc):
                    acc = 0.0
                    if c == 0 or ZF[prev] > 0.0:
                        for q in range(6):
                            acc += W[q, i] * RH[prev, q, c]
                    RH[j, i, c] -= acc
        if not _chol6(S, L):
            return False
        _forward6(L, RH[j], 0, 7 if ZF[j] > 0.0 else 1)
        nxt = m < n - 1 and _touching(UN[j])
        if nxt:
            for i in range(6):
                for l in range(6):
                    S[i, l] = UN[j, i, l]
            _forward6(L, S, 0, 6)
        prev = j if nxt else -1
    return True


@njit
def chain_backward(RH, ZF, y, UN, n, j0, LW, CW, X):
    """Back substitution of the open ring after chain_forward: x_j = L_j^-T (Y_j - Z_j y -
    W_j x_next) along the chain backwards (y: the roller's solution), into X (n x 6)."""
    for m in range(n - 1, -1, -1):
        j = (j0 + m) % n
        xj = X[j]
        for i in range(6):
            acc = RH[j, i, 0]
            if ZF[j] > 0.0:
                for c in range(6):
                    acc -= RH[j, i, 1 + c] * y[c]
            xj[i] = acc
        if m < n - 1 and _touching(UN[j]):
            jn = (j + 1) % n
            W = CW[j]
            for i in range(6):
                acc = 0.0
                for l in range(6):
                    acc += W[i, l] * X[jn, l]
                xj[i] -= acc
        _backward6(LW[j], xj)
