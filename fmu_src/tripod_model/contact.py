"""Contact laws of the contact model, each one equation: Hertz normal force (Eq. 10), tanh
friction (Eq. 11), spin moment (Eqs. 14-16), the roller-groove contact they make, and the lumped
needle row's load (Eq. 17) and damping.

Forces in res are on the roller; the outputs report those on the groove (kernel.run_substeps).
"""
import math

from reduced_model import friction
from .jit import inline, njit
from .layout import (P_A1, P_CLR, P_FLANK, P_FRIC, P_HC, P_K, P_KN, P_KWR, P_LT, P_MU, P_MUN, P_MUR, P_R, P_RB, P_RG,
    P_SPIN, P_VST, P_ZROW, R_FN, R_FX, R_FY, R_FZ, R_G, R_LEN, R_MX, R_MY, R_MZ, R_NX, R_NY,
    R_PX, R_PY, R_PZ, R_SLIP, R_SLOPE, R_VTX, R_VTY, R_VTZ)


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
    r = P[P_R]
    dx = cx - flank_centre(P, cx)             # from the facing flank's arc centre
    rho = math.sqrt(dx * dx + cy * cy)
    nx = dx / rho
    ny = cy / rho
    delta = rho + r - P[P_RG]                 # penetration, model.md
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


@inline
def row_sliding_friction(P, q, ud, vax, h):
    """Lumped row: the needles' sliding friction on the roller's slide along the trunnion
    [N] (mu_needle, tanh law, on the slide rate ud less the trunnion's own vax [m/s]) under
    the needle loads q [N], and h [s] times its slope [N/m] (the implicit step's term)."""
    g = math.tanh(3.0 * (ud - vax) / P[P_VST])
    return P[P_MUN] * q * g, h * P[P_MUN] * q * 3.0 / P[P_VST] * (1.0 - g * g)


@inline
def row_rolling_resistance(P, q, om, spin, h):
    """Lumped row: Eq. (12)'s rolling force mu_r per needle load, acting on the bore (radius
    r_bore) against the roller's spin om relative to the trunnion's [rad/s]: its moment
    [N m] under the needle loads q [N], and h [s] times its slope [N m s/rad / s]."""
    vr = (om - spin) * P[P_RB]
    g = math.tanh(3.0 * vr / P[P_VST])
    return (P[P_MUR] * q * P[P_RB] * g,
            h * P[P_MUR] * q * P[P_RB] ** 2 * 3.0 / P[P_VST] * (1.0 - g * g))


@inline
def row_stiffness(P, kr):
    """Lumped row: its tangent stiffness across the load kw [N/m] and in tilt about e1, e2
    kt1, kt2 [N m/rad] from the radial one kr [N/m] (line contacts of length l: tilt = radial
    x l^2/12)."""
    kw = kr * P[P_KWR]
    kt2 = kr * P[P_LT]
    return kw, kt2 * P[P_KWR], kt2


@inline
def groove_stiffness_x(P, res, c):
    """Tangent stiffness [N/m] of the groove's Hertz contact along x: d f_n / d delta (Eq. 10,
    n = 3/2) times n_x^2, the roller's centre at c [m]."""
    cx, cy = c[0], c[1]
    dx = cx - flank_centre(P, cx)
    delta = math.sqrt(dx * dx + cy * cy) + P[P_R] - P[P_RG]
    if delta > 0.0:
        return 1.5 * res[R_FN] / delta * res[R_NX] * res[R_NX]
    return 0.0


@inline
def row_damping(P, k, mass):
    """Damping [N s/m, N m s] of a mode of stiffness k [N/m, N m] and mass [kg, kg m^2] on the
    lumped row: 2 zeta sqrt(k mass), zeta = row_damping (the lumped form of the resolved row's
    needle-contact damping, docs/model.md)."""
    return 2.0 * P[P_ZROW] * math.sqrt(k * mass)
