"""Every step ends in bounded time (tripod_model/budget.py): the adaptive substeps stop at their
floor, at their budget of tries, or at a non-finite error estimate, and the step is refused
with one line saying which and where; ordinary scenes run far from the budget; a model state
that cannot be stepped is refused before it is set (tripod_model/state_check.py)."""
import math

import pytest

from reduced_model.scene import DEG, StepRefused, check_value
from tripod_model import budget, steplib, layout as K
from tripod_model.model import JointModel
from tripod_model import fmu_arrays as FA
from tripod_model.state_check import speed_bound

DT, OMEGA, THETA = 1e-4, 2 * math.pi * 10, 8 * DEG


def _settled(params, steps=60):
    m = JointModel(dict(params))
    for _ in range(steps):
        m.step(DT, THETA, OMEGA, 0.0, 300.0)
    return m


def _tries(m):
    return sum(r._hs[K.H_TAKEN] + r._hs[K.H_REJECTED] for r in m.rollers)


@pytest.mark.parametrize("params", [{}, {"bearing": 1}, {"n_rollers": 3}],
                         ids=["ideal", "lumped", "three"])
@pytest.mark.parametrize("u", [0.01, 0.5, -3.0])
def test_a_state_the_step_cannot_serve_is_refused_within_the_budget(params, u):
    """The issue's crafted states (the roller's slide u set far off: one 1e-4 s step ran for
    22 s at 0.01 m and did not return at 0.5 m): the step is refused, naming what ran out, after
    no more substeps than the budget allows a call (one call here: the Newton fallback)."""
    m = _settled(params)
    m.rollers[0].Y[K.Y_U] = u
    before = _tries(m)
    with pytest.raises(StepRefused, match=r"the adaptive substeps stopped at .* % of the step"):
        m.step(DT, THETA, OMEGA, 0.0, 300.0)
    hmax = m.rollers[0].P[K.P_HMAX]
    n = m.rollers[0]._OP[K.OP_N]
    allowed = n + budget.ADAPT_TRIES_MIN + budget.ADAPT_TRIES_PER * math.ceil(DT / hmax)
    assert _tries(m) - before <= allowed
    assert m.rollers[0]._hs[K.H_FAIL] in (K.FAIL_FLOOR, K.FAIL_TRIES, K.FAIL_ESTIMATE)


def _adaptive_call(m, T):
    """adaptive_steps as Python (its constants read at call time) on roller 1 of m over T."""
    r = m.rollers[0]
    OP = r._OP
    drive = K.Drive(OP[K.OP_THETA], OP[K.OP_W], OP[K.OP_X0], 0.0)
    hs = r._hs
    taken, rejected = hs[K.H_TAKEN], hs[K.H_REJECTED]
    ok = steplib.adaptive_steps.py_func(r.Y, r.P, drive, T, 0.25 * T, r._W, None) \
        if hasattr(steplib.adaptive_steps, "py_func") else \
        steplib.adaptive_steps(r.Y, r.P, drive, T, 0.25 * T, r._W, None)
    return ok, hs[K.H_TAKEN] - taken + hs[K.H_REJECTED] - rejected


def test_the_tries_run_out_at_the_budget(monkeypatch):
    """With a budget of 5 tries and none per largest substep, a span that needs more stops
    after exactly 5, says so, and reports how far it got."""
    m = _settled({}, 10)
    m.rollers[0]._hs[K.H_SUB] = 1e-7     # a short substep carried in: many tries to span 1e-4 s
    monkeypatch.setattr(steplib, "ADAPT_TRIES_MIN", 5.0)
    monkeypatch.setattr(steplib, "ADAPT_TRIES_PER", 0.0)
    ok, tries = _adaptive_call(m, 1e-4)
    hs = m.rollers[0]._hs
    assert not ok and tries == 5 and hs[K.H_FAIL] == K.FAIL_TRIES
    assert 0.0 < hs[K.H_FAIL_DONE] < 1.0
    assert "the substeps tried reached their budget" in budget.refusal(hs, m.rollers[0].P)


def test_a_non_finite_error_estimate_stops_at_once():
    """NaN in a velocity makes the error estimate NaN: the first try stops, neither accepted
    nor retried at ever smaller substeps (the unbounded loop of before)."""
    m = _settled({}, 10)
    m.rollers[0].Y[K.Y_OM] = math.nan
    ok, tries = _adaptive_call(m, 1e-4)
    assert not ok and tries == 0 and m.rollers[0]._hs[K.H_FAIL] == K.FAIL_ESTIMATE


