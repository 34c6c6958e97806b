"""System assembly of one linearly implicit step: the roller's velocity unknowns (ud, om[, wd,
b1d, b2d][, ed]), the friction Jacobian, the bearing's terms (lumped row, or every needle of the
resolved row), and the state update once the increments are solved.
"""
import math

from .jit import inline, njit
from . import ring
from .needles import needle_forces
from .contact import (groove_contact, line_kinematics, roller_motion, row_damping, row_load,
    row_lever, row_load_moment, row_play, row_rolling_resistance, row_sliding_friction,
    row_stiffness, row_stroke,
    spin_moment, trunnion_axial)
from .layout import (INT_EXPLICIT, L_AAX, L_AAY, L_AAZ, L_AX, L_AY, L_AZ, L_KTH, L_KW, L_QZDD,
    L_SPIN, L_VAX,
    P_AXIAL, P_A1, P_FRICTION_NEEDLE, P_INTEGRATOR, P_IS, P_IT, P_M_ROLLER, P_MU_GROOVE, P_QSUM,
    P_R_ROLLER, P_ROLLING_RESISTANCE, P_S, P_SPIN_MOMENT, P_VST_OP, R_FN, R_FX, R_FY, R_FZ, R_G,
    R_MX, R_MY, R_MZ, R_NX, R_NY, R_SLIP, R_SLOPE, R_VTX, R_VTY, R_VTZ, Y_B1, Y_B1D, Y_B2, Y_B2D,
    Y_E, Y_ED, Y_X, Y_LEN, Y_OM, Y_U, Y_UD, Y_W, Y_WD)


@njit
def resolved_forces(Y, P, NW, theta, x, h, L, e1, e2, cpl):
    """Needle-resolved bearing: the roller's pose and velocity and the trunnion's motion in the
    trunnion frame T (axes e1, e2, a), then every needle contact (needles.needle_forces) for a
    step of h [s]: split (each body's system on its own, scaled tangents) or, with cpl, one
    system with the roller-needle coupling blocks, linearized at a predicted state
    (bdf2.bdf2_substep: the stiffness's K v term drops out, hk = 0)."""
    hk = 0.0 if cpl else h
    e1x, e1z, e2z = e1[0], e1[2], e2[2]
    ax, az = L[L_AX], L[L_AZ]
    E, W, u = Y[Y_E], Y[Y_W], Y[Y_U]
    Ed, Wd, ud = Y[Y_ED], Y[Y_WD], Y[Y_UD]
    # roller centre: u a + E x_hat + W e2 from Q; x_hat = e1x e1 + ax a in T
    o1, o2, o3 = E * e1x, W, u + E * ax
    vo1, vo2, vo3 = Ed * e1x, Wd, ud + Ed * ax
    b1, b2 = Y[Y_B1], Y[Y_B2]
    ib = 1.0 / math.sqrt(1.0 + b1 * b1 + b2 * b2)
    d_tr = trunnion_axial(x, theta, P[P_S], P[P_AXIAL] > 0.5)
    g = L[L_QZDD]   # the frame origin Q accelerates along the groove (z) only
    pose = (o1, o2, o3, vo1, vo2, vo3, b2 * ib, -b1 * ib, ib, Y[Y_B1D], Y[Y_B2D], Y[Y_OM],
            d_tr, L[L_VAX], L[L_SPIN])
    # bool(): one compiled needle loop for both steps (a literal True or False would compile
    # the loop once for each)
    needle_forces(Y, NW, P[P_VST_OP], h, hk, bool(cpl), pose, (e1x, ax),
                  (g * e1z, g * e2z, g * az))


