"""The lumped needle row against the needle-resolved row it stands for (docs/model.md, "What
the needle row does to the thrust"): the needle loads it shares, the thrust's orders, and the
roller's rocking on the row."""
import functools
import math

import numpy as np
import pytest

from harness import row_rocking as R
from harness.envelope_grid import JOINTS, analytic_orders, contact_orders, off
from reduced_model.orders import last_cycle_orders
from tripod_model import contact, layout as K, oppoint
from tripod_model.model import ContactModel

THETA, OMEGA = math.radians(8.0), 20 * math.pi
PAPER = next(j for j in JOINTS if j.stem == "paper")   # the defaults' joint


@pytest.mark.parametrize("F", [4500.0, 45000.0])
def test_lumped_row_shares_the_load_as_the_resolved_row(F):
    """Eq. (17) summed over the needles with the clearance at the roller's offset
    (oppoint.row_sums) against the resolved row's own bore loads, summed, over a stretch of a
    cycle: the sum of the needle loads per radial load (1.06 at 4.5 kN, 1.16 at 45 kN; a row
    without clearance shares 1.26 at every load).  Within 1 %: the resolved row's radial load
    moves by about 1 % over the cycle (its Fx), the loads' share by less."""
    m = ContactModel({"bearing": 2, "theta": THETA, "omega": OMEGA, "F_press": F})
    got, want = [], []
    for i in range(300):
        m.step(1e-4, THETA, OMEGA, F)
        if i >= 100:
            ND = m.needle_loads()
            got.append(ND[:, K.D_BORE].sum() / ND[:, K.D_R1].sum())
            f, _k, _kw, q, _qs = oppoint.row_sums(m.P, abs(m.Y[K.Y_E]))
            want.append(q / f)
    assert np.mean(got) == pytest.approx(np.mean(want), rel=0.01)
    assert np.mean(want) < m.P[K.P_QSUM] - 0.05   # not the share without clearance


@pytest.mark.slow   # (two resolved rows: about 30 s)
@pytest.mark.parametrize("F", [4500.0, 45000.0])
def test_both_fast_models_follow_the_resolved_row_at_the_papers_scene_and_a_launch(F):
    """One roller, 8 deg, 10 Hz: order 3 of Fz, complex (amplitude and phase), of the lumped
    row and of the analytic model at its default (its needle row) against the resolved row's:
    within the issue's 3 % at 4.5 kN (300 N m, the paper's kind of load; measured 0.5 % lumped,
    0.3 % analytic) and at 45 kN (3000 N m, a launch; measured 1.9 % and 1.5 %; 4.1 % and 4.1 %
    with the needles' friction at one point, not around the loaded arc); order 1 within 5 %
    (measured 1.8 % and 2.4 % lumped, 2.1 % and 2.7 % analytic).  The resolved row's
    realizations spread by about 0.2 % here; the ideal bearing is 10 % and 19 % off."""
    res, lum = (contact_orders(PAPER, THETA, F, OMEGA, b) for b in (2, 1))
    ana = analytic_orders(PAPER, THETA, F, OMEGA)
    for fast in (lum, ana):
        assert off(fast, res, 3) < 3.0
        assert off(fast, res, 1) < 5.0


def _run(over, F, tilt_scale=1.0):
    """One roller on the paper's joint at 8 deg, 10 Hz, three cycles at 0.1 ms
    (harness.row_rocking.run): the model, orders of Fz over the last cycle, the tilt b2's peak
    there [rad] and f_n's [N]; the lumped row's tilt stiffness (P_LT) scaled by tilt_scale.
    (Runs are shared between the tests.)"""
    return _cached(tuple(sorted(over.items())), F, tilt_scale)


@functools.lru_cache(maxsize=None)
def _cached(over, F, tilt_scale):
    a, _r, _k, m = R.run(dict(over), tilt_scale, F, THETA, OMEGA)
    last = a[:, R.C_X] >= a[-1, R.C_X] - 2 * math.pi
    orders = last_cycle_orders(a[:, R.C_T], a[:, R.C_FZ], a[:, R.C_X], (1, 3))
    return m, orders, np.abs(a[last, R.C_B2]).max(), a[last, R.C_FN].max(), a[last]


