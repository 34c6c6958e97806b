"""The peer table of `tripod-thrust bench --peer` (quick mode): scipy's solve_ivp on the same
equations as the contact FMU.  Two independent integrators of the same equations must agree:
LSODA at rtol 1e-4 and the FMU at its defaults both land within 0.1 % (complex, order 3 of Fz')
of the reference (the FMU at a 12.5 us step), which is the accuracy budget the bench quotes."""
import math

from harness import bench


def test_peer_table_quick():
    rows = bench.peers(runs=1, quick=True, log=lambda m: None)
    by = {(r["engine"], r["setting"]): r for r in rows}
    lsoda = by[("scipy solve_ivp LSODA", "rtol=0.0001")]
    fmu = by[("contact FMU through FMI (integrator 4)", "defaults, dt=0.0001")]
    assert lsoda["err_order3"] < 1e-3 and fmu["err_order3"] < 1e-3
    # each peer row is set against the cheapest FMU setting at least as accurate
    for r in rows:
        if r["engine"].startswith("scipy"):
            assert math.isfinite(r["ratio"]) and r["ratio"] > 0
    assert "| scipy solve_ivp Radau | rtol=0.001 |" in bench.peers_markdown(rows)
