"""Hot kernel of the one-roller contact model: driving motions, roller-groove contact, bearing,
and the substep integrator.  Scalar math only so that numba compiles it (see jit.py).

Frame (model.md): groove fixed, groove axis = z axis through the origin, x = pressing
direction, y = trunnion axis (nominal).  Forces are reported from the roller on the groove.
"""
import math


from .jit import inline, njit
from .linalg import solve_small
from . import needles as NDL

from .layout import (  # noqa: F401  (re-exported: K.P_S etc.)
    P_S, P_R, P_RG, P_M, P_IS, P_K, P_A1, P_MU, P_VST, P_PITCH, P_YAW, P_ROLL, P_AXIAL,
    P_TRAV, P_FRIC, P_SPIN, P_BEAR, P_MUN, P_MUR, P_FRICN, P_ROLLR, P_KN, P_RB, P_QSUM,
    P_CLR, P_INTEG, P_KWR, P_LT, P_IT, P_TOL, P_HMAX, P_VP, P_HC, P_ZROW, P_DF, P_LEN,
    Y_X, Y_U, Y_UD, Y_OM, Y_E, Y_ED, Y_W, Y_WD, Y_B1, Y_B1D, Y_B2, Y_B2D, Y_PL, Y_LEN, NV,
    O_FX, O_FY, O_FZ, O_CY, O_CZ, O_SLIP, O_SPIN, O_FN, O_X, O_PL, O_LEN, L_LEN,
    W_R, W_A, W_D, W_RT, W_AT, W_M, W_A0, W_S)

from . import oppoint


def _compile_oppoint():
    """numba versions of oppoint's functions in place of the plain ones, so that derive calls
    compiled callees; the model's Python then calls them too (numba is loaded anyway)."""
    for name in oppoint.FUNCTIONS:
        f = getattr(oppoint, name)
        if not hasattr(f, "py_func"):
            setattr(oppoint, name, njit(f))


_compile_oppoint()
derive_op = oppoint.derive   # the operating point at OP's inputs (oppoint.derive)

HX = 2e-4   # whirl-angle step for finite-difference derivatives of the driving motions [rad]


@njit
def trunnion_line(x, theta, s, pitch, roll):
    """Trunnion axis at whirl angle x: point Q on it at the groove's mid-plane and direction a.

    Pitching about x through the spider centre, Eq. (1): the axis meets the plane y = 0 at
    z = s tan(phi) (Eq. 18).  Rolling, Eq. (5), turns the axis about -z through that point
    (sense chosen so that the slip on the loaded +x flank is V = v1 + v2, model.md).
    Returns (Qz, ax, ay, az); Q = (x0, 0, Qz) with x0 the pressing offset.
    """
    T = math.tan(theta)
    phi = math.atan(T * math.sin(x)) if pitch else 0.0
    xi = 0.0
    if roll:
        k = (1.0 - math.cos(theta)) / (2.0 * math.cos(theta))   # e / s
        xi = math.asin(k * math.sin(2.0 * x))
    cp = math.cos(phi)
    return s * math.tan(phi), math.sin(xi) * cp, math.cos(xi) * cp, math.sin(phi)


@njit
def trunnion_axial(x, theta, s, axial):
    """Axial displacement of the trunnion along its axis d [m], Eq. (7)."""
    if not axial:
        return 0.0
    c = math.cos(theta)
    e = s * (1.0 - c) / (2.0 * c)
    xi = math.asin(e * math.sin(2.0 * x) / s)
    return s - (e * math.cos(2.0 * x) + s * math.cos(xi))


@njit
def trunnion_yaw(x, theta, yaw):
    """Yawing angle psi [rad], Eq. (3): turns the trunnion about its own axis."""
    return math.atan(math.tan(theta) * math.cos(x)) if yaw else 0.0


@njit
def line_kinematics(x, w, theta, P, out):
    """Q, a and their first and second time derivatives at whirl angle x, whirl rate w.

    out[0:3] a, [3:6] da/dt, [6:9] d2a/dt2, [9] Qz, [10] dQz/dt (with the plunge speed
    P[P_VP]: the spider's travel along the groove), [11] d2Qz/dt2,
    [12] trunnion material velocity along its axis (dd/dt), [13] trunnion spin rate about a,
    [14:18] the (x, w, theta, plunge speed) they were computed for (a one-entry cache; NaN =
    empty).  Central differences in x (step HX), chain rule with constant w within a substep.
    """
    vp = P[P_VP]
    if out[14] == x and out[15] == w and out[16] == theta and out[17] == vp:
        return   # same whirl angle as the last call (the extrapolated step visits x + h twice)
    out[14] = x
    out[15] = w
    out[16] = theta
    out[17] = vp
    s = P[P_S]
    pitch = P[P_PITCH] > 0.5
    roll = P[P_ROLL] > 0.5
    q0, a0x, a0y, a0z = trunnion_line(x, theta, s, pitch, roll)
    qp, apx, apy, apz = trunnion_line(x + HX, theta, s, pitch, roll)
    qm, amx, amy, amz = trunnion_line(x - HX, theta, s, pitch, roll)
    i1 = w / (2.0 * HX)
    i2 = w * w / (HX * HX)
    out[0] = a0x
    out[1] = a0y
    out[2] = a0z
    out[3] = (apx - amx) * i1
    out[4] = (apy - amy) * i1
    out[5] = (apz - amz) * i1
    out[6] = (apx - 2.0 * a0x + amx) * i2
    out[7] = (apy - 2.0 * a0y + amy) * i2
    out[8] = (apz - 2.0 * a0z + amz) * i2
    out[9] = q0
    out[10] = (qp - qm) * i1
    if vp != 0.0:
        out[10] += vp
    out[11] = (qp - 2.0 * q0 + qm) * i2
    if P[P_BEAR] > 0.5:   # the trunnion's own slide and spin matter only to the needles
        ax = P[P_AXIAL] > 0.5
        out[12] = (trunnion_axial(x + HX, theta, s, ax) - trunnion_axial(x - HX, theta, s, ax)) * i1
        yw = P[P_YAW] > 0.5
        out[13] = (trunnion_yaw(x + HX, theta, yw) - trunnion_yaw(x - HX, theta, yw)) * i1
    else:
        out[12] = 0.0
        out[13] = 0.0


@inline
def hertz_normal_force(K, delta):
    """Roller-groove normal force [N] at the approach delta [m]: Eq. (10) with Table 1's point
    contact, f_n = K delta^(3/2) (K [N/m^1.5] from hertz.hertz_point)."""
    return K * delta ** 1.5


@inline
def tanh_friction(mu, fn, vt, vst):
    """Regularised friction, Eq. (11) with model.md's law mu(v) = mu tanh(3 v / v_st): returns
    g = tanh(3 |v_t| / v_st) (the friction force is mu f_n g [N]) and its slope
    d(mu f_n g)/d|v_t| [N s/m] at the slip |v_t| [m/s], normal force f_n [N]."""
    g = math.tanh(3.0 * vt / vst)
    return g, mu * fn * 3.0 / vst * (1.0 - g * g)


@inline
def spin_moment(mu, fn, a1, wn, vst):
    """Spin moment [N m] of the elliptical contact about its normal, Eqs. (14)-(16): the
    contact's semi-major axis a = a1 f_n^(1/3) (Eq. 15) and 3/8 mu f_n a, regularised in the
    spin rate wn [rad/s] like the sliding friction."""
    a = a1 * fn ** (1.0 / 3.0)
    return 0.375 * mu * math.tanh(3.0 * wn * a / vst) * fn * a