def test_the_roller_rocks_on_the_row_as_far_as_its_moments_tilt_it():
    """docs/model.md, "The roller rocks on the row" and "Why the resolved row rocks more": with
    the row's friction off two moments about e2 tilt the roller, the groove friction's at the
    roller's rim, M2 = -r_roller f_a, and the row's radial load F_r acting where the needles
    are, d from the roller's centre along the trunnion (they ride the trunnion's stroke, Eq. 7,
    relative to the roller).  The tilt's balance k_t2 b2 = M2 + F_r d is quasi-static (the
    roller's tilt mode on the row, about 10 kHz, is far above the whirl's orders), so the
    stiffness fitted to it over the last cycle (harness.row_rocking.tilt_stiffness: M2 from the
    groove's forces, d from Eq. 7) is the row's k_t2 = k_r l^2 / 12 (contact.row_load at the
    roller's offset) within 3 %: k_r moves by about 1 % over the cycle (measured 0.9999, the
    residual 0.1 % of the moments' spread).  Without F_r d the fit misses by more than 5 %
    (measured 8.6 %).  At 8 deg, 45 kN the groove's friction slides in full at its peak: |M2|
    peaks at r_roller mu_groove f_n within 3 % (tanh(3 v / v_st) there within 1 % of 1, f_n
    moves by about 1 %)."""
    m, _o, peak, fn, a = _run(dict(R.FRICTION_OFF, bearing=1), 45000.0)
    kr = contact.row_load(m.P, m.Y[K.Y_E])[1]
    kt2 = kr * m.P[K.P_LT]
    k, res = R.tilt_stiffness(a, shift=True)
    assert k == pytest.approx(kt2, rel=0.03) and res < 0.03
    assert abs(R.tilt_stiffness(a)[0] / kt2 - 1.0) > 0.05
    rim = m.P[K.P_R_ROLLER] * m.P[K.P_MU_GROOVE] * fn
    assert np.abs(a[:, R.C_M2]).max() == pytest.approx(rim, rel=0.03)
    # at 45 kN its travel at the groove, r_roller b2, is more than the slide's (16 um)
    assert m.P[K.P_R_ROLLER] * peak > 20e-6


def test_a_row_without_friction_and_rigid_in_tilt_is_the_ideal_bearing():
    """The rocking is what moves the frictionless lumped row's thrust off the ideal bearing's
    (order 1 by 18 deg at 8 deg, 45 kN): with its tilt stiffness a hundred times higher the
    rocking's travel falls from 28 um to 0.3 um (of a 16 um slide) and orders 1 and 3 come
    within 1.5 % (complex) of the ideal bearing's, a separate code path; measured 0.6 %, the
    rest of the difference the row's radial compliance, which the ideal bearing lacks."""
    ideal = _run({"bearing": 0}, 45000.0)[1]
    rocking = _run(dict(R.FRICTION_OFF, bearing=1), 45000.0)[1]
    rigid = _run(dict(R.FRICTION_OFF, bearing=1), 45000.0, tilt_scale=100.0)[1]
    assert off(rocking, ideal, 1) > 20.0
    for k in (1, 3):
        assert off(rigid, ideal, k) < 1.5


