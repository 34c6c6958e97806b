"""Contact laws of the needle-resolved bearing (needles.py assembles them): the needle's line
contact as spheres (Eq. 17), its normal force with contact damping, tanh friction, and the laws
of a needle on the trunnion, on the roller's bore, on its neighbour and on the axial stops,
each with the tangent an implicit step needs.
"""
import math

from .contact import tanh_clipped
from .jit import inline, njit


E10_9 = 10.0 / 9.0
C_ROLLER = 1.25   # implicit tangent factors of a roller-needle contact (eps = 0.25, contact_tangent)
C_NEEDLE = 5.0


@inline
def contact_tangent(F, nrm, r, kp, coef, w, b, A, MOM, gn):
    """Add one contact (force F, normal nrm, each (x, y, z)) to one body's linearly implicit
    system in its standard velocities (v1, v2, v3, w1, w2, w3 about its reference point; the
    contact point at r from it):
    b += (F, r x F) - kp g_n,  A += coef g_n g_n^T (its upper triangle),  MOM += w (1, r, r r^T),
    g_n = (n, r x n).

    With the contact's tangent stiffness k, damping cd and friction secant iso (each body's
    scale c, see C_ROLLER): kp = c h k (n . v_point), coef = c (h^2 k + h cd - h iso),
    w = c h iso.  The friction part sum_c w G G^T = w (G G^T) over the contacts is built once a
    substep from the moments MOM (moment_block); only the rank-one normal part is per contact.
    """
    F1, F2, F3 = F
    n1, n2, n3 = nrm
    r1, r2, r3 = r
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
    if coef != 0.0:   # upper triangle only: A is symmetric (mirror completes it)
        for i in range(6):
            ci = coef * g[i]
            for l in range(i, 6):
                A[i, l] += ci * g[l]
    if w != 0.0:
        add_moments(MOM, w, r1, r2, r3)


@inline
def mirror(A):
    """Lower triangle of a symmetric 6 x 6 A from its upper (contact_tangent adds only that)."""
    for i in range(1, 6):
        for l in range(i):
            A[i, l] = A[l, i]