@njit
def groove_contact(cx, cy, cz, vx, vy, vz, wx, wy, wz, P, res):
    """Roller (sphere) in groove (concave cylinder along z): Hertz normal force, tanh friction
    on the full 3-D slip at the contact point, spin moment Eq. (16).

    c: roller centre [m], v: its velocity [m/s], w: roller angular velocity [rad/s].
    res (on the roller): [0:3] force [N], [3:6] moment about c [N m], [6:9] normal n,
    [9] f_n [N], [10:13] tangential slip v_t [m/s], [13] |v_t|, [14] g = tanh(3|v_t|/v_st),
    [15] friction slope d(mu f_n g)/d|v_t| [N s/m], [16:19] contact point [m].
    """
    r = P[P_R]
    rho = math.sqrt(cx * cx + cy * cy)
    nx = cx / rho
    ny = cy / rho
    delta = rho + r - P[P_RG]                 # penetration, model.md
    for i in range(19):
        res[i] = 0.0
    res[6] = nx
    res[7] = ny
    res[16] = cx + r * nx
    res[17] = cy + r * ny
    res[18] = cz
    if delta <= 0.0:
        return
    fn = hertz_normal_force(P[P_K], delta)
    if P[P_HC] > 0.0:     # Hunt-Crossley: f_n (1 + 3/2 alpha d delta/dt), never pulling
        fn = max(0.0, fn * (1.0 + 1.5 * P[P_HC] * (vx * nx + vy * ny)))
    # velocity of the roller material at the contact point p = c + r n
    px = vx + (wy * 0.0 - wz * r * ny)
    py = vy + (wz * r * nx - wx * 0.0)
    pz = vz + (wx * r * ny - wy * r * nx)
    pn = px * nx + py * ny
    tx = px - pn * nx
    ty = py - pn * ny
    tz = pz
    vt = math.sqrt(tx * tx + ty * ty + tz * tz)
    mu = P[P_MU]
    vst = P[P_VST]
    fx = -fn * nx
    fy = -fn * ny
    fz = 0.0
    mx = 0.0
    my = 0.0
    mz = 0.0
    g = 0.0
    slope = 0.0
    if P[P_FRIC] > 0.5 and mu > 0.0:
        g, slope = tanh_friction(mu, fn, vt, vst)
        if vt > 0.0:
            ft = mu * fn * g / vt             # Eq. (11): |f_t| = mu(v) f_n, opposing the slip
            fx -= ft * tx
            fy -= ft * ty
            fz -= ft * tz
            # moment of the friction about the centre: (r n) x f_t
            mx += r * ny * (-ft * tz)
            my += -r * nx * (-ft * tz)
            mz += r * nx * (-ft * ty) - r * ny * (-ft * tx)
    if P[P_SPIN] > 0.5 and mu > 0.0:
        ms = spin_moment(mu, fn, P[P_A1], wx * nx + wy * ny, vst)   # spin against the groove
        mx -= ms * nx
        my -= ms * ny
    res[0] = fx
    res[1] = fy
    res[2] = fz
    res[3] = mx
    res[4] = my
    res[5] = mz
    res[9] = fn
    res[10] = tx
    res[11] = ty
    res[12] = tz
    res[13] = vt
    res[14] = g
    res[15] = slope


@njit
def roller_motion(Y, x0, L, lumped):
    """Roller centre c [m], its velocity v [m/s] and angular velocity w [rad/s] from the state
    and the trunnion line L, plus the row axes e1 (pressing direction normal to the trunnion
    axis) and e2 = a x e1 (zero with the ideal bearing, whose extra freedoms are locked).

    c = Q + u a + e x_hat + w_o e2; w = a x da/dt + om a + b1' e1 + b2' e2.
    """
    ax, ay, az = L[0], L[1], L[2]
    adx, ady, adz = L[3], L[4], L[5]
    e1x = e1y = e1z = e2x = e2y = e2z = 0.0
    if lumped:
        e1x, e1y, e1z = 1.0 - ax * ax, -ax * ay, -ax * az
        ne = math.sqrt(e1x * e1x + e1y * e1y + e1z * e1z)
        e1x, e1y, e1z = e1x / ne, e1y / ne, e1z / ne
        e2x, e2y, e2z = ay * e1z - az * e1y, az * e1x - ax * e1z, ax * e1y - ay * e1x
    u, ud, om = Y[Y_U], Y[Y_UD], Y[Y_OM]
    wo, wod, b1d, b2d = Y[Y_W], Y[Y_WD], Y[Y_B1D], Y[Y_B2D]
    cx = x0 + u * ax + Y[Y_E] + wo * e2x
    cy = u * ay + wo * e2y
    cz = L[9] + u * az + wo * e2z
    vx = ud * ax + u * adx + Y[Y_ED] + wod * e2x
    vy = ud * ay + u * ady + wod * e2y
    vz = L[10] + ud * az + u * adz + wod * e2z
    wx = ay * adz - az * ady + om * ax + b1d * e1x + b2d * e2x
    wy = az * adx - ax * adz + om * ay + b1d * e1y + b2d * e2y
    wz = ax * ady - ay * adx + om * az + b1d * e1z + b2d * e2z
    return cx, cy, cz, vx, vy, vz, wx, wy, wz, e1x, e1y, e1z, e2x, e2y, e2z


@njit
def tilt_drag(It, L, e1x, e1y, e1z, e2x, e2y, e2z):
    """Moments [N m] about e1, e2 with which the trunnion's angular acceleration a x a''
    drags the tilting roller (inertia It about a diameter) along."""
    ax, ay, az = L[0], L[1], L[2]
    alx = ay * L[8] - az * L[7]
    aly = az * L[6] - ax * L[8]
    alz = ax * L[7] - ay * L[6]
    return It * (alx * e1x + aly * e1y + alz * e1z), It * (alx * e2x + aly * e2y + alz * e2z)


@njit
def row_load(P, e):
    """Lumped needle row: the row's radial force on the roller F_r [N] along x and its tangent
    stiffness [N/m] at the roller's radial offset e [m].  Eq. (17) summed over the loaded
    needles: |F_r| = K_row g^(10/9), g the radial approach beyond the row's clearance; it
    pushes the roller back onto the trunnion axis (+x in drive, e < 0; -x in coast)."""
    g = abs(e) - P[P_CLR]
    if g <= 0.0:
        return 0.0, 0.0
    Fr = P[P_KN] * g ** (10.0 / 9.0)
    return (Fr if e < 0.0 else -Fr), 10.0 / 9.0 * Fr / g


@njit
def resolved_forces(Y, P, NW, theta, x, h, L, e1x, e1y, e1z, e2x, e2y, e2z, hk, cpl):
    """Needle-resolved bearing: the roller's pose and velocity and the trunnion's motion in the
    trunnion frame T, then every needle contact (needles.needle_forces) for a step of h [s]:
    split (each body's system on its own, scaled tangents) or, with cpl, one system with the
    roller-needle coupling blocks.  hk: the h of the stiffness's K v term (h, or 0 for a step
    linearized at a predicted state, bdf2_substep)."""
    NP, SP, FN, AN, FR, AR, ND = NW[0], NW[1], NW[2], NW[3], NW[4], NW[5], NW[6]
    MOM, gn, PM, RS, UN, MR, gn2 = NW[7], NW[8], NW[9], NW[10], NW[11], NW[12], NW[13]
    ax, az = L[0], L[2]
    E, W, u = Y[Y_E], Y[Y_W], Y[Y_U]
    Ed, Wd, ud = Y[Y_ED], Y[Y_WD], Y[Y_UD]
    # roller centre: u a + E x_hat + W e2 from Q; x_hat = e1x e1 + ax a in T
    o1, o2, o3 = E * e1x, W, u + E * ax
    vo1, vo2, vo3 = Ed * e1x, Wd, ud + Ed * ax
    b1, b2 = Y[Y_B1], Y[Y_B2]
    ib = 1.0 / math.sqrt(1.0 + b1 * b1 + b2 * b2)
    d_tr = trunnion_axial(x, theta, P[P_S], P[P_AXIAL] > 0.5)
    g = L[11]   # the frame origin Q accelerates along the groove (z) only
    NDL.needle_forces(Y, Y_LEN, NP, P[P_VST], h, hk, cpl, o1, o2, o3, vo1, vo2, vo3,
                      b2 * ib, -b1 * ib, ib, Y[Y_B1D], Y[Y_B2D], Y[Y_OM], e1x, ax,
                      d_tr, L[12], L[13], g * e1z, g * e2z, g * az,
                      SP, FN, AN, UN, FR, AR, ND, MOM, PM, RS, MR, gn, gn2, NW[18], NW[19])


