"""The lumped needle row against the needle-resolved row it stands for (docs/model.md, "What
the needle row does to the thrust"): the needle loads it shares, the thrust's orders, and the
roller's rocking on the row."""
import functools
import math

import numpy as np
import pytest

from harness.envelope_grid import JOINTS, contact_orders, off, scene
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
            f, _k, _kw, q = oppoint.row_sums(m.P, abs(m.Y[K.Y_E]))
            want.append(q / f)
    assert np.mean(got) == pytest.approx(np.mean(want), rel=0.01)
    assert np.mean(want) < m.P[K.P_QSUM] - 0.05   # not the share without clearance


@pytest.mark.slow   # (two resolved rows: about 40 s)
@pytest.mark.parametrize("F, bound3", [(4500.0, 0.03), (45000.0, 0.06)])
def test_lumped_row_thrust_follows_the_resolved_row(F, bound3):
    """One roller, 8 deg, 10 Hz: order 3 of Fz, complex (amplitude and phase), against the
    resolved row's: within 3 % at 4.5 kN (the paper's kind of load; measured 0.7 %) and 6 % at
    45 kN, a launch (measured 5.0 %; the 3 % the issue asks for is not reached there, docs/model.md
    says what is left); order 1 within 5 % (measured 1.5 % and 3.8 %).  The resolved row's
    realizations spread by about 0.2 % here; the ideal bearing is 10 % and 19 % off."""
    res, lum = (contact_orders(PAPER, THETA, F, OMEGA, b) for b in (2, 1))
    assert off(lum, res, 3) < 100 * bound3
    assert off(lum, res, 1) < 5.0


@pytest.mark.slow   # (six resolved rows: about 2 minutes)
@pytest.mark.parametrize("i", range(13, 19))
def test_lumped_row_follows_the_resolved_row_over_the_envelope(i):
    """Scenes 13-18 of the envelope's grid (harness/envelope_grid.py: the three joints, 2.7-23.6
    deg, 0.4-31 kN a roller, drive and coast, 2.8-21.7 Hz; docs/validation.md): order 3 of one
    roller's Fz on the lumped row within the issue's 3 % of the needle-resolved row's (complex),
    order 1 within 5 %.  Measured 0.3-2.1 % and 0.5-3.4 %; the resolved row's realizations
    spread by about 0.2 %.  (Of the grid's 24 scenes two miss 3 %: a 25.8 kN coast at 3.4 deg,
    4.1 %, and an order 3 a tenth of order 1, 11.5 %.)"""
    s = scene(i)
    res, lum = contact_orders(*s, 2), contact_orders(*s, 1)
    assert off(lum, res, 3) < 3.0
    assert off(lum, res, 1) < 5.0


FRICTION_OFF = {"friction_needle": False, "rolling_resistance": False}


def _run(over, F, tilt_scale=1.0):
    """One roller on the paper's joint at 8 deg, 10 Hz, three cycles at 0.1 ms: orders of Fz
    over the last cycle, the tilt b2's peak there [rad] and f_n's [N]; the lumped row's tilt
    stiffness (P_LT) scaled by tilt_scale.  (Runs are shared between the tests.)"""
    return _cached(tuple(sorted(over.items())), F, tilt_scale)


@functools.lru_cache(maxsize=None)
def _cached(over, F, tilt_scale):
    m = ContactModel(dict(over, theta=THETA, omega=OMEGA, F_press=F))
    m.P[K.P_LT] *= tilt_scale
    t, fz, x, b2, fn = [], [], [], [], []
    for _ in range(3000):
        o = m.step(1e-4, THETA, OMEGA, F)
        t.append(m.time)
        fz.append(o["Fz"])
        x.append(m.whirl_angle)
        b2.append(m.Y[K.Y_B2])
        fn.append(m._res[K.R_FN])
    x = np.array(x)
    last = x >= x[-1] - 2 * math.pi
    orders = last_cycle_orders(np.array(t), np.array(fz), x, (1, 3))
    return m, orders, np.abs(np.array(b2)[last]).max(), np.array(fn)[last].max()


def test_the_roller_rocks_on_the_row_as_far_as_the_groove_friction_tilts_it():
    """docs/model.md, "The roller rocks on the row": with the row's friction off the only
    moment about e2 is the groove friction's at the roller's rim, so the tilt's balance
    k_t2 b2 = -r_roller f_a bounds the rocking by r_roller mu_groove f_n / k_t2, and at 8 deg,
    45 kN the friction slides in full at the tilt's peak: the peak is that bound.  k_t2 =
    k_r l^2 / 12 from the row's load law (contact.row_load) at the roller's offset.  Within 3 %:
    f_n and the row's stiffness move by about 1 % over the cycle, and tanh(3 v / v_st) at the
    peak slip is within 1 % of 1."""
    m, _o, peak, fn = _run(dict(FRICTION_OFF, bearing=1), 45000.0)
    _Fr, kr, _kw, _q = contact.row_load(m.P, m.Y[K.Y_E])
    bound = m.P[K.P_R_ROLLER] * m.P[K.P_MU_GROOVE] * fn / (kr * m.P[K.P_LT])
    assert peak == pytest.approx(bound, rel=0.03)
    # at 45 kN its travel at the groove, r_roller b2, is more than the slide's (16 um)
    assert m.P[K.P_R_ROLLER] * peak > 20e-6


def test_a_row_without_friction_and_rigid_in_tilt_is_the_ideal_bearing():
    """The rocking is what moves the frictionless lumped row's thrust off the ideal bearing's
    (order 1 by 18 deg at 8 deg, 45 kN): with its tilt stiffness a hundred times higher the
    rocking's travel falls from 28 um to 0.3 um (of a 16 um slide) and orders 1 and 3 come
    within 1.5 % (complex) of the ideal bearing's, a separate code path; measured 0.6 %, the
    rest of the difference the row's radial compliance, which the ideal bearing lacks."""
    ideal = _run({"bearing": 0}, 45000.0)[1]
    rocking = _run(dict(FRICTION_OFF, bearing=1), 45000.0)[1]
    rigid = _run(dict(FRICTION_OFF, bearing=1), 45000.0, tilt_scale=100.0)[1]
    assert off(rocking, ideal, 1) > 20.0
    for k in (1, 3):
        assert off(rigid, ideal, k) < 1.5
