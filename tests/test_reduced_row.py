"""The reduced traverse model with the needle row (needle_row = true, reduced_model/equations.py:
row_point, row_step): the same equations solved independently, its limit where the row cannot
rock, the slide stepped in time against the settled table, and the row's own law shared with
the contact model's lumped row."""
import math

import numpy as np
import pytest

from reduced_model import needle_row as NR
from reduced_model import scene as S
from reduced_model.analytic_kernel import INPUT_NAMES
from reduced_model.analytic_model import AnalyticModel
from reduced_model.orders import last_cycle_orders, order_component
from reduced_model.scene import defaults
from reduced_model.traverse import Traverse


def _table_orders(**over):
    """Orders 1 and 3 of Fz [N] (complex) of the settled table of one roller at 10 Hz."""
    from benchmarks.needle_mechanism import phasor
    sc = S.validate(dict({"omega": 20 * math.pi, "needle_row": True}, **over), "analytic")
    fz = np.asarray(Traverse(sc).Fz[:-1])
    return {k: phasor(order_component(fz, k)) for k in (1, 3)}


@pytest.mark.parametrize("deg,F", [(8.0, 45000.0), (8.0, 4500.0)], ids=["launch", "paper"])
def test_the_kernel_and_an_independent_march_agree(deg, F):
    """benchmarks/reduced_row.py marches the same equations four cycles from rest with scipy's
    fsolve on (slip, tilt) and T3 inverted at each point; the kernel solves the periodic cycle by
    Newton on the slip vector and the tilt.  Both discretize alike (360 steps a cycle), and
    each solve converges to 1e-9 of v_st or better: orders 1 and 3 agree within 1e-5
    (measured 6e-9 and 6e-8)."""
    from benchmarks.reduced_row import reduced_orders
    th = math.radians(deg)
    march = reduced_orders(S.validate({"theta": th, "F_press": F, "omega": 20 * math.pi},
                                      "contact"), True, True, True, True)
    table = _table_orders(theta=th, F_press=F)
    for k in (1, 3):
        assert abs(march[k] - table[k]) <= 1e-5 * abs(table[k]), k


def test_a_row_that_cannot_rock_nor_rub_is_the_ideal_bearing():
    """The needles' friction and rolling resistance off and the row's tilt stiffness about 470
    times the default's (needles of 0.1 m: k_t2 = k_r l^2 / 12 with k_r ~ l^(8/9)): what is
    left of the row (the tilt under the groove's friction and the row's load) moves the
    groove contact by 1/470 of what the default row does, so the orders are the ideal
    bearing's within 0.5 % (the default row moves order 1 by 36-43 % at these loads)."""
    for F in (4500.0, 45000.0):
        over = dict(theta=math.radians(8.0), F_press=F)
        stiff = _table_orders(friction_needle=False, rolling_resistance=False, l_needle=0.1,
                              **over)
        ideal = _table_orders(needle_row=False, **over)
        default = _table_orders(**over)
        for k in (1, 3):
            assert abs(stiff[k] - ideal[k]) <= 5e-3 * abs(ideal[k]), (F, k)
        assert abs(default[1] - ideal[1]) >= 0.2 * abs(ideal[1])


def test_the_slide_stepped_in_time_follows_the_table():
    """Held inputs moved once by a part in 1e9 after a cycle hand the slide from the settled
    table to the march (T4 by the trapezoidal rule at the communication step, the tilt by
    backward Euler) from where the table had it: the next cycle's orders 1 and 3 of Fz agree
    with the table's within 1 %, and nothing jumps at the hand-over (within 2 % of the order 3
    amplitude).  The two step at 1e-4 s and 2.8e-4 s, and backward Euler's tilt rate is first
    order in the step: they part by 0.3-0.65 % (measured at 4.5 and 45 kN; the ideal
    bearing's table and march by 0.04-0.06 %)."""
    v = dict(defaults("analytic"), theta=math.radians(8.0), F_press=45000.0, needle_row=True)
    m = AnalyticModel(v)
    inp = [v[n] for n in INPUT_NAMES]
    dt, n = 1e-4, 1100
    t, fz, x = [], [], []
    for k in range(2 * n):
        if k == n:
            inp[INPUT_NAMES.index("theta")] *= 1.0 + 1e-9
        m.step(dt, k * dt, inp)
        o = m.outputs()
        t.append((k + 1) * dt)
        fz.append(o["Fz"])
        x.append(o["whirl_angle"])
    t, fz, x = np.array(t), np.array(fz), np.array(x)
    table = last_cycle_orders(t[:n], fz[:n], x[:n], (1, 3))
    march = last_cycle_orders(t, fz, x, (1, 3))
    for k in (1, 3):
        za, zb = (a * np.exp(1j * math.radians(p)) for a, p in (table[k], march[k]))
        assert abs(za - zb) <= 1e-2 * abs(za), k
    jumps = np.abs(np.diff(fz[n - 5:n + 5]))
    assert jumps.max() <= jumps[:4].max() + 0.02 * table[3][0]


