"""Every parameter and input of both built FMUs at NaN, +-Inf, 0, -0, a denormal, its min, its
max and +-1e300 (integers: min, max, 0, -1, one past each end, the int32 limits), set before
initialisation and during the run: each case runs to finite outputs or is refused with a
one-line logged reason, within 10 s (issue: untrusted input).  The same worker runs every
bearing in benchmarks/abuse.py."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from harness.fmus import ensure_fmu

WORKER = Path(__file__).with_name("value_matrix.py")
CASE_SECONDS = 10.0


def matrix(name, **spec):
    p = subprocess.run([sys.executable, str(WORKER), str(ensure_fmu(name)), json.dumps(spec)],
                       capture_output=True, text=True, timeout=1800)
    assert p.returncode == 0, p.stderr[-3000:]
    return [json.loads(line) for line in p.stdout.splitlines() if line.startswith("{\"case")]


@pytest.mark.parametrize("name,ints", [("TripodRoller", {}),
                                       ("TripodRollerAnalytic", {"n_rollers": 3})],
                         ids=["contact", "analytic-3"])
def test_every_value_runs_finite_or_is_refused_with_a_reason(name, ints):
    rows = matrix(name, ints=ints)
    cases = {r["case"]: r for r in rows}
    defects = {k: r for k, r in cases.items() if r["outcome"] not in ("finite", "refused")}
    assert not defects, defects
    slow = {k: r["seconds"] for k, r in cases.items() if r["seconds"] > CASE_SECONDS}
    assert not slow, slow
    # the matrix is whole: 10 real values (8 integer) x 2 phases for every variable
    from fmpy import read_model_description
    md = read_model_description(str(ensure_fmu(name)))
    n = sum(20 if v.type == "Real" else 16 for v in md.modelVariables
            if v.causality in ("parameter", "input") and v.type in ("Real", "Integer"))
    assert len(cases) == n
    for inp in ("theta", "omega", "F_press", "torque", "plunge_speed", "shaft_angle"):
        # a non-finite or far out-of-range input is refused during the run as at the start
        # (shaft_angle too, while drive_by_angle is off and it is unused)
        for v in ("nan", "+inf", "-inf", "1e300", "-1e300"):
            for phase in ("before", "during"):
                r = cases[f"{inp}={v} {phase}"]
                assert r["outcome"] == "refused" and inp in r["message"], r
        # the bottom of each input's range runs (the check can tell a run from a refusal):
        # coast at 100 kN, reverse whirl at 1e4 rad/s
        assert cases[f"{inp}=min during"]["outcome"] == "finite"
    # a fixed parameter set during the run is refused by name, the run goes on without it
    assert cases["E=min during"]["outcome"] == "refused"
    assert "E is a fixed parameter" in cases["E=min during"]["message"]
    assert cases["E=max before"]["outcome"] == "finite"


def test_powertrain_every_value_runs_finite_or_is_refused_with_a_reason():
    """The driveline example's powertrain FMU under the same matrix: its inputs (the joint's
    forces and angle) and parameters."""
    p = subprocess.run([sys.executable, str(WORKER), str(ensure_fmu("Powertrain")), "{}"],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0 and "Warning" not in p.stderr, p.stderr[-3000:]   # nothing on stderr
    rows = [json.loads(line) for line in p.stdout.splitlines() if line.startswith("{\"case")]
    cases = {r["case"]: r for r in rows}
    defects = {k: r for k, r in cases.items() if r["outcome"] not in ("finite", "refused")}
    assert not defects, defects
    for inp in ("Fz_joint", "F_housing_x", "F_housing_y", "whirl_angle"):
        for v in ("nan", "+inf", "-inf", "1e300", "-1e300"):
            for phase in ("before", "during"):
                r = cases[f"{inp}={v} {phase}"]
                assert r["outcome"] == "refused" and inp in r["message"], r
        assert cases[f"{inp}=min during"]["outcome"] == "finite"
    for case in ("mass=0 before", "mass=denormal before"):
        assert cases[case]["outcome"] == "refused" and "mass" in cases[case]["message"]