@inline
def slip_sensitivities(r, L, res, e1x, e1y, e1z, e2x, e2y, e2z, sixdof, resolved, G, b):
    """Rows of G: the contact slip's sensitivity d v_t / d v_i to each velocity unknown
    (ud, om[, wd, b1d, b2d][, ed]); b: the groove's force and moment on the roller projected
    on them (generalized forces [N, N m])."""
    ax, ay, az = L[0], L[1], L[2]
    fx, fy, fz = res[0], res[1], res[2]
    mx, my, mz = res[3], res[4], res[5]
    nx, ny = res[6], res[7]
    rnx, rny = r * nx, r * ny
    an = ax * nx + ay * ny
    G[0, 0], G[0, 1], G[0, 2] = ax - an * nx, ay - an * ny, az          # ud: P_t a
    G[1, 0], G[1, 1], G[1, 2] = -az * rny, az * rnx, ax * rny - ay * rnx  # om: a x r n
    b[0] = fx * ax + fy * ay + fz * az
    b[1] = mx * ax + my * ay + mz * az
    if sixdof:
        e2n = e2x * nx + e2y * ny
        G[2, 0], G[2, 1], G[2, 2] = e2x - e2n * nx, e2y - e2n * ny, e2z      # wd: P_t e2
        G[3, 0], G[3, 1], G[3, 2] = -e1z * rny, e1z * rnx, e1x * rny - e1y * rnx  # b1d
        G[4, 0], G[4, 1], G[4, 2] = -e2z * rny, e2z * rnx, e2x * rny - e2y * rnx  # b2d
        b[2] = fx * e2x + fy * e2y + fz * e2z
        b[3] = mx * e1x + my * e1y + mz * e1z
        b[4] = mx * e2x + my * e2y + mz * e2z
    if resolved:
        G[5, 0], G[5, 1], G[5, 2] = 1.0 - nx * nx, -nx * ny, 0.0             # ed: P_t x_hat
        b[5] = fx


@inline
def friction_jacobian(P, h, res, G, nv, A):
    """A = -h J, J the Jacobian of the groove friction (Eq. 11, tanh law) in the unknowns:
    J = -G (slope t t^T + iso (I - t t^T)) G^T with t = v_t/|v_t|, slope the tangent and
    iso = mu f_n g/|v_t| the secant [N s/m]; zero for the explicit integrator 2."""
    vt = res[13]
    fn = res[9]
    if vt > 1e-12:
        iso = P[P_MU] * fn * res[14] / vt
        tx, ty, tz = res[10] / vt, res[11] / vt, res[12] / vt
    else:
        iso = res[15]
        tx, ty, tz = 0.0, 0.0, 0.0
    aniso = res[15] - iso
    if P[P_INTEG] == 2.0:
        iso = 0.0      # explicit (symplectic) Euler, for comparison: no friction Jacobian
        aniso = 0.0
    for i in range(nv):
        gi_t = G[i, 0] * tx + G[i, 1] * ty + G[i, 2] * tz
        for j in range(nv):
            gj_t = G[j, 0] * tx + G[j, 1] * ty + G[j, 2] * tz
            gg = G[i, 0] * G[j, 0] + G[i, 1] * G[j, 1] + G[i, 2] * G[j, 2]
            A[i, j] = h * (iso * gg + aniso * gi_t * gj_t)      # -h J


@inline
def groove_stiffness_x(P, res, cx, cy):
    """Tangent stiffness [N/m] of the groove's Hertz contact along x: d f_n / d delta (Eq. 10,
    n = 3/2) times n_x^2."""
    delta = math.sqrt(cx * cx + cy * cy) + P[P_R] - P[P_RG]
    if delta > 0.0:
        return 1.5 * res[9] / delta * res[6] * res[6]
    return 0.0


@inline
def row_damping(P, k, mass):
    """Damping [N s/m, N m s] of a mode of stiffness k [N/m, N m] and mass [kg, kg m^2] on the
    lumped row: 2 zeta sqrt(k mass), zeta = row_damping (the lumped form of the resolved row's
    needle-contact damping, docs/model.md)."""
    return 2.0 * P[P_ZROW] * math.sqrt(k * mass)


@inline
def lumped_row_terms(Y, P, L, h, It, drag1, drag2, A, b):
    """Lumped needle row (section 2.4.2) in the implicit step: needle sliding friction on the
    slide, Eq. (12) rolling resistance on the spin, the row's stiffness across the load and in
    tilt, implicit like the friction.  Returns the row's radial load F_r [N] and stiffness
    [N/m] (row_load)."""
    m = P[P_M]
    ud, om = Y[Y_UD], Y[Y_OM]
    Fr, kr = row_load(P, Y[Y_E])
    q = P[P_QSUM] * abs(Fr)       # sum of the needle loads (> F_r: they fan out)
    if P[P_FRICN] > 0.5 and q > 0.0:
        # axial sliding of the roller on the needles, mu_needle, tanh law
        gn = math.tanh(3.0 * (ud - L[12]) / P[P_VST])
        b[0] -= P[P_MUN] * q * gn
        if P[P_INTEG] != 2.0:
            A[0, 0] += h * P[P_MUN] * q * 3.0 / P[P_VST] * (1.0 - gn * gn)
    if P[P_ROLLR] > 0.5 and q > 0.0:
        # Eq. (12): rolling force mu_r P per needle, acting on the bore (radius r_bore)
        # against the roller's spin relative to the trunnion
        vr = (om - L[13]) * P[P_RB]
        grl = math.tanh(3.0 * vr / P[P_VST])
        b[1] -= P[P_MUR] * q * P[P_RB] * grl
        if P[P_INTEG] != 2.0:
            A[1, 1] += h * P[P_MUR] * q * P[P_RB] ** 2 * 3.0 / P[P_VST] * (1.0 - grl * grl)
    # tangent stiffness of the row: across the load (w) and in tilt (line contacts of
    # length l: radial stiffness times l^2/12)
    kw = kr * P[P_KWR]
    kt2 = kr * P[P_LT]
    kt1 = kt2 * P[P_KWR]
    cw, c1, c2 = row_damping(P, kw, m), row_damping(P, kt1, It), row_damping(P, kt2, It)
    b[2] -= kw * (Y[Y_W] + h * Y[Y_WD]) + cw * Y[Y_WD]
    b[3] -= kt1 * (Y[Y_B1] + h * Y[Y_B1D]) + drag1 + c1 * Y[Y_B1D]
    b[4] -= kt2 * (Y[Y_B2] + h * Y[Y_B2D]) + drag2 + c2 * Y[Y_B2D]
    A[2, 2] += m + h * h * kw + h * cw
    A[3, 3] += It + h * h * kt1 + h * c1
    A[4, 4] += It + h * h * kt2 + h * c2
    return Fr, kr


@inline
def resolved_row_terms(Y, P, NW, theta, x, h, L, e1x, e1y, e1z, e2x, e2y, e2z, It, kh,
                       drag1, drag2, A, b, hk, cpl):
    """Needle-resolved bearing in the implicit step: the roller's own inertia and the groove's
    radial stiffness, then every needle contact on the roller with its tangent, evaluated at
    the start of the substep (needles and roller step on the same state); hk, cpl as in
    resolved_forces."""
    m = P[P_M]
    b[3] -= drag1
    b[4] -= drag2
    b[5] -= hk * kh * Y[Y_ED]
    A[2, 2] += m
    A[3, 3] += It
    A[4, 4] += It
    A[5, 5] += m + h * h * kh
    # NW is None for the other bearings: numba then prunes this branch at compile time, so
    # their kernels never compile the needle code (a 15 s first compile)
    if NW is not None:
        resolved_forces(Y, P, NW, theta, x, h, L, e1x, e1y, e1z, e2x, e2y, e2z, hk, cpl)
        FR, AR = NW[4], NW[5]
        for i in range(6):
            b[i] += FR[i]
            for j in range(6):
                A[i, j] += AR[i, j]


@inline
def hold_slide(A, b, nv):
    """Traverse off: the slide along the trunnion axis is held (ud drops out of the system)."""
    for j in range(nv):
        A[0, j] = 0.0
        A[j, 0] = 0.0
    A[0, 0] = 1.0
    b[0] = 0.0


