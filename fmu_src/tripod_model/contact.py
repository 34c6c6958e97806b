"""The roller at the groove, in the contact model's frame: where the trunnion drives it and what
the groove does on it.  The driving motions: the trunnion's line (pitch, roll, Eqs. 1, 5, 18),
its axial travel and yaw (Eqs. 3, 7) with their time derivatives, and the roller's motion on it.
The contact laws, each one equation: Hertz normal force (Eq. 10), tanh friction (Eq. 11), spin
moment (Eqs. 14-16), the roller-groove contact they make, and the lumped needle row's load
(Eq. 17) and damping.

Frame (model.md): groove fixed, groove axis = z axis through the origin, x = pressing
direction, y = trunnion axis (nominal).  Forces in res are on the roller; the outputs report
those on the groove (kernel.run_substeps).
"""
import math

from reduced_model import friction, needle_row
from .jit import inline, njit
from .layout import (BEAR_IDEAL, L_AAX, L_AAY, L_AAZ, L_ADX, L_ADY, L_ADZ, L_AX, L_AY, L_AZ, L_KTH,
    L_KVP, L_KW, L_KX, L_QZ, L_QZD, L_QZDD, L_SPIN, L_VAX, P_A1, P_AXIAL, P_BEARING,
    P_NEEDLE_CLEARANCE, P_NEEDLE_AXIAL_CLEARANCE, P_FLANK, P_FRICTION_GROOVE, P_CONTACT_DAMPING,
    P_K, P_KN, P_KN1, P_LT, P_NROW,
    P_FRICTION_NEEDLE, P_MU_GROOVE, P_MU_NEEDLE, P_MU_ROLLING, P_PITCH, P_R_ROLLER, P_R_BORE,
    P_R_GROOVE, P_ROLL, P_S,
    P_SPIN_MOMENT, P_VP, P_VST_OP, P_YAW, P_ROW_DAMPING, R_FN, R_FX, R_FY, R_FZ, R_G, R_LEN, R_MX,
    R_MY, R_MZ, R_NX, R_NY, R_PX, R_PY, R_PZ, R_SLIP, R_SLOPE, R_VTX, R_VTY, R_VTZ, Y_B1D, Y_B2D,
    Y_E, Y_ED, Y_OM, Y_U, Y_UD, Y_W, Y_WD, Y_X)


# --- driving motions ---

@njit
def trunnion_line(x, theta, s, pitch, roll):
    """Trunnion axis at whirl angle x: point Q on it at the groove's mid-plane and direction a.

    Pitching about x through the spider centre, Eq. (1): the axis meets the plane y = 0 at
    z = s tan(phi) (Eq. 18).  Rolling, Eq. (5), turns the axis about -z through that point
    (sense chosen so that the slip on the loaded +x flank is V = v1 + v2, model.md).
    Returns (Qz, ax, ay, az); Q = (x0, 0, Qz) with x0 the pressing offset.
    """
    q, _q1, _q2, a, _a1, _a2 = _line_rates(math.sin(x), math.cos(x), math.tan(theta),
                                           _roll_ratio(theta), s, pitch, roll)
    return q, a[0], a[1], a[2]


@inline
def _roll_ratio(theta):
    """e / s of the roll, Eq. (5): the trunnion's eccentricity over the spider radius."""
    return (1.0 - math.cos(theta)) / (2.0 * math.cos(theta))


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


@inline
def trunnion_axial_rate(x, theta, s, axial):
    """d/dx of trunnion_axial [m/rad], Eq. (7) differentiated: with sin(xi) = e sin(2x) / s,
    2 e (sin 2x + tan(xi) cos 2x)."""
    if not axial:
        return 0.0
    c = math.cos(theta)
    e = s * (1.0 - c) / (2.0 * c)
    sxi = e * math.sin(2.0 * x) / s
    return 2.0 * e * (math.sin(2.0 * x) + sxi / math.sqrt(1.0 - sxi * sxi) * math.cos(2.0 * x))


@inline
def trunnion_yaw_rate(x, theta, yaw):
    """d/dx of trunnion_yaw [rad/rad], Eq. (3) differentiated: -T sin x / (1 + T^2 cos^2 x),
    T = tan(theta)."""
    if not yaw:
        return 0.0
    T = math.tan(theta)
    tc = T * math.cos(x)
    return -T * math.sin(x) / (1.0 + tc * tc)