@pytest.mark.slow   # (a resolved row, three cycles: about 30 s)
def test_the_resolved_row_rocks_more_as_its_load_moves_along_the_trunnion():
    """docs/model.md, "Why the resolved row rocks more": with the row's friction off at 8 deg,
    45 kN the needles ride the trunnion's axial stroke (Eq. 7; they sit between its stops) and
    float within their play +-needle_axial_clearance, pushed by the tilted bore, while the roller
    stays in the groove.  So the row's load acts off the roller's centre by d, and its moment
    d F_r1 adds to the groove's.  Fitted on the groove's moment alone the resolved row's tilt
    stiffness is well below the lumped row's k_r l^2 / 12 (measured 0.77; bound 0.85); with
    d F_r1 beside it, it comes within what the row's static nonlinearity (0.97 at this tilt:
    Eq. 17 on the spheres) and the tilted normals' moment (about 2 % of k_t2) leave, 0.88-1.0
    (measured 0.91), and the fit's residual halves (measured 3.5 % to 1.8 %).  The load's
    place follows the trunnion's stroke relative to the roller (correlation measured 0.987),
    spans more than it (the float adds: 410 um against 246 um) and stays within the needles'
    play about the stops' centre (+-82 um of +-100 um; 10 um for the roller's offset along
    the trunnion and the stops' compliance)."""
    a, _r, k_lumped, m = R.run(dict(R.FRICTION_OFF, bearing=2), 1.0, 45000.0, THETA, OMEGA)
    last = a[a[:, R.C_X] >= a[-1, R.C_X] - 2 * math.pi]
    k1, res1 = R.tilt_stiffness(last)
    k2, res2 = R.tilt_stiffness(last, shift=True)
    assert k1 / k_lumped < 0.85
    assert 0.88 < k2 / k_lumped < 1.0
    assert res2 < 0.7 * res1
    d, u = last[:, R.C_SHIFT], last[:, R.C_U]
    stroke = np.array([contact.trunnion_axial(x, THETA, m.P[K.P_S], True)
                       for x in last[:, R.C_X]])
    assert np.corrcoef(d, stroke - u)[0, 1] > 0.95
    assert np.ptp(d) > np.ptp(stroke - u)
    assert np.abs(d + u - stroke).max() < m.p["needle_axial_clearance"] + 10e-6


@pytest.mark.slow   # (a resolved row at 20 deg, three cycles: about 30 s)
def test_the_resolved_rows_needles_lag_the_trunnion_within_their_play():
    """docs/model.md, "The needles' play": with the row's friction on the needles roll half the
    trunnion's stroke's way until their lag reaches their axial play, then the stop carries
    them (needle_row.needle_lag, which the lumped and analytic rows take).  At 20 deg, 4.5 kN on
    the paper's joint the stroke (1.43 mm peak to peak) is far beyond what the play lets them
    lag (0.4 mm of stroke): the loaded needles' place d spans the stroke less twice the play
    (measured 1228 um against 1227 um), not half the stroke (713 um), and follows the play
    operator stepped on the run's stroke (correlation measured 1.000).  Bounds: the span within
    3 % (37 um: the needles' own float about their mean place, 14 um rms at 8 deg, 45 kN, rides
    on the operator), the correlation above 0.99."""
    theta = math.radians(20.0)
    a, play = R.stroke_and_place(theta, 4500.0, OMEGA)
    stroke, d = a[:, 1], a[:, 2]
    pred = R.play_operator(stroke, play)
    assert np.ptp(pred) == pytest.approx(np.ptp(stroke) - 2.0 * play, rel=0.02)
    assert np.ptp(d) == pytest.approx(np.ptp(pred), rel=0.03)
    assert abs(np.ptp(d) - 0.5 * np.ptp(stroke)) > 0.3 * np.ptp(stroke)
    assert np.corrcoef(pred, d)[0, 1] > 0.99


@pytest.mark.slow   # (one resolved row: about 20 s)
def test_the_lumped_rows_arc_carries_the_resolved_needles_friction_moment():
    """At 8 deg, 45 kN (one roller, 10 Hz): the moment about e1 of the resolved needles' axial
    friction at the bore (sum x2_j F3_j) against the lumped law's around the loaded arc (its
    two points +-row_arc, the line's length left out) at the resolved roller's own motion,
    orders 1 and 3 over the last of three cycles: within 25 % in amplitude and 10 deg
    (measured +17 % and +7 %, -5.5 and -5.9 deg: the arc's two points stand for needles spread
    over +-70 deg, whose slips saturate the tanh law unequally).  A law at one point has none."""
    a = R.arc_moments(THETA, 45000.0, OMEGA)
    res, arc = (last_cycle_orders(np.arange(len(a)), a[:, k], a[:, 0], (1, 3)) for k in (1, 2))
    for k in (1, 3):
        assert arc[k][0] == pytest.approx(res[k][0], rel=0.25), k
        assert abs((arc[k][1] - res[k][1] + 180.0) % 360.0 - 180.0) < 10.0, k
    assert res[1][0] > 0.5      # N m: the resolved row has the moment the one-point law lacks