@inline
def advance_roller(Y, dv, h, trav, sixdof, resolved, NW):
    """Velocities by the solved increments dv, then positions with the new velocities
    (semi-implicit); the needles of the resolved bearing by their own ring solve."""
    if trav:
        Y[Y_UD] = Y[Y_UD] + dv[0]
        Y[Y_U] = Y[Y_U] + h * Y[Y_UD]
    Y[Y_OM] = Y[Y_OM] + dv[1]
    if sixdof:
        Y[Y_WD] = Y[Y_WD] + dv[2]
        Y[Y_W] = Y[Y_W] + h * Y[Y_WD]
        Y[Y_B1D] = Y[Y_B1D] + dv[3]
        Y[Y_B1] = Y[Y_B1] + h * Y[Y_B1D]
        Y[Y_B2D] = Y[Y_B2D] + dv[4]
        Y[Y_B2] = Y[Y_B2] + h * Y[Y_B2D]
    if resolved:
        Y[Y_ED] = Y[Y_ED] + dv[5]
        Y[Y_E] = Y[Y_E] + h * Y[Y_ED]
        if NW is not None:
            NDL.needle_update(Y, Y_LEN, NW[0], h, NW[2], NW[3], NW[11], NW[14], NW[15],
                              NW[16], NW[17])


@inline
def lumped_radial_step(Y, h, m, Fe, ktot, c):
    """Lumped bearing, radial along the pressing direction: the groove pushes the roller in -x,
    the needles push it back (net force Fe [N], stiffness ktot [N/m], the row's damping c
    [N s/m]).  Linearly implicit in both, so the stiff radial mode (about 2e4 Hz) is stable at
    any substep."""
    ed = Y[Y_ED]
    ded = h * (Fe - h * ktot * ed - c * ed) / (m + h * h * ktot + h * c)
    Y[Y_ED] = ed + ded
    Y[Y_E] = Y[Y_E] + h * Y[Y_ED]


@inline
def _roller_system(Y, P, theta, w, x0, x, h, L, res, G, A, b, sixdof, resolved, nv):
    """The roller's own part of a linearly implicit step of h [s] ending at whirl angle x
    [rad]: the groove contact on the state Y, its friction Jacobian in the nv unknowns, the
    masses, the driving acceleration along the axis.  Returns the contact centre's x, y [m]
    and the row axes e1, e2."""
    line_kinematics(x, w, theta, P, L)
    (cx, cy, cz, vx, vy, vz, wx, wy, wz,
     e1x, e1y, e1z, e2x, e2y, e2z) = roller_motion(Y, x0, L, sixdof)
    groove_contact(cx, cy, cz, vx, vy, vz, wx, wy, wz, P, res)
    slip_sensitivities(P[P_R], L, res, e1x, e1y, e1z, e2x, e2y, e2z, sixdof, resolved, G, b)
    friction_jacobian(P, h, res, G, nv, A)
    m = P[P_M]
    A[0, 0] += m
    A[1, 1] += P[P_IS]
    # driving accelerations seen along the axis: c'' . a = Q''.a + u'' + u a''.a
    b[0] -= m * (L[11] * L[2] + Y[Y_U] * (L[6] * L[0] + L[7] * L[1] + L[8] * L[2]))
    return cx, cy, e1x, e1y, e1z, e2x, e2y, e2z


@njit
def substep(Y, P, theta, w, F_press, x0, h, L, res, G, A, b, NW):
    """One linearly implicit Euler substep of h [s] on the state Y (in place).

    Velocities v = (ud, om[, wd, b1d, b2d][, ed]): (M - h J + h^2 K) dv = h (Q - h K v), with J
    the friction Jacobian (the friction slope mu f_n / v_st against the roller's mass and
    inertia is the stiff part) and K the needle row's stiffness; positions then move with the
    new velocities; the driving motion is taken at the end of the substep (backward in the
    driving terms, so the rolling target is not lagged by a whole substep).
    G (NV x 3), A (NV x NV), b (NV) are work arrays.
    """
    m = P[P_M]
    lumped = P[P_BEAR] == 1.0
    resolved = P[P_BEAR] == 2.0
    sixdof = lumped or resolved
    x = Y[Y_X] + h * w
    Y[Y_X] = x
    nv = 6 if resolved else 5 if lumped else 2
    cx, cy, e1x, e1y, e1z, e2x, e2y, e2z = _roller_system(Y, P, theta, w, x0, x, h, L, res, G,
                                                           A, b, sixdof, resolved, nv)
    It = P[P_IT]
    drag1 = drag2 = kh = Fr = kr = 0.0
    if sixdof:
        drag1, drag2 = tilt_drag(It, L, e1x, e1y, e1z, e2x, e2y, e2z)
        kh = groove_stiffness_x(P, res, cx, cy)
    if lumped:
        Fr, kr = lumped_row_terms(Y, P, L, h, It, drag1, drag2, A, b)
    if resolved:
        resolved_row_terms(Y, P, NW, theta, x, h, L, e1x, e1y, e1z, e2x, e2y, e2z, It, kh,
                           drag1, drag2, A, b, h, False)
    trav = P[P_TRAV] > 0.5
    if not trav:
        hold_slide(A, b, nv)
    for i in range(nv):
        b[i] *= h
    solve_small(A, b, nv)
    advance_roller(Y, b, h, trav, sixdof, resolved, NW)
    if lumped:
        lumped_radial_step(Y, h, m, res[0] + Fr, kh + kr, row_damping(P, kh + kr, m))


@njit
def extrapolated_step(Y, Y1, P, theta, w, F_press, x0, h, L, res, G, A, b, NW):
    """One substep of h [s] extrapolated (Richardson) from one linearly implicit Euler step of
    h (in Y1, work) and two of h/2: second order, L-stable (integrator 1)."""
    ny = Y.shape[0]
    for i in range(ny):
        Y1[i] = Y[i]
    substep(Y1, P, theta, w, F_press, x0, h, L, res, G, A, b, NW)
    substep(Y, P, theta, w, F_press, x0, 0.5 * h, L, res, G, A, b, NW)
    substep(Y, P, theta, w, F_press, x0, 0.5 * h, L, res, G, A, b, NW)
    for i in range(ny):
        Y[i] = 2.0 * Y[i] - Y1[i]


@njit
def step_error(Y, Y1, P):
    """Scaled error estimate of one extrapolated step: the difference between the two half
    steps (Y) and the whole step (Y1) in the roller's velocities, against tol x v_st (slides)
    and tol x v_st / r (turns): what sets the friction's direction and so the thrust."""
    vs = P[P_TOL] * P[P_VST]
    vr = vs / P[P_R]
    e = abs(Y[Y_OM] - Y1[Y_OM]) / vr
    if P[P_TRAV] > 0.5:
        e = max(e, abs(Y[Y_UD] - Y1[Y_UD]) / vs)
    if P[P_BEAR] > 0.5:
        e = max(e, abs(Y[Y_WD] - Y1[Y_WD]) / vs, abs(Y[Y_ED] - Y1[Y_ED]) / vs,
                abs(Y[Y_B1D] - Y1[Y_B1D]) / vr, abs(Y[Y_B2D] - Y1[Y_B2D]) / vr)
    return e


# generalized-alpha step (integrator 4, ideal and lumped bearing): Chung & Hulbert (1993)
RHO_GA = 0.8   # spectral radius at infinity; 1 (no numerical damping) lets the stick mode
               # ring: order 3 off by 40-200 % at 25-100 us, while 0.6-0.9 all stay below
               # 0.02 % at 25-50 us (paper's scene, ideal bearing)
GA_NTOL = 1e-3   # Newton stops at velocity increments below GA_NTOL x v_st (1e-2: same order 3)
GA_MAXIT = 12


def _ga_coefficients(rho):
    """(alpha_m, alpha_f, gamma, beta) from the spectral radius at infinity rho (Chung &
    Hulbert: second order, maximal damping at infinity for the given rho)."""
    am, af = (2.0 * rho - 1.0) / (rho + 1.0), rho / (rho + 1.0)
    return am, af, 0.5 - am + af, 0.25 * (1.0 - am + af) ** 2


