"""A joint on a floating spider (spider = 1) in one call: each substep the three rollers on
the trunnion lines the spider's pose gives (their pressing offsets x0_i = g_i . q moving at
g_i . q'), then the spider on their forces and the input torque; the physics in spider.py
(docs/model.md, "The floating spider").  kernel.step_joint hands a joint to step_free_spider
when P[P_SPIDER] says so; the arrays as step_joint takes them, the spider's state in OP's header
row (layout.OP_SP_*).
"""
import math

from . import layout as K
from . import spider
from .budget import MAX_SUBSTEPS
from .contact import line_kinematics, row_load
from .jit import njit
from .kernel import (advance, inputs_moved, joint_into, joint_operating_points, outputs_into,
                     roller_outputs, spider_into)
from .layout import (BEAR_IDEAL, OP_F, OP_H, OP_N, OP_THETA, OP_TQ, OP_W, OP_X0, OUT_FZ_2,
                     OUT_FZ_3, OUT_FZ_JOINT, Y_X)

SECANT_PASSES = 4   # the spider's step again with a stiffer row, at most (_spider_substep)


@njit
def _row_work(Wn, i):
    """Roller i's work arrays (layout.Work) from the joint's rows."""
    return K.Work(Wn.L[i], Wn.res[i], Wn.Y1[i], Wn.Y2[i], Wn.G[i], Wn.A[i], Wn.b[i], Wn.hs[i],
                  Wn.GW[i])


@njit
def _spider_map(i, Yi, Pi, Wi, theta, w):
    """Roller i's pressing map g_i (spider.pressing_map) at its state Yi and the twist's
    displacement d it is made of (spider.twist_arm): (g, d)."""
    L = Wi.L
    line_kinematics(Yi[Y_X], w, theta, Pi, L)
    d = spider.twist_arm(Pi[K.P_S], theta, Yi[Y_X], Yi[K.Y_U], L[K.L_AY], L[K.L_AX], L[K.L_AZ],
                         L[K.L_QZ])
    return spider.pressing_map(i, L[K.L_AX], L[K.L_AY], d), d


@njit
def _spider_maps(n, Y, P, Wn, theta, w):
    """The rollers' pressing maps at their states now (_spider_map's g, three)."""
    gs = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    for i in range(n):
        g = _spider_map(i, Y[i], P[i], _row_work(Wn, i), theta, w)[0]
        gs = (g if i == 0 else gs[0], g if i == 1 else gs[1], g if i == 2 else gs[2])
    return gs


@njit
def _spider_forces(n, Y, P, Wn, q, v, theta, w, head):
    """The rollers' forces on the spider at their states now, the trunnions at q moving at v:
    the generalized force F (3), the upper triangle of K h-free and of the rollers' masses
    (spider.spider_update's A), and the rollers' pressing maps there (which the next substep
    drives them by): (F, Kg, Mg, gs); the pressing loads into head."""
    F = (0.0, 0.0, 0.0)
    Kg = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    Mg = Kg
    gs = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    ideal = P[0, K.P_BEARING] == BEAR_IDEAL
    for i in range(n):
        Wi = _row_work(Wn, i)
        g, d = _spider_map(i, Y[i], P[i], Wi, theta, w)
        gs = (g if i == 0 else gs[0], g if i == 1 else gs[1], g if i == 2 else gs[2])
        x0 = g[0] * q[0] + g[1] * q[1] + g[2] * q[2]
        rate = g[0] * v[0] + g[1] * v[1] + g[2] * v[2]
        fx, fy, fz, k = spider.trunnion_force(Y[i], P[i], x0, rate, K.Drive(theta, w, x0, rate),
                                              Wi)
        Q = spider.generalized(i, (fx, fy, fz), d)
        F = (F[0] + Q[0], F[1] + Q[1], F[2] + Q[2])
        Kg = spider.add_outer(Kg, k, g)
        if ideal:
            Mg = spider.add_outer(Mg, P[i, K.P_M_ROLLER], g)
        head[K.OP_SP_F1 + i] = -fx
    head[K.OP_SP_GX] = F[0]
    head[K.OP_SP_GY] = F[1]
    head[K.OP_SP_GPSI] = F[2]
    return F, Kg, Mg, gs


