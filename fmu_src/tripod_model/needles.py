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

Integration, two ways.  The default (integrator 4, bdf2.bdf2_substep): a linearly implicit
BDF2 step with the roller and every needle in one system: needle_forces with cpl adds the
roller-needle coupling blocks BN (needle rows, the roller's standard velocities; the friction's
from the moments PB, as for neighbouring needles) and leaves every tangent unscaled; the
roller borders the needles' ring (rowsolve.coupled_solve: block Cholesky along the open ring,
ring.chain_forward / chain_backward, and the roller's 6 x 6 Schur complement; a closed ring by
ring.ring_solve_m for seven right-hand sides).  One contact evaluation a substep,
linearized at a predicted state, which converges only because the system is the whole one.
The others (steplib.substep, integrators 0, 1, 3): one contact evaluation per substep gives
every body its forces and its implicit tangent (stiffness, contact damping, friction secant);
the needles step together in the ring (ring.ring_solve), the roller on its own 6 velocities, split
from the needles with its and their tangents scaled so the split matrix dominates the coupled
one (C_ROLLER, C_NEEDLE; contact_tangent).  Either way the implicit step damps the 300 kHz contact
modes of the needles (300 times lighter than the roller) instead of resolving them
(L-stable); the contact damping (needle_normal) takes the rebound out of free needles hitting a
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
from .needle_laws import (C_NEEDLE, C_ROLLER, add_moments, axial_stop_law, bore_gap, bore_law,
    contact_tangent, mirror, moment_block, neighbour_law,
    trunnion_law)

from .layout import (D_BORE, D_FLANGE, D_LEN, D_NEIGH, D_R1, D_R2, D_R3, D_TRUN, N_CS, N_DC, N_F, N_FRIC, N_HW,
    N_LN, N_MN, N_MU, N_MUR, N_N, N_NS, N_RBR, N_RN, N_ROLLR, N_RT, N_ZAX, Y_LEN)


@inline
def _clear_needle(j, Y, NW, g):
    """Clear needle j's system; its inertial force of the moving frame (its origin accelerating
    at g [m/s^2]) and its sphere centres SP (spheres evenly along its axis)."""
    NP, SP, FN, AN, UN, ND, MOM, PM = NW.NP, NW.SP, NW.FN, NW.AN, NW.UN, NW.ND, NW.MOM, NW.PM
    g1, g2, g3 = g
    y0 = Y_LEN
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
# adds what they return to the bodies' systems (contact_tangent).


@inline
def _coupling_block(B, M, d1, d2, d3):
    """A friction coupling block of two bodies from the moments M of the first's arms:
    B -= sum w G(r) G(r + d)^T, d the first's reference point less the second's (M is spent)."""
    for i in range(10):
        M[i] = -M[i]
    moment_block(B, M, d1, d2, d3)


@inline
def _friction_blocks(Y, y0, n, AN, MOM, UN, PM, AR6, MR):
    """The friction parts of the systems from their moments: each needle's own block, each
    neighbour pair's coupling block (UN -= sum w G_j G_jn^T) and the roller's block."""
    for j in range(n):
        mirror(AN[j])
        moment_block(AN[j], MOM[j], 0.0, 0.0, 0.0)
        if PM[j, 0] != 0.0:
            jn = j + 1 if j + 1 < n else 0
            q, qn = y0 + N_F * j, y0 + N_F * jn
            _coupling_block(UN[j], PM[j], Y[q] - Y[qn], Y[q + 1] - Y[qn + 1], Y[q + 2] - Y[qn + 2])
    mirror(AR6)
    moment_block(AR6, MR, 0.0, 0.0, 0.0)