@inline
def slip_sensitivities(r, L, res, e1, e2, sixdof, resolved, G, b):
    """Rows of G: the contact slip's sensitivity d v_t / d v_i to each velocity unknown
    (ud, om[, wd, b1d, b2d][, ed]); b: the groove's force and moment on the roller projected
    on them (generalized forces [N, N m]); e1, e2 the row's axes."""
    e1x, e1y, e1z = e1
    e2x, e2y, e2z = e2
    ax, ay, az = L[L_AX], L[L_AY], L[L_AZ]
    fx, fy, fz = res[R_FX], res[R_FY], res[R_FZ]
    mx, my, mz = res[R_MX], res[R_MY], res[R_MZ]
    nx, ny = res[R_NX], res[R_NY]
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
def friction_jacobian(P, h, res, G, nv, A, secant):
    """A = -h J, J the Jacobian of the groove friction (Eq. 11, tanh law) in the unknowns:
    J = -G (slope t t^T + iso (I - t t^T)) G^T with t = v_t/|v_t|, slope the tangent and
    iso = mu f_n g/|v_t| the secant [N s/m]; with ``secant`` the secant along the slip too
    (J = -iso G G^T); zero for the explicit integrator 2."""
    vt = res[R_SLIP]
    fn = res[R_FN]
    if vt > 1e-12:
        iso = P[P_MU_GROOVE] * fn * res[R_G] / vt
        tx, ty, tz = res[R_VTX] / vt, res[R_VTY] / vt, res[R_VTZ] / vt
    else:
        iso = res[R_SLOPE]
        tx, ty, tz = 0.0, 0.0, 0.0
    aniso = 0.0 if secant else res[R_SLOPE] - iso
    if P[P_INTEGRATOR] == INT_EXPLICIT:
        iso = 0.0      # explicit (symplectic) Euler, for comparison: no friction Jacobian
        aniso = 0.0
    for i in range(nv):
        gi_t = G[i, 0] * tx + G[i, 1] * ty + G[i, 2] * tz
        for j in range(nv):
            gj_t = G[j, 0] * tx + G[j, 1] * ty + G[j, 2] * tz
            gg = G[i, 0] * G[j, 0] + G[i, 1] * G[j, 1] + G[i, 2] * G[j, 2]
            A[i, j] = h * (iso * gg + aniso * gi_t * gj_t)      # -h J


@inline
def spin_moment_jacobian(P, h, res, wr, L, e1, e2, nv, A):
    """A += -h J, J the Jacobian of the spin moment (Eq. 16: -M_s(w_n) n, w_n = w . n) in the
    rotational unknowns om, b1d, b2d (axes a, e1, e2; as many as nv holds): J = -s k k^T with
    k_i = n . axis_i and s its secant M_s / w_n [N m s] (the slope at w_n = 0), which, like
    the sliding friction's, cannot overshoot."""
    fn, mu, vst = res[R_FN], P[P_MU_GROOVE], P[P_VST_OP]
    if (P[P_SPIN_MOMENT] < 0.5 or mu <= 0.0 or fn <= 0.0 or vst <= 0.0
            or P[P_INTEGRATOR] == INT_EXPLICIT):
        return
    nx, ny = res[R_NX], res[R_NY]
    wn = wr[0] * nx + wr[1] * ny
    if abs(wn) < 1e-9:   # the slope at 0: tanh(x) / x = 1 - x^2 / 3, exact here
        wn = 1e-9
    s = spin_moment(mu, fn, P[P_A1], wn, vst) / wn
    k1 = L[L_AX] * nx + L[L_AY] * ny
    k3 = e1[0] * nx + e1[1] * ny
    k4 = e2[0] * nx + e2[1] * ny
    A[1, 1] += h * s * k1 * k1
    if nv > 4:     # the tilts b1d, b2d (unknowns 3, 4)
        A[1, 3] += h * s * k1 * k3
        A[3, 1] += h * s * k1 * k3
        A[1, 4] += h * s * k1 * k4
        A[4, 1] += h * s * k1 * k4
        A[3, 3] += h * s * k3 * k3
        A[3, 4] += h * s * k3 * k4
        A[4, 3] += h * s * k3 * k4
        A[4, 4] += h * s * k4 * k4