def test_the_row_law_is_the_lumped_rows():
    """needle_row.sum_row at the offset row_offset finds carries the load asked (to 1e-12),
    the same offset from scratch or from the one at a load 30 % off; for a row without
    clearance its load is row_constants' K_row g^(10/9) (every needle of the loaded half
    squeezed by g cos(psi_j), Eq. 17): the law the lumped row and the reduced model share."""
    c1, k_row, q_sum = NR.row_constants(46, 0.012)
    for F in (300.0, 4500.0, 45000.0):
        a = NR.row_offset(1e-5, 46, c1, k_row, F, 0.0, 0.0)
        Fr, kr, kw, q, _qs = NR.sum_row(1e-5, 46, c1, a)
        assert Fr == pytest.approx(F, rel=1e-12)
        # started from the offset at a load 30 % off (the march's step before), the same root
        for near in (0.7 * F, 1.3 * F):
            a_near = NR.row_offset(1e-5, 46, c1, k_row, near, 0.0, 0.0)
            assert NR.row_offset(1e-5, 46, c1, k_row, F, a_near, near) == pytest.approx(
                a, rel=1e-13)
        assert q > Fr and kr > 0 and kw > 0
        g = 2e-6 * F / 4500.0
        Fr0, _kr, _kw, q0, _qs = NR.sum_row(0.0, 46, c1, g)
        assert Fr0 == pytest.approx(k_row * g ** (10.0 / 9.0), rel=1e-12)
        assert q0 == pytest.approx(q_sum * Fr0, rel=1e-12)


@pytest.mark.parametrize("deg", [3.0, 8.0, 15.0, 25.0])
def test_the_needles_lag_is_a_play_operator_on_the_stroke(deg):
    """needle_row.needle_lag, closed-form over the stroke's cycle, against the play operator
    stepped along a sampled cycle of Eq. (7)'s stroke (the lag follows the rest, 1 - ROW_CARRY,
    of each step's travel and is clipped to the play, from a centred start, the cycle run twice:
    a stroke within the play keeps the start, one beyond it forgets it): equal within the stepping's own error, the rest of one step's travel; at a
    stop exactly where the stepped lag sits on the play.  The paper's joint (s = 22 mm) and
    play (0.1 mm): the stroke's half travel E is 15 um at 3 deg and 108 um at 8 deg (never at
    a stop: the rest of the whole stroke fits in the play below 10.8 deg), 388 um at 15 deg
    and 1.14 mm at 25 deg."""
    s, play, k = 0.022, 1e-4, 1.0 - NR.ROW_CARRY
    th = math.radians(deg)
    E = s * (1.0 - math.cos(th)) / (2.0 * math.cos(th))
    x = np.linspace(0.0, 2.0 * math.pi, 20001)[:-1]
    c = E / s * np.sin(2.0 * x)
    stroke = s - (E * np.cos(2.0 * x) + s * np.sqrt(1.0 - c * c))          # Eq. (7)
    rising = np.sin(2.0 * x) + c / np.sqrt(1.0 - c * c) * np.cos(2.0 * x) >= 0.0
    step = k * np.abs(np.diff(stroke)).max()
    lag = k * stroke[0]     # centred: the lag of a stroke whose middle is the trunnion's
    for _ in range(2):
        prev = stroke[0]
        stepped = []
        for v in stroke:
            lag = min(play, max(-play, lag + k * (v - prev)))
            prev = v
            stepped.append(lag)
    closed = [NR.needle_lag(v, E, play, bool(r)) for v, r in zip(stroke, rising)]
    lags = np.array([lg for lg, _stop in closed])
    stops = np.array([stop for _lg, stop in closed])
    free = k * E <= play
    if free:   # never at a stop: centred, ROW_CARRY of the way from the stroke's middle
        assert not stops.any()
    else:
        assert stops.any() and not stops.all()
        assert np.all(np.abs(np.abs(lags[stops]) - play) == 0.0)
    assert np.abs(lags - np.array(stepped)).max() <= 2.0 * step + 1e-15