@inline
def _line_rates(sx, cx, T, k, s, pitch, roll):
    """trunnion_line's Qz and a with their first and second derivatives in the whirl angle x
    (sine and cosine sx, cx; T = tan(theta), k = _roll_ratio(theta)), in closed form from
    tan(phi) = T sin x (Eq. 1) and sin(xi) = k sin 2x (Eq. 5): (Qz, Qz', Qz'', a, a', a''),
    each of a's an (x, y, z) tuple."""
    # the pitch and roll angles enter only as tan(phi) and sin(xi): no atan, asin, nor sines
    # and cosines of them (with glibc's tanh and pow, libm took a third of the contact step's
    # time)
    t = t1 = t2 = 0.0
    if pitch:
        t, t1, t2 = T * sx, T * cx, -T * sx          # tan(phi) and its derivatives
    c = 1.0 / math.sqrt(1.0 + t * t)                   # cos(phi)
    c3 = c * c * c
    c1 = -t * t1 * c3
    c2 = -(t1 * t1 + t * t2) * c3 + 3.0 * t * t * t1 * t1 * c3 * c * c
    u = u1 = u2 = 0.0
    if roll:
        u = k * 2.0 * sx * cx                          # sin(xi) = k sin 2x
        u1, u2 = 2.0 * k * (cx * cx - sx * sx), -4.0 * u
    v = math.sqrt(1.0 - u * u)                         # cos(xi)
    v1 = -u * u1 / v
    v2 = -(u1 * u1 + u * u2) / v - u * u * u1 * u1 / (v * v * v)
    a = (u * c, v * c, t * c)
    a1 = (u1 * c + u * c1, v1 * c + v * c1, t1 * c + t * c1)
    a2 = (u2 * c + 2.0 * u1 * c1 + u * c2, v2 * c + 2.0 * v1 * c1 + v * c2,
          t2 * c + 2.0 * t1 * c1 + t * c2)
    return s * t, s * t1, s * t2, a, a1, a2


@njit
def line_kinematics(x, w, theta, P, L):
    """Q, a and their first and second time derivatives at whirl angle x, whirl rate w.

    out[0:3] a, [3:6] da/dt, [6:9] d2a/dt2, [9] Qz, [10] dQz/dt (with the plunge speed
    P[P_VP]: the spider's travel along the groove), [11] d2Qz/dt2,
    [12] trunnion material velocity along its axis (dd/dt), [13] trunnion spin rate about a,
    [14:18] the (x, w, theta, plunge speed) they were computed for (a one-entry cache; NaN =
    empty).  The derivatives in closed form (_line_rates), chain rule with constant w within
    a substep: finite differences in x would carry rounding noise of about 1e-8 into the
    second ones, redrawn by any change of theta.
    """
    vp = P[P_VP]
    if L[L_KX] == x and L[L_KW] == w and L[L_KTH] == theta and L[L_KVP] == vp:
        return   # same whirl angle as the last call (the extrapolated step visits x + h twice)
    L[L_KX] = x
    L[L_KW] = w
    L[L_KTH] = theta
    L[L_KVP] = vp
    s = P[P_S]
    q, q1, q2, a, a1, a2 = _line_rates(math.sin(x), math.cos(x), math.tan(theta),
                                       _roll_ratio(theta), s, P[P_PITCH] > 0.5,
                                       P[P_ROLL] > 0.5)
    ww = w * w
    L[L_AX], L[L_AY], L[L_AZ] = a
    L[L_ADX], L[L_ADY], L[L_ADZ] = a1[0] * w, a1[1] * w, a1[2] * w
    L[L_AAX], L[L_AAY], L[L_AAZ] = a2[0] * ww, a2[1] * ww, a2[2] * ww
    L[L_QZ] = q
    L[L_QZD] = q1 * w
    if vp != 0.0:
        L[L_QZD] += vp
    L[L_QZDD] = q2 * ww
    if P[P_BEARING] != BEAR_IDEAL:   # the trunnion's own slide and spin matter only to the needles
        L[L_VAX] = trunnion_axial_rate(x, theta, s, P[P_AXIAL] > 0.5) * w
        L[L_SPIN] = trunnion_yaw_rate(x, theta, P[P_YAW] > 0.5) * w
    else:
        L[L_VAX] = 0.0
        L[L_SPIN] = 0.0