@inline
def lumped_row_terms(Y, P, L, h, It, drag1, drag2, A, b):
    """Lumped needle row (section 2.4.2) in the implicit step: needle sliding friction on the
    slide, Eq. (12) rolling resistance on the spin, the row's stiffness across the load and in
    tilt, implicit like the friction.  Returns the row's radial load F_r [N] and stiffness
    [N/m] (row_load)."""
    m = P[P_M_ROLLER]
    ud, om = Y[Y_UD], Y[Y_OM]
    Fr, kr, kw, q, arc = row_load(P, Y[Y_E])
    stroke = row_stroke(Y, P, L[L_KTH], L[L_AX])
    lag, series = row_play(P, Y[Y_X], L[L_KW], L[L_KTH], stroke)
    if P[P_FRICTION_NEEDLE] > 0.5 and q > 0.0:
        fu, f1, f2, juu, ju1, ju2, j11, j12, j22 = row_sliding_friction(
            P, q, ud, L[L_VAX], Y[Y_B1D], Y[Y_B2D], row_lever(P, Fr, q), arc, h, series)
        b[0] -= fu
        b[3] -= f1
        b[4] -= f2
        if P[P_INTEGRATOR] != INT_EXPLICIT:
            A[0, 0] += juu
            A[0, 3] += ju1
            A[3, 0] += ju1
            A[0, 4] += ju2
            A[4, 0] += ju2
            A[3, 3] += j11
            A[3, 4] += j12
            A[4, 3] += j12
            A[4, 4] += j22
    if P[P_ROLLING_RESISTANCE] > 0.5 and q > 0.0:
        mr, hk = row_rolling_resistance(P, q, om, L[L_SPIN], h)
        b[1] -= mr
        if P[P_INTEGRATOR] != INT_EXPLICIT:
            A[1, 1] += hk
    kw, kt1, kt2 = row_stiffness(P, kr, kw)
    cw, c1, c2 = row_damping(P, kw, m), row_damping(P, kt1, It), row_damping(P, kt2, It)
    b[2] -= kw * (Y[Y_W] + h * Y[Y_WD]) + cw * Y[Y_WD]
    b[3] -= kt1 * (Y[Y_B1] + h * Y[Y_B1D]) + drag1 + c1 * Y[Y_B1D]
    b[4] -= kt2 * (Y[Y_B2] + h * Y[Y_B2D]) + drag2 + c2 * Y[Y_B2D]
    b[4] += row_load_moment(P, Fr, stroke, lag)
    A[2, 2] += m + h * h * kw + h * cw
    A[3, 3] += It + h * h * kt1 + h * c1
    A[4, 4] += It + h * h * kt2 + h * c2
    return Fr, kr


@inline
def resolved_row_terms(Y, P, NW, theta, x, h, W, axes, kh, drag, cpl):
    """Needle-resolved bearing in the implicit step: the roller's own inertia and the groove's
    radial stiffness kh [N/m], then every needle contact on the roller with its tangent,
    evaluated at the start of the substep (needles and roller step on the same state); axes
    the row's (e1, e2), drag the tilts' drag moments (contact.tilt_drag), cpl as in
    resolved_forces."""
    A, b = W.A, W.b
    drag1, drag2 = drag
    hk = 0.0 if cpl else h
    It = P[P_IT]
    m = P[P_M_ROLLER]
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
        resolved_forces(Y, P, NW, theta, x, h, W.L, axes[0], axes[1], cpl)
        FR, AR = NW.FR, NW.AR
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
            ring.needle_update(Y, Y_LEN, NW, h)


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
def roller_system(Y, P, drive, x, h, W, sixdof, resolved, nv, secant):
    """The roller's own part of a linearly implicit step of h [s] ending at whirl angle x
    [rad]: the groove contact on the state Y, its friction Jacobian in the nv unknowns, the
    masses, the driving acceleration along the axis; ``secant`` (BDF2's choice): the friction's
    secant along the slip too, and the spin moment implicit (spin_moment_jacobian).  Returns
    the roller's centre [m] and the row axes e1, e2."""
    L, res, G, A, b = W.L, W.res, W.G, W.A, W.b
    line_kinematics(x, drive.w, drive.theta, P, L)
    c, v, wr, e1, e2 = roller_motion(Y, drive.x0, drive.x0_rate, L, sixdof)
    groove_contact(c, v, wr, P, res)
    slip_sensitivities(P[P_R_ROLLER], L, res, e1, e2, sixdof, resolved, G, b)
    friction_jacobian(P, h, res, G, nv, A, secant)
    if secant:
        spin_moment_jacobian(P, h, res, wr, L, e1, e2, nv, A)
    m = P[P_M_ROLLER]
    A[0, 0] += m
    A[1, 1] += P[P_IS]
    # driving accelerations seen along the axis: c'' . a = Q''.a + u'' + u a''.a
    b[0] -= m * (L[L_QZDD] * L[L_AZ] + Y[Y_U] * (L[L_AAX] * L[L_AX] + L[L_AAY] * L[L_AY] + L[L_AAZ] * L[L_AZ]))
    return c, e1, e2
