"""The lumped needle row against the needle-resolved row it stands for (docs/model.md, "What
the needle row does to the thrust"): the needle loads it shares, and the thrust's orders."""
import math

import numpy as np
import pytest

from harness.row_grid import JOINTS, contact_orders, off, scene
from tripod_model import layout as K, oppoint
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
    """Scenes 13-18 of the envelope's grid (harness/row_grid.py: the three joints, 2.7-23.6
    deg, 0.4-31 kN a roller, drive and coast, 2.8-21.7 Hz; docs/validation.md): order 3 of one
    roller's Fz on the lumped row within the issue's 3 % of the needle-resolved row's (complex),
    order 1 within 5 %.  Measured 0.3-2.1 % and 0.5-3.4 %; the resolved row's realizations
    spread by about 0.2 %.  (Of the grid's 24 scenes two miss 3 %: a 25.8 kN coast at 3.4 deg,
    4.1 %, and an order 3 a tenth of order 1, 11.5 %.)"""
    s = scene(i)
    res, lum = contact_orders(*s, 2), contact_orders(*s, 1)
    assert off(lum, res, 3) < 3.0
    assert off(lum, res, 1) < 5.0