@njit
def roller_motion(Y, x0, x0_rate, L, lumped):
    """Roller centre c [m], its velocity v [m/s] and angular velocity w [rad/s] from the state,
    the trunnion line L and its pressing offset x0 [m] moving at x0_rate [m/s] (a load's ramp,
    a floating spider), plus the row axes e1 (pressing direction normal to the trunnion axis)
    and e2 = a x e1 (zero with the ideal bearing, whose extra freedoms are locked); each an
    (x, y, z) tuple.

    c = Q + u a + e x_hat + w_o e2; w = a x da/dt + om a + b1' e1 + b2' e2.
    """
    ax, ay, az = L[L_AX], L[L_AY], L[L_AZ]
    adx, ady, adz = L[L_ADX], L[L_ADY], L[L_ADZ]
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
    cz = L[L_QZ] + u * az + wo * e2z
    vx = ud * ax + u * adx + Y[Y_ED] + wod * e2x
    if x0_rate != 0.0:
        vx += x0_rate
    vy = ud * ay + u * ady + wod * e2y
    vz = L[L_QZD] + ud * az + u * adz + wod * e2z
    wx = ay * adz - az * ady + om * ax + b1d * e1x + b2d * e2x
    wy = az * adx - ax * adz + om * ay + b1d * e1y + b2d * e2y
    wz = ax * ady - ay * adx + om * az + b1d * e1z + b2d * e2z
    return (cx, cy, cz), (vx, vy, vz), (wx, wy, wz), (e1x, e1y, e1z), (e2x, e2y, e2z)


@njit
def tilt_drag(It, L, e1, e2):
    """Moments [N m] about e1, e2 with which the trunnion's angular acceleration a x a''
    drags the tilting roller (inertia It about a diameter) along."""
    e1x, e1y, e1z = e1
    e2x, e2y, e2z = e2
    ax, ay, az = L[L_AX], L[L_AY], L[L_AZ]
    alx = ay * L[L_AAZ] - az * L[L_AAY]
    aly = az * L[L_AAX] - ax * L[L_AAZ]
    alz = ax * L[L_AAY] - ay * L[L_AAX]
    return It * (alx * e1x + aly * e1y + alz * e1z), It * (alx * e2x + aly * e2y + alz * e2z)


# --- contact laws ---


@inline
def hertz_normal_force(K, delta):
    """Roller-groove normal force [N] at the approach delta [m]: Eq. (10) with Table 1's point
    contact, f_n = K delta^(3/2) (K [N/m^1.5] from hertz.hertz_point)."""
    return K * delta * math.sqrt(delta)   # (pow costs more)


# tanh from one exp (reduced_model.friction.tanh_clipped: the needle row calls it about 1100
# times an evaluation; the groove's friction and the lumped row's laws use it too), inline
tanh_clipped = inline(friction.tanh_clipped)


@inline
def tanh_friction(mu, fn, vt, vst):
    """Regularised friction, Eq. (11) with model.md's law mu(v) = mu tanh(3 v / v_st): returns
    g = tanh(3 |v_t| / v_st) (the friction force is mu f_n g [N]) and its slope
    d(mu f_n g)/d|v_t| [N s/m] at the slip |v_t| [m/s], normal force f_n [N]."""
    g = tanh_clipped(3.0 * vt / vst)
    return g, mu * fn * 3.0 / vst * (1.0 - g * g)


# the spin moment, Eqs. (14)-(16): reduced_model.friction.spin_moment, compiled inline
spin_moment = inline(friction.spin_moment)


@inline
def flank_centre(P, cx):
    """x [m] of the centre of the flank arc that faces a roller centred at x = cx [m]: the
    track's two flanks are arcs of radius r_groove whose centres sit P_FLANK = running_clearance
    / 2 - (r_groove - r_roller) either side of its mid-plane (P_FLANK = 0: one cylinder, the
    paper's groove).  With P_FLANK >= 0 (scene.validate) the facing flank is the only one the
    roller can touch."""
    return P[P_FLANK] if cx >= 0.0 else -P[P_FLANK]