@njit
def _spider_start(n, gs, x0, q, v):
    """The spider's pose that puts every trunnion at the pressing offset x0 [m] (the
    prescribed joint's at the start's load; g_i . q = x0 for each roller, gs their pressing
    maps: G^T G q = G^T x0), at rest."""
    a = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    b0 = b1 = b2 = 0.0
    for i in range(n):
        g = gs[i]
        a = spider.add_outer(a, 1.0, g)
        b0, b1, b2 = b0 + g[0] * x0, b1 + g[1] * x0, b2 + g[2] * x0
    q[0], q[1], q[2] = spider.solve_sym3(a[0], a[1], a[2], a[3], a[4], a[5], b0, b1, b2)
    v[0] = v[1] = v[2] = 0.0


@njit
def _spider_substep(n, Y, P, Wn, q, v, h, T, theta, w, head, gs):
    """One substep of h [s]: each roller on its trunnion moved by the spider's rate (x0_i =
    g_i . (q + h q'), gs the rollers' pressing maps at their states now), then the spider on
    their forces and the torque T [N m] (spider.spider_update).  With the lumped bearing the
    rollers keep their place when the spider's step moves the trunnions beyond their drive
    (their offset on the row is relative to the trunnion).  Returns (False: a roller ran out of
    its budget, the maps at the substep's end)."""
    for i in range(n):
        Wi = _row_work(Wn, i)
        g = gs[i]
        rate = g[0] * v[0] + g[1] * v[1] + g[2] * v[2]
        x0 = g[0] * q[0] + g[1] * q[1] + g[2] * q[2] + h * rate
        # int(1), not the literal 1: the kernel's advance compiled once for every caller
        if not advance(Y[i], P[i], K.Drive(theta, w, x0, rate), h, int(1), Wi, None):
            return False, gs
    v0, v1, v2 = v[0], v[1], v[2]
    Fg, Kg, Mg, ends = _spider_forces(n, Y, P, Wn, (q[0] + h * v[0], q[1] + h * v[1],
                                              q[2] + h * v[2]), v, theta, w, head)
    A = (Mg[0] + h * h * Kg[0], Mg[1] + h * h * Kg[1], Mg[2] + h * h * Kg[2],
         Mg[3] + h * h * Kg[3], Mg[4] + h * h * Kg[4], Mg[5] + h * h * Kg[5])
    q0, q1, q2 = q[0], q[1], q[2]
    spider.spider_update(q, v, Fg, A, h, T, P[0], theta, w, Y[0, Y_X])
    if P[0, K.P_BEARING] == K.BEAR_LUMPED:
        # a row the step pushes out of its clearance is stiffer than its tangent said: the
        # step again with each row's secant over its move, until none stiffens (an impact
        # across the running clearance, a torque reversal's)
        ku = (row_load(P[0], Y[0, K.Y_E])[1], row_load(P[1], Y[1, K.Y_E])[1],
              row_load(P[2], Y[2, K.Y_E])[1])
        for _ in range(SECANT_PASSES):
            stiffer = False
            for i in range(n):
                g = gs[i]
                de = -h * (g[0] * (v[0] - v0) + g[1] * (v[1] - v1) + g[2] * (v[2] - v2))
                e = Y[i, K.Y_E]
                if de != 0.0:
                    ks = abs(row_load(P[i], e + de)[0] - row_load(P[i], e)[0]) / abs(de)
                    if ks > 2.0 * ku[i]:
                        A = spider.add_outer(A, h * h * (ks - ku[i]), g)
                        ku = (ks if i == 0 else ku[0], ks if i == 1 else ku[1],
                              ks if i == 2 else ku[2])
                        stiffer = True
            if not stiffer:
                break
            q[0], q[1], q[2], v[0], v[1], v[2] = q0, q1, q2, v0, v1, v2
            spider.spider_update(q, v, Fg, A, h, T, P[0], theta, w, Y[0, Y_X])
        dv = (v[0] - v0, v[1] - v1, v[2] - v2)
        for i in range(n):
            g = gs[i]
            dx = g[0] * dv[0] + g[1] * dv[1] + g[2] * dv[2]
            Y[i, K.Y_E] -= h * dx
            Y[i, K.Y_ED] -= dx
            hs = Wn.hs[i]
            if hs[K.H_GA] > 0.0:   # generalized-alpha: its accelerations from the forces
                hs[K.H_GA] = 0.0
    return True, ends