GA_STEP = _ga_coefficients(RHO_GA)
# The step right after the inputs jumped (hs[3] = -1).  The method weighs the forces at
# t_{n+1-alpha_f}, the velocities there (1 - af) v1 + af v0; v0 equilibrated with the old inputs,
# so where friction pins the slip to the new inputs' value within far less than a step, v1
# overshoots that value by af / (1 - af) of the jump (0.8 at rho 0.8) and rings down at -rho a
# step: the one-sample spikes and, with a master that moves the inputs every step, a bias of up
# to 10 % in order 3.  With rho = 0 (af = 0) the forces are taken at t_{n+1}: the slip lands on
# the new value, still second order, at the cost of the same one step.
GA_RESTART = _ga_coefficients(0.0)
GA_RELAX = -2.0        # hs[3]: the next substep by the adaptive substeps
GA_JUMP_RELAX = 0.02   # the slip amplitude's change over v_st above which that is taken
GA_STEP_IN = -3.0      # hs[3]: a step input: the next two communication steps so
GA_STEP_IN_2 = -4.0    # hs[3]: the second of them
GA_JUMP_STEP = 0.2     # the slip amplitude's change over v_st above which that is taken
GA_LOAD_RELAX = 0.02   # the pressing load's relative change above which that is taken


# unknowns of the generalized-alpha step: their position and velocity in Y (-1: the spin
# angle, which nothing depends on), and whether they turn (scaled by r against v_st)
GA_POS = (Y_U, -1, Y_W, Y_B1, Y_B2, Y_E)
GA_VEL = (Y_UD, Y_OM, Y_WD, Y_B1D, Y_B2D, Y_ED)
GA_ROT = (0.0, 1.0, 0.0, 1.0, 1.0, 0.0)
# rows of the generalized-alpha work array GW (NV + 8 rows of NV): the Jacobian, then vectors


@njit
def ga_forces(Y, P, theta, w, x0, L, res, Q, M):
    """Generalized forces Q [N, N m] and masses M [kg, kg m^2] of the roller's unknowns at the
    state Y (whirl angle Y[Y_X]), the equations of kernel.substep: ideal bearing (2 unknowns:
    m u'' = F.a - m (Q''.a + u a''.a), I_s om' = M.a) or lumped (6: also the slide across the
    load w, the tilts b1, b2 and the radial offset e, with the row's forces).  Returns nv."""
    lumped = P[P_BEAR] == 1.0
    line_kinematics(Y[Y_X], w, theta, P, L)
    (cx, cy, cz, vx, vy, vz, wx, wy, wz,
     e1x, e1y, e1z, e2x, e2y, e2z) = roller_motion(Y, x0, L, lumped)
    groove_contact(cx, cy, cz, vx, vy, vz, wx, wy, wz, P, res)
    ax, ay, az = L[0], L[1], L[2]
    fx, fy, fz, mx, my, mz = res[0], res[1], res[2], res[3], res[4], res[5]
    m = P[P_M]
    u = Y[Y_U]
    Q[0] = fx * ax + fy * ay + fz * az - m * (L[11] * az + u * (L[6] * ax + L[7] * ay + L[8] * az))
    Q[1] = mx * ax + my * ay + mz * az
    M[0] = m
    M[1] = P[P_IS]
    nv = 2
    if lumped:
        nv = 6
        It = P[P_IT]
        drag1, drag2 = tilt_drag(It, L, e1x, e1y, e1z, e2x, e2y, e2z)
        Fr, kr = row_load(P, Y[Y_E])
        q = P[P_QSUM] * abs(Fr)
        if P[P_FRICN] > 0.5 and q > 0.0:
            Q[0] -= P[P_MUN] * q * math.tanh(3.0 * (Y[Y_UD] - L[12]) / P[P_VST])
        if P[P_ROLLR] > 0.5 and q > 0.0:
            vr = (Y[Y_OM] - L[13]) * P[P_RB]
            Q[1] -= P[P_MUR] * q * P[P_RB] * math.tanh(3.0 * vr / P[P_VST])
        kw, kt2 = kr * P[P_KWR], kr * P[P_LT]
        kt1 = kt2 * P[P_KWR]
        kx = kr + groove_stiffness_x(P, res, cx, cy)     # radial: the row and the groove
        Q[2] = (fx * e2x + fy * e2y + fz * e2z - kw * Y[Y_W]
                - row_damping(P, kw, m) * Y[Y_WD])
        Q[3] = (mx * e1x + my * e1y + mz * e1z - kt1 * Y[Y_B1] - drag1
                - row_damping(P, kt1, It) * Y[Y_B1D])
        Q[4] = (mx * e2x + my * e2y + mz * e2z - kt2 * Y[Y_B2] - drag2
                - row_damping(P, kt2, It) * Y[Y_B2D])
        Q[5] = fx + Fr - row_damping(P, kx, m) * Y[Y_ED]
        M[2] = m
        M[3] = It
        M[4] = It
        M[5] = m
    if P[P_TRAV] < 0.5:
        Q[0] = 0.0
    return nv


@njit
def _ga_residual(Y, Yf, P, theta, w, x0, h, GW, ra, rr, L, res, Q, co):
    """Residual M ((1 - am) a1 + am a0) - Q(t_f, q_f, v_f) of the generalized-alpha equations at
    the trial accelerations GW[ra] into GW[rr]; GW[W_A0] holds a0, GW[W_M] the masses; co the
    coefficients (GA_STEP or GA_RESTART)."""
    am, af, ga, be = co
    nv = 6 if P[P_BEAR] == 1.0 else 2
    for i in range(nv):
        a0 = GW[W_A0, i]
        a1 = GW[ra, i]
        iv = GA_VEL[i]
        v = Y[iv]
        Yf[iv] = (1.0 - af) * (v + h * ((1.0 - ga) * a0 + ga * a1)) + af * v
        ip = GA_POS[i]
        if ip >= 0:
            q = Y[ip]
            Yf[ip] = (1.0 - af) * (q + h * v + h * h * ((0.5 - be) * a0 + be * a1)) + af * q
    Yf[Y_X] = Y[Y_X] + (1.0 - af) * h * w
    ga_forces(Yf, P, theta, w, x0, L, res, Q, GW[W_M])
    for i in range(nv):
        GW[rr, i] = GW[W_M, i] * ((1.0 - am) * GW[ra, i] + am * GW[W_A0, i]) - Q[i]
    if P[P_TRAV] < 0.5:
        GW[rr, 0] = 0.0


@inline
def _ga_jacobian(Y, Yf, P, theta, w, x0, h, GW, nv, L, res, Q, co):
    """GW[0:nv, 0:nv]: the residual's Jacobian in the accelerations, column j by a finite
    difference of 1e-4 v_st in unknown j's velocity."""
    vs, r, ga = P[P_VST], P[P_R], co[2]
    for j in range(nv):
        d = 1e-4 * vs / (ga * h) / (r if GA_ROT[j] > 0.0 else 1.0)
        for i in range(nv):
            GW[W_AT, i] = GW[W_A, i]
        GW[W_AT, j] += d
        _ga_residual(Y, Yf, P, theta, w, x0, h, GW, W_AT, W_RT, L, res, Q, co)
        for i in range(nv):
            GW[i, j] = (GW[W_RT, i] - GW[W_R, i]) / d


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
def _ga_line_search(Y, Yf, P, theta, w, x0, h, GW, nv, n0, L, res, Q, co):
    """The Newton step halved (up to 8 times) until the scaled residual falls below n0 (the
    tanh friction is steep over v_st); trial point in GW[W_AT], its residual in GW[W_RT].
    Returns the step fraction."""
    lam = 1.0
    for _ in range(8):
        for i in range(nv):
            GW[W_AT, i] = GW[W_A, i] + lam * GW[W_D, i]
        _ga_residual(Y, Yf, P, theta, w, x0, h, GW, W_AT, W_RT, L, res, Q, co)
        n1 = 0.0
        for i in range(nv):
            n1 = max(n1, abs(GW[W_RT, i]) * GW[W_S, i])
        if n1 < n0:
            break
        lam *= 0.5
    return lam


