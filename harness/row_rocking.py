"""The roller's rocking on the needle row about e2 (docs/model.md, "The roller rocks on the
row"), measured in process: a run's tilt, slide and the groove's moment about e2, the tilt
stiffness fitted from them, and the axial shift of the row's load along the trunnion, whose
moment adds to the groove's.  benchmarks/row_tilt.py prints the tables; tests/test_row_mechanism.py
holds the mechanisms to their balances.  Where the needles sit along the trunnion against its
stroke (stroke_and_place, play_operator): benchmarks/row_play.py."""
from __future__ import annotations

import math

import numpy as np

from tripod_model import contact, layout as K
from tripod_model.model import ContactModel

FRICTION_OFF = {"friction_needle": False, "rolling_resistance": False}
# the columns of run's rows
(C_T, C_X, C_FZ, C_B2, C_U, C_M2, C_FN, C_FR, C_SHIFT) = range(9)


def groove_moment_e2(m, omega, theta, L):
    """The groove's moment on the roller of ContactModel m about e2 = a x e1 [N m] now (e1 the
    pressing direction x made normal to the trunnion axis a); L (layout's L_ slots) is left
    holding the trunnion's line at m's state."""
    L[K.L_KX] = math.nan
    contact.line_kinematics(m.Y[K.Y_X], omega, theta, m.P, L)
    a = np.array([L[K.L_AX], L[K.L_AY], L[K.L_AZ]])
    e1 = np.array([1.0, 0.0, 0.0]) - a[0] * a
    e2 = np.cross(a, e1 / np.linalg.norm(e1))
    r = m._res
    return float(np.dot([r[K.R_MX], r[K.R_MY], r[K.R_MZ]], e2))


def row_load_shift(m, L):
    """A needle-resolved row's radial load on the roller along e1, F_r1 = sum of the needles'
    [N], and where along the trunnion axis it acts, its needles' centres weighted by their
    bore loads, from the roller's centre, d [m]: its moment about e2 is d F_r1 (e1 x e2 = a).
    L: the trunnion's line at m's state (groove_moment_e2 leaves it)."""
    n = m.n_needle_bodies
    q = K.Y_LEN + K.N_F * np.arange(n)
    load = np.abs(m.NW.ND[:n, K.D_BORE])
    centre = m.Y[K.Y_U] + m.Y[K.Y_E] * L[K.L_AX]       # the roller's along a (resolved_forces)
    d = float((load * m.Y[q + 2]).sum() / load.sum()) - centre
    return float(m.NW.ND[:n, K.D_R1].sum()), d


def lumped_row_shift(m, theta, L):
    """A lumped row's radial load on the roller F_r [N] (contact.row_load) and where along the
    trunnion axis the row puts it, from the roller's centre, d [m]: the trunnion's axial stroke
    (Eq. 7) relative to the roller less the needles' lag behind it (contact.row_play), the whole
    stroke with the row's friction off.  L as in row_load_shift."""
    Y, P = m.Y, m.P
    stroke = contact.row_stroke(Y, P, theta, L[K.L_AX])
    lag = contact.row_play(P, Y[K.Y_X], L[K.L_KW], theta, stroke)[0]
    d = stroke - lag if P[K.P_FRICTION_NEEDLE] > 0.5 else stroke
    return float(contact.row_load(P, Y[K.Y_E])[0]), d


def run(over, tilt_scale, F, theta, omega, cycles=3, dt=1e-4):
    """One run of one roller at the pressing load F [N], joint angle theta [rad] and whirl
    omega [rad/s] (over: parameters besides): per communication step of dt [s] the time [s],
    whirl angle [rad], Fz [N], the tilt b2 about e2 [rad], the slide u along the trunnion [m],
    the groove's moment about e2 [N m], its normal force f_n [N] and the row's radial load
    F_r1 [N] and its axial shift d [m] (row_load_shift, lumped_row_shift; NaN for the ideal
    bearing), as columns C_*.  The lumped row's tilt stiffness is scaled by tilt_scale.
    Returns (rows, r_roller [m], the lumped row's k_r l^2 / 12 at the last offset over
    tilt_scale [N m/rad], the model)."""
    m = ContactModel(dict(over, theta=theta, omega=omega, F_press=F))
    m.P[K.P_LT] *= tilt_scale
    L = np.full(K.L_LEN, np.nan)
    resolved = m.NW is not None
    rows = []
    for _ in range(int(round(cycles * 2 * math.pi / omega / dt))):
        o = m.step(dt, theta, omega, F)
        m2 = groove_moment_e2(m, omega, theta, L)
        if resolved:
            fr, d = row_load_shift(m, L)
        elif m.P[K.P_BEARING] == K.BEAR_LUMPED:
            fr, d = lumped_row_shift(m, theta, L)
        else:
            fr, d = math.nan, math.nan
        rows.append((m.time, m.whirl_angle, o["Fz"], m.Y[K.Y_B2], m.Y[K.Y_U], m2,
                     m._res[K.R_FN], fr, d))
    kr = contact.row_load(m.P, m.Y[K.Y_E])[1]
    return np.array(rows), m.P[K.P_R_ROLLER], kr * m.P[K.P_LT] / tilt_scale, m


