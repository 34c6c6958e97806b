"""A serialised FMU state is data: a pickle payload runs nothing, a damaged state is refused with
fmi2Error, a good one restores, a state of another layout comes with its parameters (issue:
untrusted input).  Values changed inside a state with a valid checksum, and crafted contact
states: tests/test_native_fmu.py.  The long run (every truncation, thousands of flips and
random states, under valgrind) is benchmarks/abuse.py."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from harness.fmus import ensure_fmu

WORKER = Path(__file__).with_name("state_abuse.py")
def abuse(name, tmp_path, **spec):
    spec = dict(spec, marker=str(tmp_path / "code-ran"))
    fmu = ensure_fmu(name)
    p = subprocess.run([sys.executable, str(WORKER), str(fmu), json.dumps(spec)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("name,ints", [
    ("TripodRoller", {}),
    ("TripodRoller", {"bearing": 1, "n_rollers": 3}),
    ("TripodRollerAnalytic", {"n_rollers": 3}),
], ids=["contact", "contact-lumped-3", "analytic-3"])
def test_bad_states_are_refused_and_run_nothing(name, ints, tmp_path):
    """Pickle payloads, truncations, bit flips and random tails of a good state: each refused,
    none runs code; the good state restores."""
    r = abuse(name, tmp_path, ints=ints, moving=True, truncations=40, flips=40, random=20)
    assert r["code_ran"] is False
    cases = r["cases"]
    assert cases.pop("good") == "finite"
    wrong = {k: v for k, v in cases.items() if v != "refused"}
    assert not wrong, wrong
    assert len(cases) >= 90
    assert r["good_after"] == "finite"


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