@inline
def _ga_accept(Y, GW, h, w, nv, hs, co):
    """Newmark update of the unknowns' positions and velocities from a0 (GW[W_A0]) and the
    converged a1 (GW[W_A]); a1 kept in hs[5:] for the next step."""
    ga, be = co[2], co[3]
    for i in range(nv):
        a0 = GW[W_A0, i]
        a1 = GW[W_A, i]
        iv = GA_VEL[i]
        v = Y[iv]
        ip = GA_POS[i]
        if ip >= 0:
            Y[ip] = Y[ip] + h * v + h * h * ((0.5 - be) * a0 + be * a1)
        Y[iv] = v + h * ((1.0 - ga) * a0 + ga * a1)
        hs[5 + i] = a1
    Y[Y_X] += h * w
    hs[1] += 1.0
    # whose history the accelerations are: a restart step's (2) serve a restart at the next
    # jump, a regular step takes its own from the forces after it (ga_step)
    hs[3] = 2.0 if co[1] != GA_STEP[1] else 1.0


@njit
def ga_step(Y, P, theta, w, x0, h, L, res, Q, Yf, A, GW, hs):
    """One generalized-alpha step of h [s] on Y (ideal or lumped bearing; Chung & Hulbert
    1993).  Newton on the accelerations, its Jacobian by finite differences (refreshed when
    convergence is slow), each Newton step halved until the residual falls (the tanh friction
    is steep over v_st).  hs[5:11] carry the algorithmic accelerations from step to step
    (hs[3] = 1 when valid; 2 after a restart step; 0: first step or after a fallback, from the
    forces; -1: the inputs jumped at this communication point, this step with GA_RESTART).
    Returns False and leaves Y untouched when Newton does not converge.  Yf (like Y), A
    (NV x NV), GW (NV + 8 x NV) are work arrays."""
    vs, r = P[P_VST], P[P_R]
    trav = P[P_TRAV] > 0.5
    for i in range(Y.shape[0]):
        Yf[i] = Y[i]
    co = GA_RESTART if hs[3] < 0.0 else GA_STEP
    # accelerations from the forces: at the first step, after a fallback, and for a regular
    # step after a restart step (hs[3] = 2: the history belongs to the other coefficients; the
    # slip is on the new inputs' value by now)
    if hs[3] == 0.0 or (hs[3] == 2.0 and co[1] == GA_STEP[1]):
        nv = ga_forces(Y, P, theta, w, x0, L, res, Q, GW[W_M])
        for i in range(nv):
            hs[5 + i] = Q[i] / GW[W_M, i]
    nv = 6 if P[P_BEAR] == 1.0 else 2
    ga = co[2]
    for i in range(nv):
        GW[W_A0, i] = hs[5 + i]
        GW[W_A, i] = hs[5 + i]
    _ga_residual(Y, Yf, P, theta, w, x0, h, GW, W_A, W_R, L, res, Q, co)
    for i in range(nv):   # residual -> the velocity change it would cause, against the tolerance
        GW[W_S, i] = h * ga / (GW[W_M, i] * GA_NTOL * vs) * (r if GA_ROT[i] > 0.0 else 1.0)
    fresh = False
    for it in range(GA_MAXIT):
        if not fresh:
            _ga_jacobian(Y, Yf, P, theta, w, x0, h, GW, nv, L, res, Q, co)
            fresh = True
        n0 = _ga_newton_direction(GW, nv, trav, A, Q)
        lam = _ga_line_search(Y, Yf, P, theta, w, x0, h, GW, nv, n0, L, res, Q, co)
        conv = True
        for i in range(nv):
            GW[W_A, i] = GW[W_AT, i]
            GW[W_R, i] = GW[W_RT, i]
            dv = abs(h * ga * lam * GW[W_D, i]) * (r if GA_ROT[i] > 0.0 else 1.0)
            if dv > GA_NTOL * vs:
                conv = False
        if conv:
            _ga_accept(Y, GW, h, w, nv, hs, co)
            return True
        if it % 3 == 2 or lam < 1.0:
            fresh = False       # slow convergence: a Jacobian at the current iterate
    return False


@njit
def inputs_jumped(P, hs, jump):
    """The inputs changed at this communication point (oppoint.derive: ``jump`` the change of
    the slip's amplitude over v_st, P[P_DF] the pressing load's relative change): the
    generalized-alpha step restarts.
    - A step input (the slip above GA_JUMP_STEP, with the lumped bearing above GA_JUMP_RELAX;
      or the load above GA_LOAD_RELAX: the load sets the pressing offset, and the lumped
      row's, so the contact's spring force jumps): this communication step and the next by
      the adaptive substeps, which land on the new slip and let what the step set ringing
      decay (the lumped row's modes, about 2e4 Hz; the roller's slide); a generalized-alpha
      step restarted on them overshoots (docs/integrators.md).
    - A large jump of the slip (above GA_JUMP_RELAX, ideal bearing): one substep by the
      adaptive substeps, its boundary layer.  (Taking two communication steps there too,
      the coupled launch of docs/driveline-example.md, whose jumps hover about that bound,
      switched between the paths from step to step and lost 0.65 % of its peak.)
    - A small one (a master's ramp, every step): one GA_RESTART step; the lumped bearing
      takes a small load change so too (its row's offset moves with the load).
    The other integrators are L-stable one-step methods or BDF2: they land on the new inputs'
    slip without overshoot."""
    if P[P_INTEG] != 4.0 or P[P_BEAR] > 1.0 or hs[3] <= 0.0 or jump < 0.0:
        return
    lumped = P[P_BEAR] == 1.0
    if P[P_DF] > GA_LOAD_RELAX or jump > (GA_JUMP_RELAX if lumped else GA_JUMP_STEP):
        hs[3] = GA_STEP_IN
    elif jump > GA_JUMP_RELAX:
        hs[3] = GA_RELAX
    elif jump > 0.0 or (lumped and P[P_DF] > 0.0):
        hs[3] = -1.0


@njit
def adaptive_steps(Y, P, theta, w, F_press, x0, T, h0, L, res, Y1, Y2, G, A, b, NW, hs):
    """Advance Y by T [s] with extrapolated substeps chosen by their own error estimate
    (step_error <= 1; up to P[P_HMAX]); hs[0] carries the substep from call to call (h0 [s]
    the first), hs[1] counts accepted, hs[2] rejected substeps."""
    ny = Y.shape[0]
    t = 0.0
    hc = hs[0] if hs[0] > 0.0 else h0
    while t < T * (1.0 - 1e-12):
        last = hc >= T - t
        hh = T - t if last else hc
        for i in range(ny):
            Y1[i] = Y[i]
            Y2[i] = Y[i]
        substep(Y1, P, theta, w, F_press, x0, hh, L, res, G, A, b, NW)
        substep(Y2, P, theta, w, F_press, x0, 0.5 * hh, L, res, G, A, b, NW)
        substep(Y2, P, theta, w, F_press, x0, 0.5 * hh, L, res, G, A, b, NW)
        err = step_error(Y2, Y1, P)
        fac = 0.9 / math.sqrt(max(err, 1e-12))   # local error of the whole step ~ h^2
        fac = min(4.0, max(0.2, fac))
        if err <= 1.0:
            for i in range(ny):
                Y[i] = 2.0 * Y2[i] - Y1[i]
            t += hh
            hs[1] += 1.0
            if not last:            # a step cut short to land on T says nothing of hc
                hc = min(hc * fac, P[P_HMAX])
        else:
            hs[2] += 1.0
            hc = hh * fac
    hs[0] = hc


@njit
def ga_steps(Y, P, theta, w, F_press, x0, h, n, L, res, Y1, Y2, G, A, b, NW, hs, GW):
    """n generalized-alpha steps of h [s] (ideal or lumped bearing), restarted where the
    inputs jumped (hs[3], inputs_jumped): a step input by the adaptive substeps over this
    communication step and the next, a large jump over one substep, a small one by one
    GA_RESTART step; a step whose Newton fails by the adaptive substeps."""
    for _ in range(n):
        if hs[3] == GA_STEP_IN or hs[3] == GA_STEP_IN_2:
            # a step input: this communication step and the next by the error-controlled
            # L-stable extrapolated substeps (the slip relaxing onto the new inputs' value,
            # and what the step set ringing), then the accelerations afresh from the forces
            adaptive_steps(Y, P, theta, w, F_press, x0, h * n, 0.25 * h, L, res, Y1, Y2,
                           G, A, b, NW, hs)
            hs[3] = GA_STEP_IN_2 if hs[3] == GA_STEP_IN else 0.0
            break
        if hs[3] == GA_RELAX:
            # a large jump: its boundary layer (the slip relaxing onto the new inputs'
            # value) by the adaptive substeps over one substep
            adaptive_steps(Y, P, theta, w, F_press, x0, h, 0.25 * h, L, res, Y1, Y2, G, A,
                           b, NW, hs)
            hs[3] = 0.0    # then the accelerations afresh from the forces
            continue
        if hs[3] < 0.0:    # the inputs jumped: the restart step (GA_RESTART)
            if ga_step(Y, P, theta, w, x0, h, L, res, b, Y1, A, GW, hs):
                continue
            hs[3] = 1.0    # its Newton did not converge: the regular step
        if not ga_step(Y, P, theta, w, x0, h, L, res, b, Y1, A, GW, hs):
            # Newton did not converge (a very steep friction law): this step by the
            # error-controlled extrapolated substeps instead, then start afresh
            adaptive_steps(Y, P, theta, w, F_press, x0, h, 0.25 * h, L, res, Y1, Y2, G, A,
                           b, NW, hs)
            hs[3] = 0.0
            hs[4] += 1.0