@inline
def add_moments(MOM, w, r1, r2, r3):
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
def moment_block(A, MOM, d1, d2, d3):
    """A += sum_c w_c G(r_c) G(R_c)^T from the moments MOM of r (MOM = (s0, s1, s2) as in
    contact_tangent) with R = r + d.  G(r) rows: e_i and e_i x r.  d = 0 for a body's own block; the
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
def needle_friction(f, s1, s2, s3, n1, n2, n3, mu, vst, on):
    """tanh friction on the slip s projected on the tangent plane of normal n.
    Returns (friction force on the body whose slip is s [N], the implicit coefficient iso
    [N s/m], the same in every tangential direction)."""
    sn = s1 * n1 + s2 * n2 + s3 * n3
    t1, t2, t3 = s1 - sn * n1, s2 - sn * n2, s3 - sn * n3
    vt = math.sqrt(t1 * t1 + t2 * t2 + t3 * t3)
    if not on or mu <= 0.0 or f <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    g = tanh_clipped(3.0 * vt / vst)
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
def needle_normal(f, kn, m, sn):
    """Normal force [N] with contact damping: elastic f plus cd times the approach rate -sn,
    cd = 2 sqrt(kn m) (critical for mass m on the contact's tangent stiffness), never pulling.
    Returns (force, cd); cd = 0 once the damping would pull (the contact then only lets go)."""
    cd = 2.0 * math.sqrt(kn * m)
    ft = f - cd * sn
    if ft < 0.0:
        return 0.0, 0.0
    return ft, cd


@inline
def sphere_approach(Cs, delta):
    """Needle sphere on a race or a neighbour: Table 1's line-contact law per sphere,
    f = C_s delta^(10/9) [N], and its tangent stiffness [N/m]."""
    f = Cs * math.exp(E10_9 * math.log(delta))   # delta^(10/9); pow costs 1.4x
    return f, E10_9 * f / delta


@inline
def point_velocity(v1, v2, v3, w1, w2, w3, r1, r2, r3):
    """Velocity [m/s] of the body point at arm r from a reference point moving at v, w."""
    return v1 + w2 * r3 - w3 * r2, v2 + w3 * r1 - w1 * r3, v3 + w1 * r2 - w2 * r1


@inline
def trunnion_law(S, rho, delta, body, c, fric, om_tr, dd_tr):
    """A needle sphere (centre S = P, approach delta; the needle body = (p, v, w) flat: at p
    moving v, w) on the trunnion, convex cylinder about e3 turning at om_tr and sliding at dd_tr: Table 1 normal force with
    contact damping (needle_normal), tanh friction (needle_friction), Eq. (12) rolling resistance (mu_r P D/2 at
    each race: the paper's mu_r = F/P is the force F that rolls a needle between two plates, so
    its two contacts resist with F D in all).  Returns the force on the needle F [N], n, arm r [m], the
    contact_tangent coefficients kp, coef, w, the load f [N] and the rolling moment and its tangent.
    c: the row's constants (needle_forces)."""
    rn, Cs, ms, mu, mur, vst, h, hk = c
    P1, P2, P3 = S
    p1, p2, p3, v1, v2, v3, w1, w2, w3 = body
    ir = 1.0 / rho
    n1, n2 = P1 * ir, P2 * ir                    # onto the needle
    f, kn = sphere_approach(Cs, delta)
    X1, X2, X3 = P1 - rn * n1, P2 - rn * n2, P3
    r1, r2, r3 = X1 - p1, X2 - p2, X3 - p3
    u1, u2, u3 = point_velocity(v1, v2, v3, w1, w2, w3, r1, r2, r3)
    s1 = u1 + om_tr * X2                         # minus the trunnion's
    s2 = u2 - om_tr * X1
    s3 = u3 - dd_tr
    F1, F2, F3, iso = needle_friction(f, s1, s2, s3, n1, n2, 0.0, mu, vst, fric)
    fd, cd = needle_normal(f, kn, ms, s1 * n1 + s2 * n2)
    gr = tanh_clipped(3.0 * rn * (w3 - om_tr) / vst)
    mr = mur * f * rn * gr
    cr = h * mur * f * rn * 3.0 * rn / vst * (1.0 - gr * gr)
    return (F1 + fd * n1, F2 + fd * n2, F3, n1, n2, r1, r2, r3, hk * kn * (u1 * n1 + u2 * n2),
            h * h * kn + h * cd - h * iso, h * iso, f, mr, cr)


@inline
def bore_gap(P1, P2, P3, o1, o2, o3, ob1, ob2, ob3, hw, Rb, rn):
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
def bore_law(S, q, rb, delta, body, roller, c, fric):
    """A needle sphere (centre S = P, offset q from the bore axis; the needle body = (p, v, w)
    flat) in the roller bore (roller = (o, vo, wr) flat: its centre o moving vo, wr): the same
    laws as trunnion_law on the relative slip.  Returns the force on the needle F [N], n, the needle's and the roller's
    arms r, R [m], the tangent stiffness kn [N/m], both points' normal speeds [m/s], the
    shared coef and the secant iso (each body scales them, see C_NEEDLE), f [N] and the
    rolling moment and its tangent."""
    rn, Cs, ms, mu, mur, vst, h, hk = c
    P1, P2, P3 = S
    q1, q2, q3 = q
    p1, p2, p3, v1, v2, v3, w1, w2, w3 = body
    o1, o2, o3, vo1, vo2, vo3, wr1, wr2, wr3 = roller
    ir = -1.0 / rb
    n1, n2, n3 = q1 * ir, q2 * ir, q3 * ir       # onto the needle
    f, kn = sphere_approach(Cs, delta)
    X1, X2, X3 = P1 - rn * n1, P2 - rn * n2, P3 - rn * n3
    r1, r2, r3 = X1 - p1, X2 - p2, X3 - p3
    u1, u2, u3 = point_velocity(v1, v2, v3, w1, w2, w3, r1, r2, r3)
    R1, R2, R3 = X1 - o1, X2 - o2, X3 - o3
    z1, z2, z3 = point_velocity(vo1, vo2, vo3, wr1, wr2, wr3, R1, R2, R3)   # roller point
    F1, F2, F3, iso = needle_friction(f, u1 - z1, u2 - z2, u3 - z3, n1, n2, n3, mu, vst, fric)
    fd, cd = needle_normal(f, kn, ms, (u1 - z1) * n1 + (u2 - z2) * n2 + (u3 - z3) * n3)
    gr = tanh_clipped(3.0 * rn * (w3 - wr3) / vst)
    mr = mur * f * rn * gr
    cr = h * mur * f * rn * 3.0 * rn / vst * (1.0 - gr * gr)
    return (F1 + fd * n1, F2 + fd * n2, F3 + fd * n3, n1, n2, n3, r1, r2, r3, R1, R2, R3,
            kn, u1 * n1 + u2 * n2 + u3 * n3, z1 * n1 + z2 * n2 + z3 * n3,
            h * h * kn + h * cd - h * iso, iso, f, mr, cr)


@inline
def neighbour_law(S, Q, dist, delta, body, other, c, fric):
    """A sphere S = P of one needle (body = (p, v, w) flat) on the same sphere of the next
    needle (other = (pn, vn, wn) flat; Q = its sphere centre - P): the same laws, each needle
    damped with half the sphere's mass.  Returns the force on the first F [N], n, both arms r, R [m], kp, coef,
    w and f [N]."""
    rn, Cs, ms, mu, mur, vst, h, hk = c
    P1, P2, P3 = S
    Q1, Q2, Q3 = Q
    p1, p2, p3, v1, v2, v3, w1, w2, w3 = body
    pn1, pn2, pn3, vn1, vn2, vn3, wn1, wn2, wn3 = other
    ir = -1.0 / dist
    n1, n2, n3 = Q1 * ir, Q2 * ir, Q3 * ir       # onto the first needle
    f, kn = sphere_approach(Cs, delta)
    X1, X2, X3 = P1 + 0.5 * Q1, P2 + 0.5 * Q2, P3 + 0.5 * Q3
    r1, r2, r3 = X1 - p1, X2 - p2, X3 - p3
    u1, u2, u3 = point_velocity(v1, v2, v3, w1, w2, w3, r1, r2, r3)
    R1, R2, R3 = X1 - pn1, X2 - pn2, X3 - pn3
    z1, z2, z3 = point_velocity(vn1, vn2, vn3, wn1, wn2, wn3, R1, R2, R3)
    F1, F2, F3, iso = needle_friction(f, u1 - z1, u2 - z2, u3 - z3, n1, n2, n3, mu, vst, fric)
    vrel = (u1 - z1) * n1 + (u2 - z2) * n2 + (u3 - z3) * n3
    fd, cd = needle_normal(f, kn, 0.5 * ms, vrel)
    return (F1 + fd * n1, F2 + fd * n2, F3 + fd * n3, n1, n2, n3, r1, r2, r3, R1, R2, R3,
            hk * kn * vrel, h * h * kn + h * cd - h * iso, h * iso, f)


@inline
def axial_stop_law(p3, v3, d_tr, dd_tr, zax, Cs, mn, h, hk):
    """The trunnion's flange (inner end) and retainer (outer end): axial stops of a needle
    (centre height p3 [m], speed v3) at +-zax about the trunnion's material offset d_tr,
    Table 1 with damping, no friction.  Returns the force along e3 [N] with its implicit
    part, the tangent added to the needle's e3 row and the load f [N] (0 when clear)."""
    z = p3 - d_tr
    over = abs(z) - zax
    if not over > 0.0:
        return 0.0, 0.0, 0.0
    f, kn = sphere_approach(Cs, over)
    sg = -1.0 if z > 0.0 else 1.0
    fd, cd = needle_normal(f, kn, mn, sg * (v3 - dd_tr))
    return sg * fd - hk * kn * (v3 - dd_tr), h * h * kn + h * cd, f
