"""The peer table of `tripod-thrust bench --peer` (quick mode): scipy's solve_ivp on the same
equations as the contact FMU.  Two independent integrators of the same equations must agree:
LSODA at rtol 1e-4 and the FMU at its defaults both land within 0.1 % (complex, order 3 of Fz')
of the reference (the FMU at a 12.5 us step), which is the accuracy budget the bench quotes.

Exudyn (extra `peer`, skipped without it) builds the roller's equations itself from rigid bodies
and joints; only the contact law is shared.  Its generalized-alpha at h = 1e-4 s converges to
the FMU's reference (order-3 error 1.1e-4, 2.9e-5 at half the step, measured): within 5e-4 it
must land, where a wrong equation of motion (a lost inertial term, a wrong spin inertia) moves
order 3 by percents."""
import math

import pytest

from harness import bench


@pytest.fixture(scope="module")
def rows():
    return bench.peers(runs=1, quick=True, log=lambda m: None)


def test_peer_table_quick(rows):
    by = {(r["engine"], r["setting"]): r for r in rows}
    lsoda = by[("scipy solve_ivp LSODA", "rtol=0.0001")]
    fmu = by[("contact FMU through FMI (integrator 4)", "defaults, dt=0.0001")]
    assert lsoda["err_order3"] < 1e-3 and fmu["err_order3"] < 1e-3
    # each peer row is set against the cheapest FMU setting at least as accurate
    for r in rows:
        if r["engine"] != "contact FMU through FMI (integrator 4)":
            assert math.isfinite(r["ratio"]) and r["ratio"] > 0
    assert "| scipy solve_ivp Radau | rtol=0.001 |" in bench.peers_markdown(rows)


def test_exudyn_same_roller_quick(rows):
    pytest.importorskip("exudyn")
    ex = [r for r in rows if r["engine"] == bench.EXUDYN]
    assert len(ex) == len(bench.PEER_EXUDYN_QUICK)
    assert ex[0]["err_order3"] < 5e-4
    assert math.isfinite(ex[0]["ratio"]) and ex[0]["ratio"] > 0