def test_an_ordinary_step_input_runs_far_from_the_budget():
    """A 10 % step in theta with the lumped bearing (the adaptive substeps' hardest ordinary
    work: its row's stiff modes, benchmarks/step_budget.py) uses under a fifth of the tries and
    stays a hundred times above the floor."""
    m = _settled({"bearing": 1})
    for _ in range(20):
        m.step(DT, 1.1 * THETA, OMEGA, 0.0, 300.0)
    hs = m.rollers[0]._hs
    assert hs[K.H_FAIL] == K.FAIL_NONE
    assert 0.0 < hs[K.H_USE_TRIES] < 0.2
    assert 0.0 < hs[K.H_USE_FLOOR] < 0.01


@pytest.mark.parametrize("params", [{}, {"bearing": 1}, {"n_rollers": 3},
                                    {"bearing": 2, "n_needles": 12}],
                         ids=["ideal", "lumped", "three", "resolved"])
def test_states_a_run_reaches_pass_the_state_check(params):
    """No false refusal: the states of a launch (25 deg, 3000 N m) pass, at the start and
    after steps."""
    m = JointModel(dict(params))
    assert m.state_problem(m.get_state(), 25 * DEG, OMEGA) == ""
    for i in range(40):
        m.step(DT, 25 * DEG, OMEGA, 0.0, 3000.0)
    assert m.state_problem(m.get_state(), 25 * DEG, OMEGA) == ""


@pytest.mark.parametrize("slot,value,words", [
    (K.Y_U, 0.0061, "slide u is beyond half the needle length"),
    (K.Y_OM, math.inf, "non-finite"),
    (K.Y_UD, None, "speeds are beyond the scene's"),
    (K.Y_E, 0.0017, "radial offset or tilt on its needle row is beyond the row's thickness"),
    (K.Y_B2D, None, "speeds are beyond the scene's"),
], ids=["slide", "inf-spin", "slide-speed", "radial", "tilt-rate"])
def test_a_state_outside_the_geometry_or_speeds_is_refused_naming_the_value(slot, value, words):
    """The bounds (state_check's docstring) from the default joint: half the needle length
    (12 mm / 2), the needle diameter (1.6 mm), ten times the driven motion's speed; just
    outside each is refused with the reason, as the FMU refuses a state a host sets."""
    m = _settled({"bearing": 1}, 10)
    st = m.get_state()
    v = speed_bound(m.p, THETA, OMEGA, 0.0)
    if value is None:
        value = 1.01 * v * (1.0 / m.p["r_bore"] if slot == K.Y_B2D else 1.0)
    bad = st.copy()
    bad[FA.X_Y + slot] = value           # roller 1's state Y
    assert words in m.state_problem(bad, THETA, OMEGA)
    assert m.state_problem(st, THETA, OMEGA) == ""


@pytest.mark.parametrize("value,words", [(1.5, "restart weight or counts are out of range"),
                                         (-0.1, "restart weight or counts are out of range"),
                                         (math.nan, "non-finite")])
def test_a_restart_weight_outside_zero_to_one_is_refused(value, words):
    """The integrators' history slot hs[H_JUMPW] (genalpha.inputs_jumped's restart weight,
    in [0, 1] whenever the model writes it): a restored state with another value is refused;
    the state as the run left it passes."""
    m = _settled({"bearing": 1}, 10)
    st = m.get_state()
    assert m.state_problem(st, THETA, OMEGA) == ""
    st[FA.X_HS + K.H_JUMPW] = value      # roller 1's history
    assert words in m.state_problem(st, THETA, OMEGA)


def test_the_speed_bound_is_ten_times_the_driven_motion():
    """(s + r) |omega| (1 + tan theta) at the paper's joint, 10 Hz, 8 deg: 0.041 m x 62.8 rad/s
    x 1.14 = 2.94 m/s; ten times that."""
    p = {"s": 0.022, "r_roller": 0.019}
    assert speed_bound(p, THETA, OMEGA, 0.0) == pytest.approx(
        10 * 0.041 * OMEGA * (1 + math.tan(THETA)), rel=1e-12)
    assert speed_bound(p, 0.0, 0.0, 0.0) == 10.0     # at rest: 1 m/s, ten times