def test_the_lumped_rows_friction_acts_around_the_loaded_arc():
    """contact.row_sliding_friction's two points +-row_arc across the pressing direction: in the
    tanh law's linear range the moment about e1 they make against a tilt rate b1' is the row's
    own, mu k b1' (sum_j q_j x2_j^2 + q <y^2>), summed here needle by needle (Eq. 17 loads at
    psi_j, x2_j = r_bore sin psi_j; <y^2> over the line's seven points), and a slide alone
    meets one tanh law, mu q tanh(k s), as at one point.  Both to rounding (1e-12)."""
    from tripod_model import contact, layout as K
    from tripod_model.model import ContactModel
    m = ContactModel({"bearing": 1})
    m.step(1e-4, 0.14, 62.8, 45000.0)
    P = m.P
    n, c, c1, rb = int(P[K.P_NROW]), P[K.P_NEEDLE_CLEARANCE], P[K.P_KN1], P[K.P_R_BORE]
    a = NR.row_offset(c, n, c1, NR.row_constants(n, math.sqrt(12.0 * P[K.P_LT]))[1], 45000.0,
                      0.0, 0.0)
    Fr, _kr, _kw, q, arc = contact.row_load(P, -a)
    psi = 2.0 * math.pi * np.arange(n) / n
    squeeze = np.clip(a * np.cos(psi) - c, 0.0, None)
    qj = c1 * squeeze ** (10.0 / 9.0)
    assert q == pytest.approx(qj.sum(), rel=1e-12)
    series = contact.ROW_SERIES                      # half the slip at the bore
    k = series * 3.0 / P[K.P_VST_OP]
    mu, l = P[K.P_MU_NEEDLE], math.sqrt(12.0 * P[K.P_LT])
    y = l * ((np.arange(7) + 0.5) / 7 - 0.5)
    lever = contact.row_lever(P, Fr, q)
    b1d = 1e-12 * P[K.P_VST_OP] / rb                # k x2 b1' about 1e-12: linear
    f = contact.row_sliding_friction(P, q, 0.0, 0.0, b1d, 0.0, lever, arc, 0.0, series)
    want = mu * k * b1d * ((qj * (rb * np.sin(psi)) ** 2).sum() + q * (y * y).mean())
    assert f[1] == pytest.approx(want, rel=1e-12)
    assert arc > 0.3 * rb                            # the load fans out well off e1 at 45 kN
    s = 0.7 * P[K.P_VST_OP]
    f = contact.row_sliding_friction(P, q, s, 0.0, 0.0, 0.0, lever, arc, 0.0, series)
    assert f[0] == pytest.approx(mu * q * math.tanh(k * s), rel=1e-12)


def test_the_reduced_rows_line_takes_the_arcs_two_sides():
    """equations.row_line with the needles' line shrunk to a point (O_LN = 0): the two sides of
    the loaded arc meet the slide u less and plus O_ARC b1', each with half the load,
    mu q (tanh(k (u + x b1')) + tanh(k (u - x b1'))) / 2, to rounding."""
    from reduced_model import equations as E
    O = np.zeros(E.O_LEN)
    O[E.O_MQ], O[E.O_ARC], O[E.O_LN] = 3000.0, 6e-3, 0.0
    kr, u, b1d = 300.0, 2e-3, 0.5
    f, _df = E.row_line(O, u, b1d, kr)
    x = O[E.O_ARC] * b1d
    assert f == pytest.approx(1500.0 * (math.tanh(kr * (u + x)) + math.tanh(kr * (u - x))),
                              rel=1e-12)


@pytest.mark.parametrize("F", [1000.0, 45000.0])
def test_t5_with_the_row_has_one_root_from_any_start(F):
    """equations.normal_force (T5 with the row in series) started from a nearby f_n, from far
    above the load where the contact opens (f_n beyond rho_c k_r / h: the start is refused and
    Newton starts from F) and from F itself lands on one root, and that root solves T5 to
    rounding: K ((rho_c - (f_n h - F) / k_r) / sqrt(1 - p^2) - clearance)^1.5 = f_n."""
    from reduced_model import equations as E
    from reduced_model import analytic_kernel as K
    m = AnalyticModel({"F_press": F})
    O = m.X[K.X_OP:K.X_OP + K.O_LEN].copy()
    assert O[E.O_KRR] > 0.0                      # the row is in series
    for p in (0.0, 0.05, -0.08):
        ref = E.normal_force(O, p)
        for start in (0.9 * ref, 1.1 * ref, 1e12):
            assert E.normal_force(O, p, start) == pytest.approx(ref, rel=1e-12)
        c = math.sqrt(1.0 - p * p)
        h = E.row_carried(O, p) * O[E.O_F]
        d = (O[E.O_RHO] - (ref * h - O[E.O_F]) / O[E.O_KRR]) / c - O[E.O_CLEAR]
        assert O[E.O_K] * d ** 1.5 == pytest.approx(ref, rel=1e-12)