@njit
def groove_contact(c, v, wr, P, res):
    """Roller (sphere) on the facing flank of the groove (a concave cylinder along z, or two
    arcs apart: flank_centre): Hertz normal force, tanh friction on the full 3-D slip at the
    contact point, spin moment Eq. (16).

    c: roller centre [m], v: its velocity [m/s], wr: roller angular velocity [rad/s] (each
    (x, y, z)).  res (layout's R_ slots, on the roller): force [N], moment about c [N m],
    normal n, f_n [N], tangential slip v_t [m/s], |v_t|, g = tanh(3|v_t|/v_st), friction slope
    d(mu f_n g)/d|v_t| [N s/m], contact point [m].
    """
    cx, cy, cz = c
    vx, vy, vz = v
    wx, wy, wz = wr
    r = P[P_R_ROLLER]
    dx = cx - flank_centre(P, cx)             # from the facing flank's arc centre
    rho = math.sqrt(dx * dx + cy * cy)
    nx = dx / rho
    ny = cy / rho
    delta = rho + r - P[P_R_GROOVE]                 # penetration, model.md
    for i in range(R_LEN):
        res[i] = 0.0
    res[R_NX] = nx
    res[R_NY] = ny
    res[R_PX] = cx + r * nx
    res[R_PY] = cy + r * ny
    res[R_PZ] = cz
    if delta <= 0.0:
        return
    fn = hertz_normal_force(P[P_K], delta)
    if P[P_CONTACT_DAMPING] > 0.0:   # Hunt-Crossley: f_n (1 + 3/2 alpha d delta/dt), never pulling
        fn = max(0.0, fn * (1.0 + 1.5 * P[P_CONTACT_DAMPING] * (vx * nx + vy * ny)))
    # velocity of the roller material at the contact point p = c + r n
    px = vx + (wy * 0.0 - wz * r * ny)
    py = vy + (wz * r * nx - wx * 0.0)
    pz = vz + (wx * r * ny - wy * r * nx)
    pn = px * nx + py * ny
    tx = px - pn * nx
    ty = py - pn * ny
    tz = pz
    vt = math.sqrt(tx * tx + ty * ty + tz * tz)
    mu = P[P_MU_GROOVE]
    vst = P[P_VST_OP]
    fx = -fn * nx
    fy = -fn * ny
    fz = 0.0
    mx = 0.0
    my = 0.0
    mz = 0.0
    g = 0.0
    slope = 0.0
    if P[P_FRICTION_GROOVE] > 0.5 and mu > 0.0:
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
    if P[P_SPIN_MOMENT] > 0.5 and mu > 0.0:
        ms = spin_moment(mu, fn, P[P_A1], wx * nx + wy * ny, vst)   # spin against the groove
        mx -= ms * nx
        my -= ms * ny
    res[R_FX] = fx
    res[R_FY] = fy
    res[R_FZ] = fz
    res[R_MX] = mx
    res[R_MY] = my
    res[R_MZ] = mz
    res[R_FN] = fn
    res[R_VTX] = tx
    res[R_VTY] = ty
    res[R_VTZ] = tz
    res[R_SLIP] = vt
    res[R_G] = g
    res[R_SLOPE] = slope


# the lumped row's law, Eq. (17) over its needles (needle_row.sum_row), compiled inline
sum_row = inline(needle_row.sum_row)
row_arc = inline(needle_row.row_arc)


@inline
def row_load(P, e):
    """Lumped needle row with the roller e [m] off the trunnion axis along x: the row's radial
    force on the roller F_r [N] (pushing it back onto the axis: +x in drive, e < 0; -x in
    coast), its tangent stiffness along the load k_r and across it k_w [N/m], the sum of
    the needle loads q [N] and where across the load they meet the bore, row_arc [m]
    (sum_row, as oppoint.row_sums)."""
    f, k, kw, q, qs = sum_row(P[P_NEEDLE_CLEARANCE], int(P[P_NROW]), P[P_KN1], abs(e))
    return (f if e < 0.0 else -f), k, kw, q, row_arc(P[P_R_BORE], q, qs)


