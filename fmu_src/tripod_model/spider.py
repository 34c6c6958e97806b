"""The floating spider (spider = 1): the joint's three rollers on one rigid spider whose centre
and twist come from the forces instead of Eqs. (1)-(8) (docs/model.md, "The floating spider").

The spider's coordinates q = (dX, dY, psi) are its pose off the kinematic one: its centre off
Eq. (5)'s orbit in the housing frame [m] and its twist about the shaft axis in the drive sense
[rad].  Each trunnion's line is the prescribed one moved by q (first order in q: micrometres
against millimetres of the motions themselves): its pressing offset x0_i = g_i . q
(pressing_map); the rollers step on it as on a prescribed line.  The spider steps after them,
linearly implicit in the rollers' pressing stiffness (a partitioned step, one substep behind):

    M q'' = sum_i Q_i + (0, 0, T) - m_s a_orbit,

Q_i the generalized force of roller i's bearing on its trunnion (trunnion_force), T the input
torque [N m], a_orbit the orbit's own acceleration (9 w^2 toward the shaft axis: Eq. (5)'s orbit
at 2w in the housing, which turns at w).  With the ideal bearing the rollers' masses move with
the trunnions across the groove and join M.

Housing frame (reduced_model/housing.py): Z the shaft axis, groove i at angle a_i = 2 pi i / 3,
its trunnion axis y_i = (cos a_i, sin a_i), its pressing direction x_i = (sin a_i, -cos a_i).
"""
import math

from . import layout as K
from .contact import groove_contact, groove_stiffness_x, line_kinematics, roller_motion, row_load
from .contact import row_damping, row_lever, row_play, row_sliding_friction, row_stroke
from reduced_model.housing import spider_orbit
from .jit import inline, njit

_C3 = (1.0, math.cos(2.0 * math.pi / 3.0), math.cos(4.0 * math.pi / 3.0))
_S3 = (0.0, math.sin(2.0 * math.pi / 3.0), math.sin(4.0 * math.pi / 3.0))


# Eq. (5)'s orbit (reduced_model/housing.py: plain Python, for the model without numba)
orbit = njit(spider_orbit)


@inline
def twist_arm(s, theta, x, u, ay, ax, az, Qz):
    """The displacement of roller i's trunnion point per unit twist [m/rad], in its groove's
    frame: -n x p, n the shaft axis (n = (sin theta cos x, -sin theta sin x, cos theta) at the
    roller's whirl angle x [rad]), p the roller centre from the spider centre (the slide u [m]
    along the axis a = (ax, ay, az), Qz [m] the line's travel along the groove)."""
    e = s * (1.0 - math.cos(theta)) / (2.0 * math.cos(theta))
    st = math.sin(theta)
    nx, ny, nz = st * math.cos(x), -st * math.sin(x), math.cos(theta)
    px = e * math.sin(2.0 * x) + u * ax
    py = s - e * math.cos(2.0 * x) + u * ay
    pz = Qz + u * az
    return -(ny * pz - nz * py), -(nz * px - nx * pz), -(nx * py - ny * px)


@inline
def pressing_map(i, ax, ay, d):
    """g_i: roller i's pressing offset per unit of q = (dX, dY, psi): the trunnion line moved
    across its groove (along y_i it slides along itself, which moves its point in the groove's
    mid-plane by -ax/ay), d the twist's displacement (twist_arm)."""
    t = ax / ay
    return _S3[i] - t * _C3[i], -_C3[i] - t * _S3[i], d[0] - t * d[1]


