"""A serialised FMU state is data: a pickle payload runs nothing, a damaged, crafted, foreign
or inconsistent state is refused with fmi2Error, a good one restores (issue: untrusted input).
The pythonfmu slaves' states: the references of the FMUs (the shipped FMUs are compiled, their
states checked in C and by the compiled model: tests/test_native_fmu.py).  The long run (every
truncation, thousands of flips and random states, under valgrind) is
benchmarks/state_fuzz.py."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from harness.fmus import ensure_fmu, reference_fmu

WORKER = Path(__file__).with_name("state_abuse.py")
COMMON = ["nan-output", "inf-input", "input-out-of-range", "extra-variable",
          "missing-variable", "other-guid", "other-structural", "other-version",
          "nested-200-deep", "string-for-number"]
ARRAYS = ["array-longer-than-data", "array-offset-past-end", "array-negative-shape",
          "array-object-dtype"]


def abuse(name, tmp_path, **spec):
    spec = dict(spec, marker=str(tmp_path / "code-ran"))
    fmu = reference_fmu(name)
    p = subprocess.run([sys.executable, str(WORKER), str(fmu), json.dumps(spec)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("name,extra,ints", [
    ("TripodRoller", ARRAYS, {}),
    ("TripodRoller", ARRAYS, {"bearing": 1, "n_rollers": 3}),
    ("TripodRollerAnalytic", ["X-cut-short", "X-a-number"], {"n_rollers": 3}),
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


_IN_MEMORY = r'''
import json, sys
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
md = read_model_description(sys.argv[1]); d = extract(sys.argv[1])
vr = {v.name: v.valueReference for v in md.modelVariables}

def make(name, n):
    s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=name)
    s.instantiate(); s.setupExperiment(startTime=0.0); s.enterInitializationMode()
    s.setInteger([vr["n_rollers"]], [n]); s.exitInitializationMode()
    for i in range(20):
        s.doStep(i * 1e-4, 1e-4)
    return s

def try_set(s, st):
    try:
        s.setFMUstate(st)
        return "set"
    except Exception:
        return "refused"

OUT = [v.valueReference for v in md.modelVariables if v.causality == "output" and v.type == "Real"]

def run_on(s):
    return [s.doStep((20 + i) * 1e-4, 1e-4) or s.getReal(OUT) for i in range(20)]

a, b = make("a", 3), make("b", 1)
st = a.getFMUstate()
res = {"other-instance": try_set(b, st)}
res["other-instance-runs-on"] = run_on(b) == run_on(a)
res["own"] = try_set(a, st)
ref = run_on(a)
a.setFMUstate(st)
a.reset(); a.setupExperiment(startTime=0.0); a.enterInitializationMode()
a.setInteger([vr["n_rollers"]], [1]); a.exitInitializationMode()
res["own-after-reset-to-other-layout"] = try_set(a, st)
res["after-reset-runs-on"] = run_on(a) == ref
print(json.dumps(res))
'''


@pytest.mark.parametrize("name", ["TripodRoller", "TripodRollerAnalytic"])
def test_an_in_memory_state_of_another_layout_comes_with_its_parameters(name):
    """A state carries its parameters (FMI 2.0 counts them part of it): handed to another
    instance with another layout (3 rollers into 1), or to this instance after an fmi2Reset to
    another layout, it is checked, set with its parameters and runs on as the instance it was
    taken from does, bit for bit; its own state, after a step, restores."""
    p = subprocess.run([sys.executable, "-c", _IN_MEMORY, str(ensure_fmu(name))],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    assert r == {"other-instance": "set", "other-instance-runs-on": True, "own": "set",
                 "own-after-reset-to-other-layout": "set", "after-reset-runs-on": True}, r


@pytest.mark.parametrize("name,ints", [
    ("TripodRoller", {}),
    ("TripodRoller", {"bearing": 1, "n_rollers": 3}),
    ("TripodRoller", {"bearing": 2, "n_needles": 12}),
    ("TripodRollerAnalytic", {"n_rollers": 3}),
], ids=["contact", "contact-lumped-3", "contact-resolved", "analytic-3"])
def test_states_with_wrong_values_are_refused_or_stepped(name, ints, tmp_path):
    """A structure-aware fuzz (issue: bounded time): one to three values inside a valid state's
    arrays changed to plausible-looking wrong ones (tests/state_abuse.py: MUTANTS), checksum
    recomputed.  Each is refused at set, or its next 20 steps end with finite outputs or are
    refused with a reason; none hangs (the worker's timeout) and none steps to a non-finite
    output with fmi2OK.  The good state still restores after them all."""
    r = abuse(name, tmp_path, ints=ints, mutations=150, seed=7)
    cases = r["cases"]
    assert cases.pop("good") == "finite"
    mutated = {k: v for k, v in cases.items() if k.startswith("mutated-")}
    assert len(mutated) == 150
    wrong = {k: v for k, v in mutated.items() if v not in ("refused", "finite", "refused-later")}
    assert not wrong, wrong
    assert r["good_after"] == "finite"


def test_a_roller_off_its_trunnion_is_refused_at_set(tmp_path):
    """The issue's state: a contact state after some steps with the roller's slide u set to
    0.5 m (the whole joint is 0.022 m): refused at fmi2SetFMUstate, not stepped (it ran for
    minutes before the budget); the reason names the value."""
    r = abuse("TripodRoller", tmp_path, crafted=["slide-half-a-metre"], log=True)
    assert r["cases"]["slide-half-a-metre"] == "refused"
    assert "slide u = 0.5 m is outside +-0.006 m" in r["log"], r["log"][-2000:]


def test_a_state_inside_the_bounds_that_cannot_be_stepped_meets_the_budget(tmp_path):
    """The roller's slide set to 3 mm (inside the state check's 6 mm; runs reach 0.1 mm): the
    state is taken, and its next step is refused (fmi2Discard) once the adaptive substeps have
    tried their budget (about 0.15 s; before, such states ran for tens of seconds), with one
    line saying so."""
    r = abuse("TripodRoller", tmp_path, crafted=["slide-three-mm"], log=True)
    assert r["cases"]["slide-three-mm"] == "refused-later"
    line = next(m for m in r["log"].splitlines() if "step refused" in m)
    assert "roller 1: the adaptive substeps stopped at" in line
    assert "the substeps tried reached their budget" in line