def tilt_stiffness(a, shift=False):
    """The tilt stiffness about e2 [N m/rad] fitted over the rows a (run's) as the balance
    k (b2 - b0) = M2 (+ d F_r1 with shift: the row's load acting off the roller's centre), with
    the residual's rms over the moment's: what holds the roller when those are the only moments
    about e2 (the row's friction off)."""
    m = a[:, C_M2] + (a[:, C_SHIFT] * a[:, C_FR] if shift else 0.0)
    A = np.column_stack([a[:, C_B2], np.ones(len(a))])
    c, res, *_ = np.linalg.lstsq(A, m, rcond=None)
    return c[0], math.sqrt(res[0] / len(a)) / m.std()


def stroke_and_place(theta, F, omega, cycles=3, dt=1e-4):
    """A needle-resolved run of one roller (row friction on) at the pressing load F [N], joint
    angle theta [rad], whirl omega [rad/s]: per communication step of dt [s] over the last
    whole cycle of `cycles`, the whirl angle [rad], the trunnion's axial stroke relative to the
    roller [m] (contact.row_stroke) and d, the bore-loaded needles' mean place from the roller's
    centre [m] (row_load_shift); and the needles' axial play [m]."""
    m = ContactModel({"bearing": 2, "theta": theta, "omega": omega, "F_press": F})
    L = np.full(K.L_LEN, np.nan)
    rows = []
    for _ in range(int(round(cycles * 2 * math.pi / omega / dt))):
        m.step(dt, theta, omega, F)
        groove_moment_e2(m, omega, theta, L)       # (leaves the trunnion's line in L)
        _fr, d = row_load_shift(m, L)
        rows.append((m.whirl_angle, contact.row_stroke(m.Y, m.P, theta, L[K.L_AX]), d))
    a = np.array(rows)
    last = a[:, 0] >= a[-1, 0] - 2 * math.pi
    return a[last], m.p["needle_axial_clearance"]


def play_operator(stroke, play, carry=contact.ROW_CARRY, passes=3):
    """d predicted [m]: the needles follow carry of the stroke's changes while their lag behind
    the trunnion stays within +-play, the stop carrying them beyond (periodic: the cycle run
    `passes` times from a centred start, the last kept)."""
    lag, out = (1.0 - carry) * stroke[0], np.empty_like(stroke)
    for _ in range(passes):
        prev = stroke[0]
        for i, s in enumerate(stroke):
            lag = min(play, max(-play, lag + (1.0 - carry) * (s - prev)))
            prev = s
            out[i] = s - lag
    return out


def arc_moments(theta, F, omega, cycles=3, dt=1e-4):
    """The needles' axial friction around the loaded arc (docs/model.md, "The needles' friction
    around the loaded arc"): a needle-resolved run of one roller at the pressing load F [N],
    joint angle theta [rad], whirl omega [rad/s]; per communication step of dt [s] over the
    last whole cycle of `cycles`, the whirl angle [rad], the moment about e1 [N m] of the
    resolved needles' axial friction at the bore, sum x2_j F3_j (x2_j = r_bore sin of needle
    j's angle from e1), and that of the lumped row's law at the resolved roller's motion with
    the line's length left out (contact.row_sliding_friction, P_LT = 0: the arc's part only)."""
    m = ContactModel({"bearing": 2, "theta": theta, "omega": omega, "F_press": F})
    lumped = ContactModel({"bearing": 1, "theta": theta, "omega": omega, "F_press": F})
    lumped.step(dt, theta, omega, F)               # (its parameter vector at this scene)
    P = lumped.P.copy()
    P[K.P_LT] = 0.0
    n = m.n_needle_bodies
    q = K.Y_LEN + K.N_F * np.arange(n)
    rb = m.P[K.P_R_BORE]
    L = np.full(K.L_LEN, np.nan)
    rows = []
    for _ in range(int(round(cycles * 2 * math.pi / omega / dt))):
        m.step(dt, theta, omega, F)
        groove_moment_e2(m, omega, theta, L)       # (leaves the trunnion's line in L)
        Y = m.Y
        x2 = rb * Y[q + 1] / np.hypot(Y[q], Y[q + 1])
        resolved = float((x2 * m.NW.ND[:n, K.D_R3]).sum())
        P[K.P_VST_OP] = m.P[K.P_VST_OP]
        Fr, _kr, _kw, qs, arc = contact.row_load(P, Y[K.Y_E])
        stroke = contact.row_stroke(Y, P, theta, L[K.L_AX])
        series = contact.row_play(P, Y[K.Y_X], omega, theta, stroke)[1]
        f1 = contact.row_sliding_friction(P, qs, Y[K.Y_UD], L[K.L_VAX], Y[K.Y_B1D], Y[K.Y_B2D],
                                          contact.row_lever(P, Fr, qs), arc, 0.0, series)[1]
        rows.append((m.whirl_angle, resolved, -f1))
    a = np.array(rows)
    return a[a[:, 0] >= a[-1, 0] - 2 * math.pi]