# the lumped row's sliding friction as a line contact along the needles: its points (the
# paper's N_s spheres a needle)
ROW_LINE = 7
# a needle sits between two sliding contacts of equal load and friction (the bore and the
# trunnion): each takes half of the roller's slip on the trunnion; against its axial stop the
# trunnion carries it and the bore takes the whole slip (row_play)
ROW_SERIES = 0.5


@inline
def row_sliding_friction(P, q, ud, vax, b1d, b2d, lever, arc, h, series):
    """Lumped row: the loaded needles' sliding friction on the roller (mu_needle, the resolved
    contacts' tanh law on the 2-D slip) as two line contacts along the needles (ROW_LINE
    points y along each, q / (2 ROW_LINE) each) where they meet the bore: lever [m] along the
    pressing direction e1 (row_lever), +-arc [m] across it (row_arc).  The slip along the
    trunnion there is ud - vax less the bore's axial motion from the tilts (lever b2d, -+arc
    b1d); across, the tilt about e1's b1d y, which a needle cannot roll away; `series` of each
    is the bore's (row_play).  q [N]; ud, vax [m/s]; b1d, b2d [rad/s].  Returns the forces
    against the slide [N] and the tilts [N m] and h [s] times their Jacobian in (ud, b1d, b2d):
    (f_u, f_1, f_2, h j_uu, h j_u1, h j_u2, h j_11, h j_12, h j_22) (docs/model.md, "What the
    needle row does to the thrust", "The needles' friction around the loaded arc")."""
    k3 = series * 3.0 / P[P_VST_OP]
    lh = math.sqrt(12.0 * P[P_LT])          # the needles' length (P_LT = l^2 / 12)
    c = 0.5 * P[P_MU_NEEDLE] * q / ROW_LINE
    s0 = ud - vax - lever * b2d
    fa = f1 = jaa = ja1 = j11 = 0.0
    for side in range(2):                   # the arc's two sides, x2 = +arc and -arc
        x2 = arc if side == 0 else -arc
        sa = s0 + x2 * b1d
        # the points at -y and y alike: the middle one, then the pairs outwards
        for k in range(ROW_LINE // 2, ROW_LINE):
            d = lh * ((k + 0.5) / ROW_LINE - 0.5)   # the point's place along the needle [m]
            w = 1.0 if 2 * k + 1 == ROW_LINE else 2.0
            st = d * b1d
            s = math.sqrt(sa * sa + st * st)
            x = k3 * s
            g = tanh_clipped(x)
            gs = k3 * (1.0 - x * x / 3.0) if x < 1e-4 else g / s   # g / |s|, its limit at 0
            t = 0.0
            if s > 0.0:
                t = (k3 * (1.0 - g * g) - gs) / (s * s)   # (dg/d|s| - g/|s|) / |s|^2
            cw = c * w
            ga = gs + t * sa * sa   # d(gs sa) / d sa (b2d: the chain rule, -lever)
            fa += cw * gs * sa
            f1 += cw * gs * (st * d + sa * x2)
            jaa += cw * ga
            ja1 += cw * (ga * x2 + t * sa * st * d)
            j11 += cw * ((gs + t * st * st) * d * d + 2.0 * t * sa * st * d * x2 + ga * x2 * x2)
    return (fa, f1, -lever * fa, h * jaa, h * ja1, -h * lever * jaa, h * j11,
            -h * lever * ja1, h * lever * lever * jaa)


ROW_CARRY = needle_row.ROW_CARRY
needle_lag = inline(needle_row.needle_lag)


@inline
def row_stroke(Y, P, theta, ax):
    """The trunnion's axial stroke (Eq. 7, joint angle theta [rad]) relative to the roller [m]:
    less its slide and its offset e along the trunnion axis (whose x component is ax)."""
    return trunnion_axial(Y[Y_X], theta, P[P_S], P[P_AXIAL] > 0.5) - Y[Y_U] - Y[Y_E] * ax


@inline
def row_play(P, x, w, theta, stroke):
    """Lumped row: how far its needles lag the trunnion [m] (needle_row.needle_lag, their play
    needle_axial_clearance) at whirl angle x [rad] turning at w [rad/s], joint angle theta
    [rad] and the trunnion's stroke relative to the roller `stroke` [m] (row_stroke), and the
    share of the roller's slip on the trunnion that their bore contact takes: ROW_SERIES, or 1
    where a stop carries them.  The stroke's ends are at x = 0 and pi/2, +-E = +-s (1 - cos
    theta) / (2 cos theta); w's sign says which it passed last.  The lag is that of a whirl
    that has run a cycle in one sense (docs/model.md, "The needles' play")."""
    c = math.cos(theta)
    E = P[P_S] * (1.0 - c) / (2.0 * c) if P[P_AXIAL] > 0.5 else 0.0
    rising = trunnion_axial_rate(x, theta, P[P_S], True) * w >= 0.0
    lag, stop = needle_lag(stroke, E, P[P_NEEDLE_AXIAL_CLEARANCE], rising)
    return lag, (1.0 if stop else ROW_SERIES)


@inline
def row_load_moment(P, Fr, stroke, lag):
    """Lumped row: the moment [N m] about e2 of its radial load F_r [N] acting off the roller's
    centre, at the loaded needles' mean place along the trunnion: the trunnion's stroke
    relative to the roller (row_stroke) less the needles' lag behind it (row_play) [m], the
    whole stroke with the row's friction off, the needles then riding the stops (docs/model.md,
    "Why the resolved row rocks more")."""
    return Fr * (stroke - lag if P[P_FRICTION_NEEDLE] > 0.5 else stroke)


@inline
def row_lever(P, Fr, q):
    """Lumped row: where along the pressing direction e1 its loaded needles meet the roller
    bore on average [m], r_bore times the load-weighted cosine of their angle, F_r / q (F_r the
    row's radial force on the roller [N]: > 0 in drive, the needles on the +e1 side; < 0 in
    coast; q the sum of the needle loads [N])."""
    return P[P_R_BORE] * Fr / q if q > 0.0 else 0.0


@inline
def row_rolling_resistance(P, q, om, spin, h):
    """Lumped row: Eq. (12)'s rolling force mu_r per needle load, acting on the bore (radius
    r_bore) against the roller's spin om relative to the trunnion's [rad/s]: its moment
    [N m] under the needle loads q [N], and h [s] times its slope [N m s/rad / s]."""
    vr = (om - spin) * P[P_R_BORE]
    g = tanh_clipped(3.0 * vr / P[P_VST_OP])
    return (P[P_MU_ROLLING] * q * P[P_R_BORE] * g,
            h * P[P_MU_ROLLING] * q * P[P_R_BORE] ** 2 * 3.0 / P[P_VST_OP] * (1.0 - g * g))


@inline
def row_stiffness(P, kr, kw):
    """Lumped row: its tangent stiffness across the load kw [N/m] and in tilt about e1, e2
    kt1, kt2 [N m/rad] from the radial ones along and across the load kr, kw [N/m] (row_load;
    line contacts of length l: tilt = radial x l^2/12)."""
    return kw, kw * P[P_LT], kr * P[P_LT]


@inline
def groove_stiffness_x(P, res, c):
    """Tangent stiffness [N/m] of the groove's Hertz contact along x: d f_n / d delta (Eq. 10,
    n = 3/2) times n_x^2, the roller's centre at c [m]."""
    cx, cy = c[0], c[1]
    dx = cx - flank_centre(P, cx)
    delta = math.sqrt(dx * dx + cy * cy) + P[P_R_ROLLER] - P[P_R_GROOVE]
    if delta > 0.0:
        return 1.5 * res[R_FN] / delta * res[R_NX] * res[R_NX]
    return 0.0


@inline
def row_damping(P, k, mass):
    """Damping [N s/m, N m s] of a mode of stiffness k [N/m, N m] and mass [kg, kg m^2] on the
    lumped row: 2 zeta sqrt(k mass), zeta = row_damping (the lumped form of the resolved row's
    needle-contact damping, docs/model.md)."""
    return 2.0 * P[P_ROW_DAMPING] * math.sqrt(k * mass)
