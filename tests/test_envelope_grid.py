"""The fast models against the full one over the driveline envelope (issue 67 point 5): every
scene of docs/validation.md's grid (harness/envelope_grid.py) rerun, held to the issue's
bounds where it names them, and the table held to the rerun."""
import re

import pytest

from harness.envelope_grid import (COLUMNS, TABLE_DOC, TABLE_HEAD, inside_checked_range, off,
                                   scene_orders)

# where the 3 % (order 3) or 5 % (order 1) is missed, the bound the scene is held to
# and why (docs/validation.md says more): (scene, model, order) -> bound [%]
MISSED = {
    # a 25.8 kN coast at 3.4 deg (measured 4.1 %): the lumped row's own, the resolved row
    # keeping drive and coast mirror images there (docs/validation.md)
    (8, "lumped", 3): 4.5,
    # 1.1 kN at 23.6 deg (measured 2.98 % and 5.3 %): the reduced form's order 1 about 3 %
    # above the lumped row's, itself 2.1 % above the resolved row's
    (15, "analytic", 3): 3.2, (15, "analytic", 1): 5.6,
}
BOUND = {1: 5.0, 3: 3.0}
# the resolved row's realizations spread by about 0.2 % (docs/model.md): the table's figures,
# printed to 0.1 points, are held to the rerun within that and their rounding
TABLE_POINTS = 0.3
TABLE_REL = 0.005


def _table_row(i):
    text = TABLE_DOC.read_text()
    text = text[text.index(TABLE_HEAD):]
    row = re.search(rf"^\| {i} \| .*$", text, re.M)
    assert row, f"docs/validation.md has no row {i} in the envelope grid's table"
    return [c.strip() for c in row.group(0).strip("|").split("|")]


@pytest.mark.slow   # (the whole grid: about 8 minutes)
@pytest.mark.parametrize("i", range(1, 25))
def test_the_fast_models_follow_the_resolved_row_over_the_envelope(i):
    """One roller's Fz against the needle-resolved row's (complex), each scene three whirl
    cycles from the start: the lumped row and, inside its checked range, the analytic model at
    its default (its needle row) within the issue's 3 % in order 3 and 5 % in order 1 but where
    MISSED names the scene; the analytic model outside its checked range (scene 9: the roller's
    inertia against the load 0.83, checked to 0.1) not held.  The table in docs/validation.md
    gives the same figures (the resolved row's amplitudes within 0.5 %, each difference within
    0.3 points)."""
    r = scene_orders(i)
    ref = r["resolved"]
    held = ["lumped"] + (["analytic"] if inside_checked_range(i) else [])
    assert (i == 9) == ("analytic" not in held)
    for label in held:
        for k in (1, 3):
            assert off(r[label], ref, k) < MISSED.get((i, label, k), BOUND[k]), (label, k)
    cells = _table_row(i)
    amp1, amp3 = (float(x) for x in cells[5].split(","))
    assert amp1 == pytest.approx(ref[1][0], rel=TABLE_REL, abs=0.01)
    assert amp3 == pytest.approx(ref[3][0], rel=TABLE_REL, abs=0.01)
    for j, (label, _m, _a) in enumerate(COLUMNS):
        doc = [float(x.strip(" %")) for x in cells[6 + j].split(",")]
        for d, k in zip(doc, (1, 3)):
            assert abs(d - off(r[label], ref, k)) <= TABLE_POINTS + 0.002 * d, (label, k)
