"""Driving motions of the contact model: the trunnion's line (pitch, roll, Eqs. 1, 5, 18), its
axial travel and yaw (Eqs. 3, 7) with their time derivatives, and the roller's motion on it.

Frame (model.md): groove fixed, groove axis = z axis through the origin, x = pressing
direction, y = trunnion axis (nominal).
"""
import math

from .jit import inline, njit
from .layout import (BEAR_IDEAL, L_AAX, L_AAY, L_AAZ, L_ADX, L_ADY, L_ADZ, L_AX, L_AY, L_AZ, L_KTH, L_KVP, L_KW,
    L_KX, L_QZ, L_QZD, L_QZDD, L_SPIN, L_VAX, P_AXIAL, P_BEAR, P_PITCH, P_ROLL, P_S, P_VP,
    P_YAW, Y_B1D, Y_B2D, Y_E, Y_ED, Y_OM, Y_U, Y_UD, Y_W, Y_WD)


HX = 2e-4   # whirl-angle step for finite-difference derivatives of the driving motions [rad]


@njit
def trunnion_line(x, theta, s, pitch, roll):
    """Trunnion axis at whirl angle x: point Q on it at the groove's mid-plane and direction a.

    Pitching about x through the spider centre, Eq. (1): the axis meets the plane y = 0 at
    z = s tan(phi) (Eq. 18).  Rolling, Eq. (5), turns the axis about -z through that point
    (sense chosen so that the slip on the loaded +x flank is V = v1 + v2, model.md).
    Returns (Qz, ax, ay, az); Q = (x0, 0, Qz) with x0 the pressing offset.
    """
    return _line_at(x, math.tan(theta), _roll_ratio(theta), s, pitch, roll)


@inline
def _roll_ratio(theta):
    """e / s of the roll, Eq. (5): the trunnion's eccentricity over the spider radius."""
    return (1.0 - math.cos(theta)) / (2.0 * math.cos(theta))


@inline
def _line_at(x, T, k, s, pitch, roll):
    """trunnion_line with T = tan(theta) and k = _roll_ratio(theta) given (line_kinematics
    evaluates the line at three angles of one theta)."""
    phi = math.atan(T * math.sin(x)) if pitch else 0.0
    xi = 0.0
    if roll:
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
def line_kinematics(x, w, theta, P, L):
    """Q, a and their first and second time derivatives at whirl angle x, whirl rate w.

    out[0:3] a, [3:6] da/dt, [6:9] d2a/dt2, [9] Qz, [10] dQz/dt (with the plunge speed
    P[P_VP]: the spider's travel along the groove), [11] d2Qz/dt2,
    [12] trunnion material velocity along its axis (dd/dt), [13] trunnion spin rate about a,
    [14:18] the (x, w, theta, plunge speed) they were computed for (a one-entry cache; NaN =
    empty).  Central differences in x (step HX), chain rule with constant w within a substep.
    """
    vp = P[P_VP]
    if L[L_KX] == x and L[L_KW] == w and L[L_KTH] == theta and L[L_KVP] == vp:
        return   # same whirl angle as the last call (the extrapolated step visits x + h twice)
    L[L_KX] = x
    L[L_KW] = w
    L[L_KTH] = theta
    L[L_KVP] = vp
    s = P[P_S]
    pitch = P[P_PITCH] > 0.5
    roll = P[P_ROLL] > 0.5
    T, k = math.tan(theta), _roll_ratio(theta)
    q0, a0x, a0y, a0z = _line_at(x, T, k, s, pitch, roll)
    qp, apx, apy, apz = _line_at(x + HX, T, k, s, pitch, roll)
    qm, amx, amy, amz = _line_at(x - HX, T, k, s, pitch, roll)
    i1 = w / (2.0 * HX)
    i2 = w * w / (HX * HX)
    L[L_AX] = a0x
    L[L_AY] = a0y
    L[L_AZ] = a0z
    L[L_ADX] = (apx - amx) * i1
    L[L_ADY] = (apy - amy) * i1
    L[L_ADZ] = (apz - amz) * i1
    L[L_AAX] = (apx - 2.0 * a0x + amx) * i2
    L[L_AAY] = (apy - 2.0 * a0y + amy) * i2
    L[L_AAZ] = (apz - 2.0 * a0z + amz) * i2
    L[L_QZ] = q0
    L[L_QZD] = (qp - qm) * i1
    if vp != 0.0:
        L[L_QZD] += vp
    L[L_QZDD] = (qp - 2.0 * q0 + qm) * i2
    if P[P_BEAR] != BEAR_IDEAL:   # the trunnion's own slide and spin matter only to the needles
        ax = P[P_AXIAL] > 0.5
        L[L_VAX] = (trunnion_axial(x + HX, theta, s, ax) - trunnion_axial(x - HX, theta, s, ax)) * i1
        yw = P[P_YAW] > 0.5
        L[L_SPIN] = (trunnion_yaw(x + HX, theta, yw) - trunnion_yaw(x - HX, theta, yw)) * i1
    else:
        L[L_VAX] = 0.0
        L[L_SPIN] = 0.0


@njit
def roller_motion(Y, x0, L, lumped):
    """Roller centre c [m], its velocity v [m/s] and angular velocity w [rad/s] from the state
    and the trunnion line L, plus the row axes e1 (pressing direction normal to the trunnion
    axis) and e2 = a x e1 (zero with the ideal bearing, whose extra freedoms are locked); each
    an (x, y, z) tuple.

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
