"""Compiled steps against Python's.  Both joint FMUs run compiled throughout, without Python
(fmu_src/tripod_model/lifecycle.py and reduced_model/analytic_kernel.py under
fmu_src/native/fmi2_native.c): every output bit for bit the same lifecycle's run as Python in
process under the same FMPy master (harness/inprocess.py), also when the inputs change during
the run, and the same end-of-run log of how roller 1 was stepped."""
import json
import subprocess
import sys

import numpy as np
import pytest

from harness.fmus import ensure_fmu

_RUN = r'''
import json, sys, numpy as np
from fmpy import simulate_fmu
req = json.loads(sys.argv[1])
logs = []
inputs = None
if req["ramp"]:   # "steps": theta steps from 10 to 12 deg at 0.05 s, back at 0.1 s: the fast path
    # leaves and returns; "const": a table of 10 deg throughout
    t = np.array([0.0, 0.05 - 1e-9, 0.05, 0.1 - 1e-9, 0.1, 0.2])
    th = np.radians([10, 10, 12, 12, 10, 10] if req["ramp"] == "steps" else [10] * 6)
    inputs = np.array(list(zip(t, th)), dtype=[("time", float), ("theta", float)])
    if req["ramp"] == "master-torque":   # the transmitted torque moves every step
        inputs = np.array([(0.0, 60.0), (0.2, 66.0)], dtype=[("time", float), ("torque", float)])
    if req["ramp"] == "master-edges":   # to a straight joint at rest, the load from zero
        inputs = np.array([(0.0, np.radians(10), 20 * np.pi, 0.0), (0.2, 0.0, 0.0, 1000.0)],
                          dtype=[("time", float), ("theta", float), ("omega", float),
                                 ("F_press", float)])
    if req["ramp"] == "master":   # every input moves every step, as in a driveline run
        t = np.array([0.0, 0.2])
        inputs = np.array([(0.0, np.radians(10), 20 * np.pi, 1000.0),
                           (0.2, np.radians(12), 22 * np.pi, 1100.0)],
                          dtype=[("time", float), ("theta", float), ("omega", float),
                                 ("F_press", float)])
kw = dict(stop_time=0.2, output_interval=1e-4, start_values=req["sv"], input=inputs)
if req["inprocess"]:   # the lifecycle as Python, here
    from harness.inprocess import InProcess
    r = simulate_fmu(req["fmu"], fmu_instance=InProcess(req["fmu"], lambda s, m: logs.append(m)),
                     fmi_type="CoSimulation", **kw)
else:
    r = simulate_fmu(req["fmu"], debug_logging=True,
                     logger=lambda c, n, s, cat, msg: logs.append(msg.decode()), **kw)
np.save(req["out"], np.column_stack([r[n] for n in r.dtype.names]))
print(json.dumps([m for m in logs if m.startswith("roller 1:")]))
print(json.dumps(sum("compiled model, no Python" in m for m in logs)))
print(json.dumps([m for m in logs if m.startswith("communication steps:")]))
'''


ANALYTIC = "TripodRollerAnalytic"