@inline
def _roller_unknowns(RS, e1x, ax, FR, AR):
    """The roller's system in its standard velocities (b in RS[:, 0], A in RS[:, 1:7]) mapped
    to its unknowns of steplib.substep: ud = t3, om = r3, wd = t2, b1d = r1, b2d = r2,
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
    a = (gn[0], gn[1], gn[2], gn[3], gn[4], gn[5])       # in registers (see contact_tangent)
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
    add_moments(M, w, r1, r2, r3)


@inline
def _pair_blocks(Aj, Ajn, U, Mj, Mjn, PMj, d1, d2, d3):
    """A touching pair's blocks from U = S = sum kq g g^T over its contacts (upper triangle,
    g = (n, r x n) in needle j's arms): needle jn's g is T g, T = [[I, 0], [D, I]], D v = d x v,
    d = p_j - p_jn, so Aj += S, Ajn += T S T^T, U <- -S T^T (the coupling, as -sum kq g g_n^T),
    Mj += PMj and Mjn += PMj shifted by d (the friction moments in jn's arms, R = r + d).
    Once a pair instead of once a contact: a pair has up to N_s contacts."""
    mirror(U)
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
    """A needle on its flange or retainer (axial_stop_law) into its system and ND."""
    fz, kz, f = axial_stop_law(p3, v3, d_tr, dd_tr, zax, Cs, mn, h, hk)
    if f > 0.0:
        Fj[2] += fz
        Aj[2, 2] += kz
        NDj[D_FLANGE] += f


@njit
def _coupling_friction(Y, n, BN, PB, o):
    """The friction's coupling blocks, BN[j] -= sum w G(r) G(R)^T from the moments PB[j]
    (the roller's arm R = r + p_j - o, o its centre)."""
    y0 = Y_LEN
    o1, o2, o3 = o
    for j in range(n):
        if PB[j, 0] != 0.0:
            q = y0 + N_F * j
            _coupling_block(BN[j], PB[j], Y[q] - o1, Y[q + 1] - o2, Y[q + 2] - o3)


@njit
def needle_forces(Y, NW, vst, h, hk, cpl, pose, frame, g):
    """Evaluate every needle contact once; fill each needle's system (FN, AN), the needles'
    coupling blocks UN (needle j to j+1) and the roller's system (FR, AR, in the roller's
    unknowns of steplib.substep) for a linearly implicit step of h [s] (h = 0: forces only), and
    ND diagnostics.  pose = (o, vo, ob, wr, d_tr, dd_tr, om_tr) flat; frame = (e1x, ax);
    g = (g1, g2, g3): see the module's docstring; NW: layout.NeedleWork."""
    n = int(NW.NP[N_N])
    _clear_roller(NW.RS, NW.MR)
    for j in range(n):
        _clear_needle(j, Y, NW, g)
    if cpl:
        _clear_coupling(n, NW.BN, NW.PB)
    _contacts(Y, NW, vst, h, hk, cpl, pose)
    _finish_systems(Y, NW, n, cpl, frame, (pose[0], pose[1], pose[2]))


@inline
def _finish_systems(Y, NW, n, cpl, frame, o):
    """After every contact: the friction blocks from their moments, the roller's system in its
    unknowns and, with cpl, the friction's roller-needle coupling blocks."""
    RS = NW.RS
    _friction_blocks(Y, Y_LEN, n, NW.AN, NW.MOM, NW.UN, NW.PM, RS[:, 1:7], NW.MR)
    _roller_unknowns(RS, frame[0], frame[1], NW.FR, NW.AR)
    if cpl:
        _coupling_friction(Y, n, NW.BN, NW.PB, o)


@njit
def _contacts(Y, NW, vst, h, hk, cpl, pose):
    """Every needle's contacts (trunnion, bore, next needle jn, axial stops) into the needles'
    and the roller's systems (RS: b, A in columns 0, 1..6; MR); pose: needle_forces' o .. om_tr."""
    (o1, o2, o3, vo1, vo2, vo3, ob1, ob2, ob3, wr1, wr2, wr3, d_tr, dd_tr, om_tr) = pose
    roller = (o1, o2, o3, vo1, vo2, vo3, wr1, wr2, wr3)
    SP, FN, AN, UN, ND, MOM, PM = NW.SP, NW.FN, NW.AN, NW.UN, NW.ND, NW.MOM, NW.PM
    BN, PB, NP, gn, gn2 = NW.BN, NW.PB, NW.NP, NW.gn, NW.gn2
    bR, AR6, MR = NW.RS[:, 0], NW.RS[:, 1:7], NW.MR
    n, ns = int(NP[N_N]), int(NP[N_NS])
    rn, Rt, Rb, hw, dc, zax = NP[N_RN], NP[N_RT], NP[N_RBR], NP[N_HW], NP[N_DC], NP[N_ZAX]
    Cs, mn, mu, mur, fric = NP[N_CS], NP[N_MN], NP[N_MU], NP[N_MUR], NP[N_FRIC] > 0.5
    rollr = NP[N_ROLLR] > 0.5 and mur > 0.0
    c = (rn, Cs, mn / ns, mu, mur, vst, h, hk)   # one tuple (numba inlines calls of < 30)
    # one system (cpl): no split, so no scaled tangents
    cn, cr_ = (1.0, 1.0) if cpl else (C_NEEDLE, C_ROLLER)
    rt = Rt + rn   # square roots only within these bounds (1e-12 wider, beyond rounding)
    rt2, dc2 = rt * rt * (1.0 + 1e-12), dc * dc * (1.0 + 1e-12)
    for j in range(n):
        q = Y_LEN + N_F * j
        body = (Y[q], Y[q + 1], Y[q + 2], Y[q + 5], Y[q + 6], Y[q + 7], Y[q + 8], Y[q + 9],
                Y[q + 10])
        p1, p2, p3, v3 = body[0], body[1], body[2], body[5]
        jn = j + 1 if j + 1 < n else 0
        qn = Y_LEN + N_F * jn
        Aj, Fj, Mj = AN[j], FN[j], MOM[j]
        pair = False   # j touches jn: UN[j] holds S = sum kq g g^T until _pair_blocks
        for k in range(ns):
            P1, P2, P3 = SP[j, k, 0], SP[j, k, 1], SP[j, k, 2]
            rho2 = P1 * P1 + P2 * P2
            rho = math.sqrt(rho2) if rho2 < rt2 else rt
            delta = rt - rho                                  # trunnion
            if delta > 0.0:
                F1, F2, F3, n1, n2, r1, r2, r3, kp, kq, wi, f, mr, cr = trunnion_law(
                    (P1, P2, P3), rho, delta, body, c, fric, om_tr, dd_tr)
                contact_tangent((F1, F2, F3), (n1, n2, 0.0), (r1, r2, r3), kp, kq, wi, Fj, Aj,
                                Mj, gn)
                if rollr:
                    Fj[5] -= mr
                    Aj[5, 5] += cr
                ND[j, D_TRUN] += f
            q1, q2, q3, rb, delta = bore_gap(P1, P2, P3, o1, o2, o3, ob1, ob2, ob3, hw, Rb, rn)
            if delta > 0.0:                                   # roller bore
                (F1, F2, F3, n1, n2, n3, r1, r2, r3, R1, R2, R3, kn, un, zn, kq, iso, f, mr,
                 cr) = bore_law((P1, P2, P3), (q1, q2, q3), rb, delta, body, roller, c, fric)
                nrm = (n1, n2, n3)
                contact_tangent((F1, F2, F3), nrm, (r1, r2, r3), cn * hk * kn * un, cn * kq,
                                cn * h * iso, Fj, Aj, Mj, gn)
                contact_tangent((-F1, -F2, -F3), nrm, (R1, R2, R3), cr_ * hk * kn * zn,
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
                 f) = neighbour_law((P1, P2, P3), (Q1, Q2, Q3), dist, delta, body,
                                    (Y[qn], Y[qn + 1], Y[qn + 2], Y[qn + 5], Y[qn + 6],
                                     Y[qn + 7], Y[qn + 8], Y[qn + 9], Y[qn + 10]), c, fric)
                # both needles' loads now (jn's: no block, no moments); their blocks once for
                # the pair from S = sum kq g g^T, gathered in UN[j] (_pair_blocks)
                nrm = (n1, n2, n3)
                contact_tangent((F1, F2, F3), nrm, (r1, r2, r3), kp, kq, 0.0, Fj, UN[j], Mj, gn)
                contact_tangent((-F1, -F2, -F3), nrm, (R1, R2, R3), -kp, 0.0, 0.0, FN[jn],
                                AN[jn], MOM[jn], gn2)
                add_moments(PM[j], wi, r1, r2, r3)
                ND[j, D_NEIGH] += f
                ND[jn, D_NEIGH] += f
                pair = True
        if pair:
            _pair_blocks(Aj, AN[jn], UN[j], Mj, MOM[jn], PM[j], p1 - Y[qn], p2 - Y[qn + 1],
                         p3 - Y[qn + 2])
        _axial_stop(Fj, Aj, ND[j], p3, v3, d_tr, dd_tr, zax, Cs, mn, h, hk)


# The one-system step's ring solve (rowsolve.coupled_solve): the ring's matrix is symmetric
# positive definite (masses plus h^2 K + h D + the friction secant's G G^T, all symmetric
# positive semi-definite), so an open ring factors as a block Cholesky L L^T along the chain:
# the roller's Schur complement then needs only the forward sweep (Z = L^-1 B', U = Z^T Z)
# and one back substitution, half the work of eliminating seven columns both ways.