@njit
def run_substeps(Y, P, theta, w, F_press, x0, h, n, out, L, res, Y1, Y2, G, A, b, NW, hs,
                 GW):
    """Advance Y by n substeps of h [s] at constant inputs; write the outputs at the end.

    theta [rad], w [rad/s], F_press [N], x0 [m] the pressing offset of the trunnion axis.
    P[P_INTEG] = 1: each substep is extrapolated (Richardson) from one step of h and two of
    h/2, which makes the linearly implicit Euler second order and keeps it L-stable
    (the scheme of LIMEX/SEULEX with two stages); 0: plain linearly implicit Euler.
    P[P_INTEG] = 3: the same extrapolated step with its substep chosen by the step's own error
    estimate (step_error <= 1; up to P[P_HMAX]); hs[0] carries that substep from call to call,
    hs[1] counts accepted, hs[2] rejected substeps.
    P[P_INTEG] = 4 with the ideal or lumped bearing: n generalized-alpha steps of h (ga_step,
    work array GW), hs[3] and hs[5:11] its accelerations, hs[4] counts steps handed to the
    extrapolated substeps; with the needle-resolved bearing n BDF2 substeps (bdf2_steps), Y2
    the previous state, hs[0] the previous substep, hs[3] whether they are valid.
    L (L_LEN), res (19), Y1, Y2 (like Y), G (NV x 3), A (NV x NV), b (NV) are work arrays;
    NW the needle work arrays (model.ContactModel) with the resolved bearing, else None.
    """
    extrap = P[P_INTEG] == 1.0
    Y[Y_PL] += P[P_VP] * (h * n)     # the plunge: the held plunge speed's exact integral
    if P[P_INTEG] == 4.0 and P[P_BEAR] <= 1.0:
        ga_steps(Y, P, theta, w, F_press, x0, h, n, L, res, Y1, Y2, G, A, b, NW, hs, GW)
        n = 0
    elif P[P_INTEG] == 4.0:   # the needle-resolved bearing: BDF2, roller and row in one system
        if NW is not None:    # (always, here; the test lets numba drop it from the others)
            bdf2_steps(Y, P, theta, w, F_press, x0, h, n, L, res, Y1, Y2, G, A, b, NW, hs)
        n = 0
    elif P[P_INTEG] >= 3.0:
        adaptive_steps(Y, P, theta, w, F_press, x0, h * n, h, L, res, Y1, Y2, G, A, b, NW, hs)
        n = 0
    for _ in range(n):
        if extrap:
            extrapolated_step(Y, Y1, P, theta, w, F_press, x0, h, L, res, G, A, b, NW)
        else:
            substep(Y, P, theta, w, F_press, x0, h, L, res, G, A, b, NW)
        hs[1] += 1.0   # substeps taken, as the adaptive ones count theirs
    # outputs at the end of the step (forces on the groove = minus those on the roller)
    line_kinematics(Y[Y_X], w, theta, P, L)
    om = Y[Y_OM]
    (cx, cy, cz, vx, vy, vz, wx, wy, wz,
     e1x, e1y, e1z, e2x, e2y, e2z) = roller_motion(Y, x0, L, P[P_BEAR] > 0.5)
    groove_contact(cx, cy, cz, vx, vy, vz, wx, wy, wz, P, res)
    if NW is not None:   # needle loads at the output instant (diagnostics)
        resolved_forces(Y, P, NW, theta, Y[Y_X], 0.0, L, e1x, e1y, e1z, e2x, e2y, e2z, 0.0,
                        False)
    out[O_FX] = -res[0]
    out[O_FY] = -res[1]
    out[O_FZ] = -res[2]
    out[O_CY] = res[17]
    out[O_CZ] = res[18]
    out[O_SLIP] = res[13]
    out[O_SPIN] = om
    out[O_FN] = res[9]
    out[O_X] = Y[Y_X]
    out[O_PL] = Y[Y_PL]


# the roller's velocity unknowns in Y (ud, om, wd, b1d, b2d, ed) and the positions they move
# (-1: none)
_RV, _RQ = GA_VEL, GA_POS   # the same unknowns (velocity, position) as the GA step's


@njit
def coupled_solve(A, b, NW, g, n, trav):
    """The roller (A y = b, its unknowns) bordering the needles' ring (R x = g FN) through
    the coupling blocks BN (needle rows, the roller's standard velocities; zero for a needle
    clear of the bore, ND[j, D_BORE] = 0): Schur complement on the roller.  b <- y, FN <- x.

    An open ring (some neighbours apart, the usual case): block Cholesky along the chain
    (needles.chain_forward), U = Z^T Z with Z = L^-1 B', one back substitution.  A closed ring,
    or a block that is not positive definite: R^-1 applied to g FN and the six coupling
    columns in one elimination (ring_solve_m, _coupled_solve_general)."""
    FN, AN, UN, RH, ZF = NW[2], NW[3], NW[11], NW[20], NW[25]
    _coupled_rhs(NW, g, n, trav)
    j0 = -1
    for k in range(n):
        if not NDL._touching(UN[k]):
            j0 = (k + 1) % n
            break
    if j0 < 0 or not NDL.chain_forward(AN, UN, RH, ZF, n, j0, NW[24], NW[14]):
        if j0 >= 0:
            _coupled_rhs(NW, g, n, trav)   # the failed sweep wrote over them
        _coupled_solve_general(A, b, NW, n)
        return
    U = NW[16]   # Z^T Z is symmetric: its upper triangle, then both of A's
    for c in range(6):
        for d in range(6):
            U[c, d] = 0.0
    for j in range(n):
        if ZF[j] > 0.0:
            for i in range(6):
                y0 = RH[j, i, 0]
                for c in range(6):
                    zc = RH[j, i, 1 + c]
                    if zc != 0.0:
                        b[c] -= zc * y0
                        for d in range(c, 6):
                            U[c, d] += zc * RH[j, i, 1 + d]
    _schur_solve(A, b, U)
    NDL.chain_backward(RH, ZF, b, UN, n, j0, NW[24], NW[14], FN)


@njit
def _coupled_rhs(NW, g, n, trav):
    """coupled_solve's right-hand sides RH[j] = (g FN[j], B'[j]) with B' = BN TM^T, zero for a
    needle clear of the bore; ZF[j] flags those on it."""
    FN, ND, BN, RH, ZF = NW[2], NW[6], NW[18], NW[20], NW[25]
    TM = NW[10][:, 7:13]
    # B' = BN TM^T: TM has 7 nonzeros of 36 (needles._roller_unknowns), listed once here
    nz = 0
    KC = NW[16]   # scratch (6 x 6): row c lists TM[c]'s nonzero columns, -1 after the last
    for c in range(6):
        m = 0
        if trav or c > 0:
            for k in range(6):
                if TM[c, k] != 0.0:
                    KC[c, m] = k
                    m += 1
        if m < 6:
            KC[c, m] = -1.0
        nz += m
    for j in range(n):
        bore = ND[j, NDL.D_BORE] > 0.0 and nz > 0
        ZF[j] = 1.0 if bore else 0.0
        for i in range(6):
            RH[j, i, 0] = g * FN[j, i]
            for c in range(6):
                acc = 0.0
                if bore:
                    for m in range(6):
                        k = int(KC[c, m])
                        if k < 0:
                            break
                        acc += BN[j, i, k] * TM[c, k]
                RH[j, i, 1 + c] = acc


