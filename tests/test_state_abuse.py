"""A serialised FMU state is data: a pickle payload runs nothing, a damaged, crafted, foreign
or inconsistent state is refused with fmi2Error, a good one restores (issue: untrusted input).
The long run (every truncation, thousands of flips and random states, under valgrind) is
benchmarks/state_fuzz.py."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from harness.fmus import ensure_fmu

WORKER = Path(__file__).with_name("state_abuse.py")
COMMON = ["nan-output", "inf-input", "input-out-of-range", "extra-variable",
          "missing-variable", "other-guid", "other-structural", "other-version",
          "nested-200-deep", "string-for-number"]
ARRAYS = ["array-longer-than-data", "array-offset-past-end", "array-negative-shape",
          "array-object-dtype"]


def abuse(name, tmp_path, **spec):
    spec = dict(spec, marker=str(tmp_path / "code-ran"))
    p = subprocess.run([sys.executable, str(WORKER), str(ensure_fmu(name)), json.dumps(spec)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("name,extra,ints", [
    ("TripodRoller", ARRAYS, {}),
    ("TripodRoller", ARRAYS, {"bearing": 1, "n_rollers": 3}),
    ("TripodRollerAnalytic", ["three-angles-one-row", "nan-in-march"], {"n_rollers": 3}),
], ids=["contact", "contact-lumped-3", "analytic-3"])
def test_bad_states_are_refused_and_run_nothing(name, extra, ints, tmp_path):
    r = abuse(name, tmp_path, ints=ints, moving=True, truncations=40, flips=40, random=20,
              crafted=COMMON + extra)
    assert r["code_ran"] is False
    cases = r["cases"]
    assert cases.pop("good") == "finite"
    wrong = {k: v for k, v in cases.items() if v != "refused"}
    assert not wrong, wrong
    assert len(cases) >= 100


@pytest.mark.parametrize("src,dst", [({"n_rollers": 3}, {"n_rollers": 1}),
                                     ({"n_rollers": 1}, {"n_rollers": 3}),
                                     ({"bearing": 1}, {"bearing": 0})])
def test_a_foreign_state_is_refused(src, dst, tmp_path):
    r = abuse("TripodRoller", tmp_path, ints=src, target_ints=dst)
    assert r["cases"]["good"] == "refused"


def test_the_analytic_fmu_refuses_a_foreign_state(tmp_path):
    r = abuse("TripodRollerAnalytic", tmp_path, ints={"n_rollers": 3}, target_ints={"n_rollers": 1})
    assert r["cases"]["good"] == "refused"


@pytest.mark.parametrize("name", ["TripodRoller", "TripodRollerAnalytic"])
@pytest.mark.parametrize("ints", [{}, {"n_rollers": 3}], ids=["one", "three"])
def test_non_finite_inputs_are_discarded(name, ints, tmp_path):
    bad = [[n, v] for n in ("theta", "omega", "F_press", "torque") for v in ("inf", "-inf", "nan")]
    r = abuse(name, tmp_path, ints=ints, inputs=bad)
    assert set(r["inputs"].values()) == {"discard"}, r["inputs"]