def _run(tmp_path, sv, fast, ramp=False, fmu="TripodRoller"):
    """A run of the FMU under FMPy in a fresh process: compiled (fast "1"), or its lifecycle as
    Python in that process (fast "0")."""
    out = str(tmp_path / f"r{fast}.npy")
    req = {"fmu": str(ensure_fmu(fmu)), "sv": sv, "out": out, "inprocess": fast == "0",
           "ramp": "steps" if ramp is True else ramp}
    p = subprocess.run([sys.executable, "-c", _RUN, json.dumps(req)], capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    lines = p.stdout.strip().splitlines()
    return np.load(out), json.loads(lines[-3]), json.loads(lines[-2]), json.loads(lines[-1])


@pytest.mark.parametrize("sv,ramp", [({}, False), ({"bearing": 1}, False),
                                     ({"integrator": 1}, False), ({}, True), ({}, "master"),
                                     ({"integrator": 1, "bearing": 1}, "master"),
                                     ({}, "master-torque"), ({"n_rollers": 3}, False),
                                     ({"n_rollers": 3, "bearing": 1}, "master")],
                         ids=["default", "lumped", "integrator1", "theta-steps", "master",
                              "master-integrator1-lumped", "master-torque", "three-rollers",
                              "three-rollers-lumped-master"])
def test_fast_path_is_bitwise_the_python_step(tmp_path, sv, ramp):
    slow, slow_log, slow_said, _ = _run(tmp_path, sv, "0", ramp)
    fast, fast_log, fast_said, steps = _run(tmp_path, sv, "1", ramp)
    assert (slow_said, fast_said) == (0, 1)   # the compiled model ran in one run only
    assert slow.shape == fast.shape and np.array_equal(slow, fast)
    assert np.ptp(fast[:, 3]) > 1.0          # Fz moves (not two runs of zeros)
    # the end-of-run log: the same substeps over the same time (FMPy's step sizes t_{k+1} -
    # t_k differ in their last bits: both take those as the same step)
    assert slow_log and slow_log == fast_log, (slow_log, fast_log)
    assert steps == ["communication steps: 2000, each compiled (no Python)"], steps


@pytest.mark.parametrize("sv,ramp", [({}, False), ({"traverse": False, "n_rollers": 3}, False),
                                     ({}, True), ({}, "master"), ({"n_rollers": 3}, "master"),
                                     ({}, "master-torque"), ({}, "master-edges")],
                         ids=["traverse-table", "eqs18-27-three-rollers", "theta-steps",
                              "master", "master-three-rollers", "master-torque",
                              "master-to-straight-and-rest"])
def test_analytic_native_is_bitwise_its_lifecycle_in_python(tmp_path, sv, ramp):
    """The analytic FMU compiled, without Python, against its kernel as Python in process: the table's interpolation and Eqs. (18)-(27) alike, across input changes, and
    the march under a master that moves the inputs every step, down to theta = 0, omega = 0
    and from no load."""
    slow, _, _, slow_steps = _run(tmp_path, sv, "0", ramp, ANALYTIC)
    fast, _, _, steps = _run(tmp_path, sv, "1", ramp, ANALYTIC)
    assert slow.shape == fast.shape and np.array_equal(slow, fast)
    assert np.ptp(fast[:, 3]) > 0.1     # Fz (columns time, Fx, Fy, Fz, ...) moves
    # one table at the start; once theta moves the slide is stepped in time (no new tables)
    # (no table when the run starts unloaded)
    tables = 0 if sv.get("traverse") is False or ramp == "master-edges" else 1
    tail = f"; traverse tables derived: {tables}" + (
        "; the slide stepped in time since the inputs moved"
        if ramp and sv.get("traverse") is not False else "")
    assert slow_steps == steps == ["communication steps: 2000" + tail], (slow_steps, steps)


def test_analytic_input_table_at_a_constant_value_is_no_input(tmp_path):
    """FMPy's interpolation of a constant stretch of an input table moves the input's last bits
    (tests above: a quarter of the steps): the analytic FMU keeps its operating point then
    (scene.same_value), so the run is bit for bit the run without an input table, instead of
    stepping the slide in time from the first such step."""
    plain, _, _, _ = _run(tmp_path, {}, "0", False, "TripodRollerAnalytic")
    table, _, _, _ = _run(tmp_path, {}, "0", "const", "TripodRollerAnalytic")
    assert plain.shape == table.shape and np.array_equal(plain, table)


# an instance of the FMU at sys.argv[1] in its initialisation mode, its log on stdout
_INSTANCE = r'''
import json, sys
import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
md = read_model_description(sys.argv[1]); d = extract(sys.argv[1])
vr = {v.name: v.valueReference for v in md.modelVariables}
if sys.argv[-1] == "inprocess":   # the FMU's lifecycle as Python, here
    from harness.inprocess import InProcess
    s = InProcess(sys.argv[1], lambda status, msg: print(  # (as FMPy's default logger)
        f"[{('OK', 'Warning', 'Discard', 'Error', 'Fatal', 'Pending')[status]}] {msg}"))
else:
    s = FMU2Slave(guid=md.guid, unzipDirectory=d,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName="test")
s.instantiate(loggingOn=True); s.setupExperiment(startTime=0.0)
s.enterInitializationMode()

def step_refused(set_bad, dt=1e-4):
    """Set a bad input (set_bad()), try the step at 50 dt; print its status and the outputs
    before and after it."""
    before = s.getReal([vr["Fz"], vr["Fx"], vr["whirl_angle"]])
    set_bad()
    try:
        s.doStep(50 * dt, dt)
        status = "OK"
    except Exception as e:
        status = type(e).__name__
    after = s.getReal([vr["Fz"], vr["Fx"], vr["whirl_angle"]])
    print(json.dumps({"status": status, "before": before, "after": after}))
'''


def _how(fast):
    """The last argument of an _INSTANCE script: the compiled FMU (fast "1"), or its lifecycle
    as Python in process (fast "0")."""
    return "compiled" if fast == "1" else "inprocess"


# ... initialised
_SLAVE = _INSTANCE + "s.exitInitializationMode()\n"

_BAD = _SLAVE + r'''
dt = 1e-4
for i in range(50):   # compiled after the first step
    s.setReal([vr["theta"], vr["omega"]], [0.17 + 1e-5 * i, 62.8 + 1e-3 * i])
    s.doStep(i * dt, dt)
step_refused(lambda: s.setReal([vr["theta"]], [float(sys.argv[2])]))
'''


@pytest.mark.parametrize("fmu", ["TripodRoller", "TripodRollerAnalytic"])
@pytest.mark.parametrize("value", ["1.0", "nan"])
def test_bad_input_set_while_the_compiled_step_runs_is_reported(value, fmu):
    """An input set out of its range while steps run compiled (the analytic FMU: its march,
    the inputs moving every step): the step is refused with a log naming the input and its
    range, the outputs stay those of the last good step."""
    p = subprocess.run([sys.executable, "-c", _BAD, str(ensure_fmu(fmu)), value],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    assert r["status"] != "OK" and r["after"] == r["before"], r
    assert "invalid input" in p.stdout and "theta" in p.stdout and "allowed range" in p.stdout, \
        p.stdout[-2000:]


_MOVING = _INSTANCE + r'''
s.setBoolean([vr["needle_row"]], [sys.argv[2] == "row"])
s.exitInitializationMode()
dt, n, w = 1e-4, 3000, 20 * np.pi
out = []
for i in range(n):   # the pressing load steps 1000 -> 2000 N at 0.01 s; omega moves in its
    # last bits every step, as a master interpolating its speed would
    s.setReal([vr["omega"], vr["F_press"]], [w * (1.0 + 1e-15 * (i % 3)),
                                              1000.0 if i < 100 else 2000.0])
    s.doStep(i * dt, dt)
    out.append(s.getReal([vr["Fz_mod"]])[0])
s.terminate(); s.freeInstance()
print(json.dumps(out))
'''


@pytest.mark.parametrize("row, tol", [("row", 1e-2), ("ideal", 1e-3)])
def test_analytic_steps_the_slide_in_time_when_inputs_move(row, tol):
    """Inputs that move no longer cost a new traverse table each (0.05 s or more): the slide is
    stepped in time (Traverse.march) from the start's settled table.  After a step of the
    pressing load it settles on the new operating point's periodic solution, which the secant
    on the cycle map finds independently: orders 1 and 3 within 1e-3 without the needle row
    (the table's 360 points hold order 3 within 2e-4 of 1440, the march steps at 1e-4 s,
    finer); within 1 % with it, whose tilt goes by backward Euler, first order in the step (the
    table at 2.8e-4 s and the march part by 0.3-0.65 %, tests/test_reduced_row.py)."""
    from reduced_model import scene as sc
    from reduced_model.orders import last_cycle_orders
    from reduced_model.traverse import Traverse
    p = subprocess.run([sys.executable, "-c", _MOVING, str(ensure_fmu("TripodRollerAnalytic")),
                        row], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    assert p.stdout.count("the inputs moved: from here on") == 1, p.stdout[-3000:]
    assert "traverse tables derived: 1; the slide stepped in time" in p.stdout
    fz = np.array(json.loads(p.stdout.strip().splitlines()[-1]))
    t = 1e-4 * np.arange(1, fz.size + 1)
    got = last_cycle_orders(t, fz, 20 * np.pi * t)
    want = Traverse(sc.validate({"F_press": 2000.0, "needle_row": row == "row"},
                                "analytic")).orders()
    for k in (1, 3):
        c = [a * np.exp(1j * np.radians(ph)) for a, ph in (got[k], want[k])]
        assert abs(c[0] - c[1]) < tol * abs(c[1]), (k, got[k], want[k])


# a master whose communication step varies every step (a variable-step or event-driven master),
# the inputs moving as args say; prints the outputs and the end-of-run log's step count
_VARYING = _INSTANCE + r'''
args = json.loads(sys.argv[2])
for k, v in args["ints"].items():
    s.setInteger([vr[k]], [v])
if args.get("angle"):
    s.setBoolean([vr["drive_by_angle"]], [True])
s.exitInitializationMode()
names = ["Fz", "Fx", "Fz_joint", "whirl_angle", "plunge", "Fz_mod"]
rng = np.random.default_rng(7)
t, out = 0.0, []
for i in range(1500):
    h = float(rng.uniform(2e-5, 2e-4))
    if args["move"]:
        s.setReal([vr["theta"], vr["omega"], vr["torque"]],
                  [0.17 + 0.02 * np.sin(30 * t), 62.8 * (1 + 2 * t), 300.0 - 100 * t])
    if args.get("angle"):   # the shaft angle the master integrates, for the step's end
        s.setReal([vr["shaft_angle"]], [62.8 * ((t + h) + (t + h) ** 2)])
    s.doStep(t, h)
    t += h
    out.append(s.getReal([vr[n] for n in names]))
s.terminate(); s.freeInstance()
print(json.dumps(out))
'''


@pytest.mark.parametrize("fmu,ints,move,angle", [
    ("TripodRoller", {}, False, False),
    ("TripodRoller", {"n_rollers": 3, "bearing": 1}, True, False),
    ("TripodRoller", {"n_rollers": 3}, True, True),
    ("TripodRollerAnalytic", {"n_rollers": 3}, False, False),
    ("TripodRollerAnalytic", {}, True, False), ("TripodRollerAnalytic", {}, True, True)],
    ids=["contact", "contact-three-lumped-moving", "contact-three-by-angle",
         "analytic-table-three", "analytic-march", "analytic-by-angle"])
def test_a_varying_step_size_runs_compiled_bitwise_the_python_step(fmu, ints, move, angle):
    """A master that changes the communication step at every step (uniform in 20-200 us):
    the compiled step takes each new size (it derives its operating point at it, as the
    model's own step does), so every step after the first runs compiled, and the outputs are
    the Python step's bit for bit (before, each new size went through Python: 2.8x the cost
    of the contact FMU's fixed step, 12x the analytic FMU's).  Driven by angle (a run-up's
    shaft angle set for each step's end), the layer derives omega as the slave's step does."""
    runs = {}
    for fast in ("0", "1"):
        p = subprocess.run([sys.executable, "-c", _VARYING, str(ensure_fmu(fmu)),
                            json.dumps({"ints": ints, "move": move, "angle": angle}),
                            _how(fast)], capture_output=True, text=True, timeout=600)
        assert p.returncode == 0, p.stderr[-3000:]
        steps = [m for m in p.stdout.splitlines() if "communication steps:" in m]
        runs[fast] = (np.array(json.loads(p.stdout.strip().splitlines()[-1])), steps)
    (slow, slow_steps), (fast, fast_steps) = runs["0"], runs["1"]
    assert slow.shape == fast.shape == (1500, 6) and np.array_equal(slow, fast)
    assert np.ptp(fast[:, 2]) > 1.0           # Fz_joint moves
    if angle:   # the whirl follows the master's angle (to rounding: 1e-9 rad of up to 15 rad)
        tt = np.cumsum(np.random.default_rng(7).uniform(2e-5, 2e-4, 1500))
        assert np.allclose(fast[:, 3], 62.8 * (tt + tt ** 2), rtol=0, atol=1e-9)
    # the same functions: the same log
    assert slow_steps == fast_steps and "communication steps: 1500" in fast_steps[0]


_ANGLE_JUMP = _INSTANCE + r'''
s.setBoolean([vr["drive_by_angle"]], [True])
s.exitInitializationMode()
dt, w = 1e-4, 62.8
for i in range(50):   # compiled after the first step
    s.setReal([vr["shaft_angle"]], [w * (i + 1) * dt])
    s.doStep(i * dt, dt)
# 2 rad in one step: omega 2e4 rad/s
step_refused(lambda: s.setReal([vr["shaft_angle"]], [w * 50 * dt + 2.0]))
'''


@pytest.mark.parametrize("fmu", ["TripodRoller", "TripodRollerAnalytic"])
def test_driving_by_angle_out_of_omega_range_is_refused_on_the_compiled_path(fmu):
    """Driven by angle, a shaft angle that asks for an omega out of its range within one
    step (2 rad in 100 us: 2e4 rad/s against 1e4) while the steps run compiled: the layer
    hands the step to the slave, which refuses it naming omega and its range; the outputs stay
    those of the last good step."""
    p = subprocess.run([sys.executable, "-c", _ANGLE_JUMP, str(ensure_fmu(fmu))],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    assert r["status"] != "OK" and r["after"] == r["before"], r
    assert "compiled model, no Python" in p.stdout, p.stdout[-2000:]
    assert "omega" in p.stdout and "allowed range" in p.stdout, p.stdout[-2000:]


_ROLLBACK = _VARYING.split("rng = np.random")[0] + r'''
t, out = 0.0, []
for i in range(300):   # an iterative master: state, a trial step, back, the step it keeps
    h = 1e-4
    if args["move"] and i >= args.get("hold", 0):
        s.setReal([vr["theta"], vr["torque"]], [0.17 + 0.02 * np.sin(300 * t), 300.0 - 1e3 * t])
    if args.get("angle"):
        s.setReal([vr["shaft_angle"]], [62.8 * ((t + h) + (t + h) ** 2)])
    if args.get("plain"):   # the same run without rollback
        s.doStep(t, h)
        t += h
        out.append(s.getReal([vr[n] for n in names]))
        continue
    st = s.getFMUstate()
    s.doStep(t, h)
    trial = s.getReal([vr[n] for n in names])
    s.setFMUstate(st)
    s.freeFMUstate(st)
    s.doStep(t, h)
    t += h
    kept = s.getReal([vr[n] for n in names])
    assert kept == trial, (i, kept, trial)
    out.append(kept)
s.terminate(); s.freeInstance()
print(json.dumps(out))
'''


@pytest.mark.parametrize("fmu,ints,move,angle,hold", [
    ("TripodRoller", {}, False, False, 0),
    ("TripodRoller", {"n_rollers": 3, "bearing": 1}, True, False, 0),
    ("TripodRoller", {"n_rollers": 3}, True, True, 0),
    ("TripodRollerAnalytic", {"n_rollers": 3}, True, False, 0),
    ("TripodRollerAnalytic", {"n_rollers": 3}, True, False, 5)],
    ids=["default", "three-lumped-moving", "three-by-angle", "analytic-three-moving",
         "analytic-three-moving-after-its-table"])
def test_a_rollback_every_step_runs_compiled_bitwise_the_python_step(fmu, ints, move, angle,
                                                                     hold):
    """An iterative master (get the state, a trial step, set the state back, the step again,
    every step): the repeated step equals the trial bit for bit, and the run equals the same
    run through Python (the lifecycle in process) and the run without rollback.  hold: the inputs move
    from that step on, so states are taken on the analytic FMU's settled table after steps
    were taken there."""
    runs = {}
    for fast, plain in (("0", False), ("1", False), ("1", True)):
        p = subprocess.run([sys.executable, "-c", _ROLLBACK, str(ensure_fmu(fmu)),
                            json.dumps({"ints": ints, "move": move, "angle": angle,
                                        "plain": plain, "hold": hold}), _how(fast)],
                           capture_output=True, text=True, timeout=600)
        assert p.returncode == 0, p.stderr[-3000:]
        steps = [m for m in p.stdout.splitlines() if "communication steps:" in m]
        runs[fast, plain] = (np.array(json.loads(p.stdout.strip().splitlines()[-1])), steps)
    (slow, _), (fast, fast_steps) = runs["0", False], runs["1", False]
    plain = runs["1", True][0]
    assert slow.shape == fast.shape == plain.shape == (300, 6)
    assert np.array_equal(slow, fast) and np.array_equal(fast, plain)
    assert np.ptp(fast[:, 2]) > 1.0
    if fmu == "TripodRoller":   # (a state holds the step count: the kept steps only)
        assert "communication steps: 300, each compiled (no Python)" in fast_steps[0], \
            fast_steps


# coast and reverse whirl under a master moving the inputs at a varying step (the analytic
# FMU's march, compiled); args["case"] names the input history
_QUADRANTS = _INSTANCE + r'''
args = json.loads(sys.argv[2])
s.setInteger([vr["n_rollers"]], [3])
s.exitInitializationMode()
names = ["Fz", "Fx", "Fy", "Fz_joint", "whirl_angle", "plunge", "Fz_mod", "dFx", "F_housing_x",
         "F_housing_y", "T_housing", "F_roller", "slip_speed"]
rng = np.random.default_rng(7)
t, out = 0.0, []
for i in range(1500):
    h = float(rng.uniform(2e-5, 2e-4))
    th, w, fp, tq = 0.17 + 0.02 * np.sin(30 * t), 62.8 * (1 + 2 * t), 1000.0, 0.0
    if args["case"] == "coast":            # engine braking: a negative torque
        tq = -300.0 + 100 * t
    elif args["case"] == "reverse":        # reverse whirl in drive
        w, tq = -w, 300.0 - 100 * t
    elif args["case"] == "coast-by-load":  # F_press below 0, no torque
        fp = -2000.0 + 1000 * t
    else:                                  # a tip-out: the torque through zero
        tq = 300.0 - 4000 * t
    s.setReal([vr["theta"], vr["omega"], vr["F_press"], vr["torque"], vr["plunge_speed"]],
              [th, w, fp, tq, 0.01 * np.sin(50 * t)])
    s.doStep(t, h)
    t += h
    out.append(s.getReal([vr[n] for n in names]))
s.terminate(); s.freeInstance()
print(json.dumps(out))
'''


@pytest.mark.parametrize("case", ["coast", "reverse", "coast-by-load", "tip-out"])
def test_coast_and_reverse_run_compiled_bitwise_the_python_step(case):
    """Coast (torque or F_press below 0) and reverse whirl under a master that moves every
    input at a varying step, through a tip-out: the analytic FMU's compiled march runs them as
    its kernel as Python does, drive at the opposite whirl turned about the trunnion axis,
    bit for bit."""
    runs = {}
    for fast in ("0", "1"):
        p = subprocess.run([sys.executable, "-c", _QUADRANTS,
                            str(ensure_fmu(ANALYTIC)), json.dumps({"case": case}), _how(fast)],
                           capture_output=True, text=True, timeout=600)
        assert p.returncode == 0, p.stderr[-3000:]
        steps = [m for m in p.stdout.splitlines() if "communication steps:" in m]
        runs[fast] = (np.array(json.loads(p.stdout.strip().splitlines()[-1])), steps)
    (slow, _), (fast, fast_steps) = runs["0"], runs["1"]
    assert slow.shape == fast.shape == (1500, 13) and np.array_equal(slow, fast)
    assert np.ptp(fast[:, 3]) > 1.0 and np.isfinite(fast).all()
    assert runs["0"][1] == fast_steps and "communication steps: 1500" in fast_steps[0]