@inline
def trunnion_force(Y, P, x0, rate, drive, W):
    """The force of roller i on its trunnion [N] in its groove's frame at the state Y, the
    trunnion's pressing offset x0 [m] moving at rate [m/s], and its pressing stiffness [N/m].
    Ideal bearing: the groove's force through the roller (its pressing and thrust components;
    the radial one that keeps the force normal to the axis, which the free slide cannot carry),
    less the roller's inertia along the groove.  Lumped: the row's forces reversed (radial,
    across the load) and the needles' sliding friction along the axis."""
    L, res = W.L, W.res
    lumped = P[K.P_BEARING] == K.BEAR_LUMPED
    line_kinematics(Y[K.Y_X], drive.w, drive.theta, P, L)
    c, v, wr, e1, e2 = roller_motion(Y, x0, rate, L, lumped)
    groove_contact(c, v, wr, P, res)
    ax, ay, az = L[K.L_AX], L[K.L_AY], L[K.L_AZ]
    if not lumped:
        fx = res[K.R_FX]
        fz = res[K.R_FZ] - P[K.P_M_ROLLER] * L[K.L_QZDD]
        return fx, -(fx * ax + fz * az) / ay, fz, groove_stiffness_x(P, res, c)
    Fr, kr, kw, q, arc = row_load(P, Y[K.Y_E])
    lever = row_lever(P, Fr, q)
    # the radial damping the roller's step puts between it and the trunnion (kernel's lumped
    # radial step: the row's and the groove's stiffness together)
    m = P[K.P_M_ROLLER]
    Fr -= row_damping(P, kr + groove_stiffness_x(P, res, c), m) * Y[K.Y_ED]
    Fw = -kw * Y[K.Y_W] - row_damping(P, kw, m) * Y[K.Y_WD]
    fa = 0.0
    if P[K.P_FRICTION_NEEDLE] > 0.5 and q > 0.0:
        series = row_play(P, Y[K.Y_X], drive.w, drive.theta, row_stroke(Y, P, drive.theta, ax))[1]
        fa = row_sliding_friction(P, q, Y[K.Y_UD], L[K.L_VAX], Y[K.Y_B1D], Y[K.Y_B2D],
                                  lever, arc, 0.0, series)[0]
    e1x, e1y, e1z = e1
    e2x, e2y, e2z = e2
    return (-(Fr * e1x + Fw * e2x) + fa * ax, -(Fr * e1y + Fw * e2y) + fa * ay,
            -(Fr * e1z + Fw * e2z) + fa * az, kr)


@inline
def generalized(i, f, d):
    """Roller i's trunnion force f (trunnion_force's first three, groove frame [N]) as the
    spider's generalized force (X, Y [N], psi [N m]): across the shaft in the housing frame,
    and its work per unit twist along d (twist_arm)."""
    fx, fy, fz = f[0], f[1], f[2]
    return (fx * _S3[i] + fy * _C3[i], -fx * _C3[i] + fy * _S3[i],
            fx * d[0] + fy * d[1] + fz * d[2])


@inline
def solve_sym3(a00, a01, a02, a11, a12, a22, b0, b1, b2):
    """x of A x = b, A symmetric 3 x 3 (its upper triangle), by its adjugate (A = M + h^2 K:
    symmetric positive definite)."""
    c00 = a11 * a22 - a12 * a12
    c01 = a02 * a12 - a01 * a22
    c02 = a01 * a12 - a02 * a11
    c11 = a00 * a22 - a02 * a02
    c12 = a01 * a02 - a00 * a12
    c22 = a00 * a11 - a01 * a01
    det = a00 * c00 + a01 * c01 + a02 * c02
    return ((c00 * b0 + c01 * b1 + c02 * b2) / det, (c01 * b0 + c11 * b1 + c12 * b2) / det,
            (c02 * b0 + c12 * b1 + c22 * b2) / det)


@inline
def add_outer(a, k, g):
    """a + k g g^T, a and the result the upper triangle (a00, a01, a02, a11, a12, a22)."""
    return (a[0] + k * g[0] * g[0], a[1] + k * g[0] * g[1], a[2] + k * g[0] * g[2],
            a[3] + k * g[1] * g[1], a[4] + k * g[1] * g[2], a[5] + k * g[2] * g[2])


@inline
def spider_update(q, v, F, A, h, T, P0, theta, w, x):
    """One linearly implicit Euler substep of h [s] on the spider's coordinates q (dX, dY [m],
    psi [rad]) and rates v (arrays of 3, in place): (M + h^2 K) dv = h (F + (0, 0, T) - m_s
    a_orbit), F the generalized force at the positions the rollers stepped to (q + h v, their
    drive), A the upper triangle of M + h^2 K without the spider's own mass and inertia; T the
    input torque [N m], x roller 1's whirl angle [rad], w the whirl rate [rad/s]."""
    ms = P0[K.P_SPIDER_MASS]
    ox, oy = orbit(P0[K.P_S], theta, x)
    c = 9.0 * w * w * ms       # the orbit's acceleration is -9 w^2 (ox, oy)
    d0, d1, d2 = solve_sym3(A[0] + ms, A[1], A[2], A[3] + ms, A[4], A[5] + P0[K.P_SPIDER_INERTIA],
                            h * (F[0] + c * ox), h * (F[1] + c * oy), h * (F[2] + T))
    v[0] += d0
    v[1] += d1
    v[2] += d2
    q[0] += h * v[0]
    q[1] += h * v[1]
    q[2] += h * v[2]