@pytest.mark.parametrize("name,value", [("F_press", 5e-324), ("torque", 1e-310),
                                        ("omega", 2.2e-308), ("m_roller", 1e-310)])
def test_a_subnormal_value_is_refused_naming_the_parameter(name, value):
    with pytest.raises(ValueError, match=f"^{name} = .* is subnormal"):
        check_value(name, value)
    check_value(name, 0.0 if name != "m_roller" else 0.06)
    if name != "m_roller":
        check_value(name, 2.3e-308)    # the smallest normal numbers are values



@pytest.mark.parametrize("dt", [200.0, 1e300])
def test_a_step_longer_than_the_substeps_allow_is_refused_before_it_starts(dt):
    """At 10 Hz the substep is about 5e-5 s (a whirl cycle / 1960): a 200 s step would take
    about 4e6 substeps, over MAX_SUBSTEPS = 2^20; refused at once, the state untouched and the
    next ordinary step as if the long one had not been asked."""
    m = _settled({}, 10)
    twin = _settled({}, 10)
    y = m.rollers[0].Y.copy()
    with pytest.raises(StepRefused, match="take shorter communication steps"):
        m.step(dt, THETA, OMEGA, 0.0, 300.0)
    assert (m.rollers[0].Y == y).all()
    assert m.rollers[0]._hs[K.H_FAIL] == K.FAIL_LONG
    assert m.step(DT, THETA, OMEGA, 0.0, 300.0)["Fz"] == twin.step(DT, THETA, OMEGA, 0.0, 300.0)["Fz"]


def test_the_analytic_march_refuses_a_step_too_long():
    """The analytic FMU's march (its inputs moving) takes substeps of at most the table's
    spacing: at 10 Hz and 360 a cycle, a 1e6 s step would take 3.6e9 of them; refused before
    it starts, as the contact FMU's."""
    from reduced_model.scene import defaults, validate
    from reduced_model.traverse import Traverse
    tr = Traverse(validate(defaults("analytic"), "analytic"), periodic=False)
    with pytest.raises(StepRefused, match="take shorter communication steps"):
        tr.march(None, 0.0, 0.0, 1e6)
    s, p, x, out = tr.march(None, 0.0, 0.0, 1e-3)     # an ordinary step runs: 1 ms of whirl
    assert x == pytest.approx(2 * math.pi * 10 * 1e-3, rel=1e-12)
    assert all(math.isfinite(v) for v in out)


_HUGE_STEP = r"""
import json, sys
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
md = read_model_description(sys.argv[1]); d = extract(sys.argv[1])
vr = {v.name: v.valueReference for v in md.modelVariables}
logs = []
s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
              instanceName="t", fmiCallLogger=None)
s.instantiate(loggingOn=True, callbacks=None)
s.setupExperiment(startTime=0.0); s.enterInitializationMode(); s.exitInitializationMode()
for i in range(3):      # the inputs move: the march
    s.setReal([vr["theta"]], [0.17 + 1e-3 * i]); s.doStep(i * 1e-4, 1e-4)
before = s.getReal([vr["Fz"], vr["whirl_angle"]])
try:
    s.doStep(3e-4, 1e6); status = "OK"
except Exception as e:
    status = type(e).__name__
print(json.dumps({"status": status, "same": s.getReal([vr["Fz"], vr["whirl_angle"]]) == before}))
"""


def test_the_analytic_fmu_refuses_a_step_too_long():
    """The analytic FMU's march refuses a step of more than MAX_SUBSTEPS substeps before it
    starts, naming the count, the outputs untouched."""
    import json
    import subprocess
    import sys
    from harness.fmus import ensure_fmu
    from reduced_model.scene import MAX_SUBSTEPS
    fmu = ensure_fmu("TripodRollerAnalytic")
    p = subprocess.run([sys.executable, "-c", _HUGE_STEP, str(fmu)], capture_output=True,
                       text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    assert r["status"] != "OK" and r["same"], r
    assert f"needs more than the {MAX_SUBSTEPS:.0f} substeps" in p.stdout, p.stdout[-2000:]
    assert "step refused at t = 0.0003 s: the communication step of 1e+06 s" in p.stdout, \
        p.stdout[-2000:]