@inline
def _schur_solve(A, b, U):
    """y = (A - U)^-1 b in b, U symmetric (its upper triangle given)."""
    for c in range(6):
        A[c, c] -= U[c, c]
        for d in range(c + 1, 6):
            A[c, d] -= U[c, d]
            A[d, c] -= U[c, d]
    solve_small(A, b, 6)


@njit
def _coupled_solve_general(A, b, NW, n):
    """coupled_solve for any ring, its right-hand sides RH already set (g FN, then B'):
    R^-1 applied to all seven in one elimination (ring_solve_m), then the Schur complement."""
    FN, AN, UN, ND, RH, Bp = NW[2], NW[3], NW[11], NW[6], NW[20], NW[23]
    for j in range(n):
        for i in range(6):
            for c in range(6):
                Bp[j, i, c] = RH[j, i, 1 + c]   # kept: the solve overwrites RH
    NDL.ring_solve_m(AN, UN, RH, 7, n, NW[14], NW[21], NW[16], NW[22])
    U = NW[16]   # B'^T R^-1 B' is symmetric: its upper triangle
    for c in range(6):
        for d in range(6):
            U[c, d] = 0.0
    for j in range(n):
        if ND[j, NDL.D_BORE] > 0.0:
            for c in range(6):
                for i in range(6):
                    bc = Bp[j, i, c]
                    if bc != 0.0:
                        b[c] -= bc * RH[j, i, 0]
                        for d in range(c, 6):
                            U[c, d] += bc * RH[j, i, 1 + d]
    _schur_solve(A, b, U)
    for j in range(n):
        for i in range(6):
            acc = RH[j, i, 0]
            for c in range(6):
                acc -= RH[j, i, 1 + c] * b[c]
            FN[j, i] = acc


@njit
def bdf2_steps(Y, P, theta, w, F_press, x0, h, n, L, res, Y1, Y2, G, A, b, NW, hs):
    """n BDF2 substeps of h [s] (bdf2_substep) with the needle-resolved bearing; Y2 carries the
    previous state and hs[0] the previous substep from call to call, hs[3] whether they are
    valid, hs[1] counts substeps."""
    ny = Y.shape[0]
    for _ in range(n):
        if hs[3] == 0.0 or h > 2.0 * hs[0]:
            # no history yet (or a step more than twice the last, where variable-step BDF2
            # nears its stability limit): one extrapolated split step (re)starts it
            for i in range(ny):
                Y2[i] = Y[i]
            extrapolated_step(Y, Y1, P, theta, w, F_press, x0, h, L, res, G, A, b, NW)
            hs[3] = 1.0
        else:
            bdf2_substep(Y, Y2, Y1, P, theta, w, F_press, x0, h, hs[0], L, res, G, A, b, NW)
        hs[0] = h
        hs[1] += 1.0


@njit
def bdf2_substep(Y, Yp, YL, P, theta, w, F_press, x0, h, hp, L, res, G, A, b, NW):
    """One linearly implicit BDF2 step of h [s] (the previous step hp) with the needle-resolved
    bearing: Y = y_n -> y_{n+1}, Yp = y_{n-1} -> y_n, YL work.

    y_{n+1} - a1 y_n + a2 y_{n-1} = g f(y_{n+1}) (variable-step BDF2, g = beta h), linearized
    at the predicted state y_L: velocities extrapolated linearly, positions
    q_L = a1 q_n - a2 q_{n-1} + g v_L (the BDF2 position rule, so the correction e moves
    positions by g e_v and the stiffness needs no K v term): (M + g D + g^2 K) e_v =
    g F(y_L) - M (v_L - a1 v_n + a2 v_{n-1}).  One contact evaluation a step; second order with
    any tangent (the linearization error is O(e^2) with e = O(h^2))."""
    r = h / hp
    a1 = (1.0 + r) ** 2 / (1.0 + 2.0 * r)
    a2 = r * r / (1.0 + 2.0 * r)
    g = (1.0 + r) / (1.0 + 2.0 * r) * h
    m = P[P_M]
    It = P[P_IT]
    NP = NW[0]
    n = int(NP[NDL.N_N])
    _bdf2_predict(Y, Yp, YL, r, a1, a2, g, n)
    x = Y[Y_X] + h * w
    YL[Y_X] = x
    cx, cy, e1x, e1y, e1z, e2x, e2y, e2z = _roller_system(YL, P, theta, w, x0, x, g, L, res, G,
                                                           A, b, True, True, 6)
    drag1, drag2 = tilt_drag(It, L, e1x, e1y, e1z, e2x, e2y, e2z)
    kh = groove_stiffness_x(P, res, cx, cy)
    resolved_row_terms(YL, P, NW, theta, x, g, L, e1x, e1y, e1z, e2x, e2y, e2z, It, kh, drag1,
                       drag2, A, b, 0.0, True)
    mr = (m, P[P_IS], m, It, It, m)
    for i in range(6):
        vi = _RV[i]
        b[i] = g * b[i] - mr[i] * (YL[vi] - a1 * Y[vi] + a2 * Yp[vi])
    trav = P[P_TRAV] > 0.5
    if not trav:
        hold_slide(A, b, 6)
    # the needles: the same rule on the ring (right-hand side h FN in ring_solve)
    FN, AN, UN = NW[2], NW[3], NW[11]
    mn, I1, I3 = NP[NDL.N_MN], NP[NDL.N_I1], NP[NDL.N_I3]
    for j in range(n):
        q = Y_LEN + NDL.N_F * j
        mj = (mn, mn, mn, I1, I1, I3)
        for i in range(6):
            FN[j, i] -= mj[i] * (YL[q + 5 + i] - a1 * Y[q + 5 + i] + a2 * Yp[q + 5 + i]) / g
            AN[j, i, i] += mj[i]
    coupled_solve(A, b, NW, g, n, trav)
    _bdf2_correct(Y, Yp, YL, b, FN, g, n)


@njit
def _bdf2_predict(Y, Yp, YL, r, a1, a2, g, n):
    """bdf2_substep's predicted state YL: velocities extrapolated from y_n, y_{n-1} (step ratio
    r), positions by the BDF2 rule q_L = a1 q_n - a2 q_{n-1} + g v_L (needle tilts: t1' = w2,
    t2' = -w1)."""
    for i in range(6):
        vi, qi = _RV[i], _RQ[i]
        YL[vi] = Y[vi] + r * (Y[vi] - Yp[vi])
        if qi >= 0:
            YL[qi] = a1 * Y[qi] - a2 * Yp[qi] + g * YL[vi]
    for j in range(n):
        q = Y_LEN + NDL.N_F * j
        for i in range(5, 11):
            YL[q + i] = Y[q + i] + r * (Y[q + i] - Yp[q + i])
        for i in range(3):
            YL[q + i] = a1 * Y[q + i] - a2 * Yp[q + i] + g * YL[q + 5 + i]
        YL[q + 3] = a1 * Y[q + 3] - a2 * Yp[q + 3] + g * YL[q + 9]
        YL[q + 4] = a1 * Y[q + 4] - a2 * Yp[q + 4] - g * YL[q + 8]


@njit
def _bdf2_correct(Y, Yp, YL, b, FN, g, n):
    """bdf2_substep's new state: the predicted one plus the velocity corrections (b: the
    roller's unknowns, FN: each needle's), positions moved by g times them; Yp <- y_n,
    Y <- y_{n+1}."""
    for i in range(6):
        vi, qi = _RV[i], _RQ[i]
        YL[vi] += b[i]
        if qi >= 0:
            YL[qi] += g * b[i]
    for j in range(n):
        q = Y_LEN + NDL.N_F * j
        for i in range(6):
            YL[q + 5 + i] += FN[j, i]
        for i in range(3):
            YL[q + i] += g * FN[j, i]
        YL[q + 3] += g * FN[j, 4]
        YL[q + 4] -= g * FN[j, 3]
    for i in range(Y.shape[0]):
        Yp[i] = Y[i]
        Y[i] = YL[i]