@njit
def _free_outputs(n, Y, P, Wn, q, v, theta, w, F, head, out, dst):
    """The outputs of a joint on a free spider at the step's end (step_joint's and the
    spider's).  Returns step's codes (1, or 2: a non-finite output)."""
    gs = _spider_forces(n, Y, P, Wn, (q[0], q[1], q[2]), v, theta, w, head)[3]
    total = 0.0
    for i in range(n):
        g = gs[i]
        x0 = g[0] * q[0] + g[1] * q[1] + g[2] * q[2]
        roller_outputs(Y[i], P[i], K.Drive(theta, w, x0, 0.0), out[i], _row_work(Wn, i), None)
        total += out[i, K.O_FZ]
    s = P[0, K.P_S]
    if not math.isfinite(total) or not outputs_into(out[0], F, dst):
        return 2
    if not joint_into(out, n, s, F, dst) or not spider_into(out, n, theta, s, F, head, True,
                                                            dst):
        return 2
    dst[OUT_FZ_JOINT] = total
    dst[OUT_FZ_2] = out[1, K.O_FZ]
    dst[OUT_FZ_3] = out[2, K.O_FZ]
    return 1


@njit
def step_free_spider(n, Y, P, OP, Wn, out, dst):
    """A joint of three rollers on a floating spider (spider.py) in one call, as step_joint
    takes its arrays: each substep the rollers step on the trunnion lines the spider's pose
    gives, then the spider on their forces and the input torque (_spider_substep).  The
    spider's state is in OP's header row (OP_SP_*).  Returns step's codes."""
    head = OP[0]
    jump = joint_operating_points(n, P, OP)
    for i in range(n):
        inputs_moved(P[i], Wn.hs[i], jump)
    theta, w, F = OP[1, OP_THETA], OP[1, OP_W], OP[1, OP_F]
    T = head[OP_TQ] if head[OP_TQ] != 0.0 else 3.0 * P[0, K.P_S] * F   # the torque that presses by F
    q = head[K.OP_SP_QX:K.OP_SP_QX + 3]
    v = head[K.OP_SP_VX:K.OP_SP_VX + 3]
    gs = _spider_maps(n, Y, P, Wn, theta, w)
    if head[K.OP_SP_SET] == 0.0:
        _spider_start(n, gs, OP[1, OP_X0], q, v)
        head[K.OP_SP_SET] = 1.0
    h = OP[1, OP_H]
    nsub = 0 if OP[1, K.OP_NOSTEP] > 0.0 else int(OP[1, OP_N])
    if nsub > MAX_SUBSTEPS:   # refused before it starts (budget.py)
        hs = Wn.hs[0]
        hs[K.H_FAIL], hs[K.H_FAIL_DONE], hs[K.H_FAIL_H] = K.FAIL_LONG, h * nsub, h
        return 3
    for _ in range(nsub):
        ok, gs = _spider_substep(n, Y, P, Wn, q, v, h, T, theta, w, head, gs)
        if not ok:
            return 3
    return _free_outputs(n, Y, P, Wn, q, v, theta, w, F, head, out, dst)
