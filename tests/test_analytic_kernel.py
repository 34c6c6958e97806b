"""reduced_model/analytic_kernel.py, the analytic FMU's one source: run as Python (the
in-process oracle, the reports) and compiled (the FMU's binary) it gives the same bits; its notes word what
the Python reports and the table's checks word; its state check refuses what it cannot step."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from harness.fmus import ensure_fmu
from harness.inprocess import _layout_and_model
from reduced_model import analytic_kernel as K
from reduced_model import scene as sc
from reduced_model.traverse import outside_checked

# the FMU's binary under a host's calls, in a fresh process: its parameters set, initialised,
# then each step's inputs set and stepped; every Real output and the state's X after each
_NATIVE = r'''
import json, struct, sys
import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
fmu, req = sys.argv[1], json.loads(sys.argv[2])
md = read_model_description(fmu)
var = {v.name: v for v in md.modelVariables}
s = FMU2Slave(guid=md.guid, unzipDirectory=extract(fmu),
              modelIdentifier=md.coSimulation.modelIdentifier, instanceName="native")
s.instantiate()
s.setupExperiment(startTime=0.0)
s.enterInitializationMode()
for name, value in req["set"].items():
    v = var[name]
    {"Real": s.setReal, "Integer": s.setInteger,
     "Boolean": s.setBoolean}[v.type]([v.valueReference], [value])
s.exitInitializationMode()
real = [v for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
outs = [v.valueReference for v in real]
rows, xs = [], []
for t, h, ins in req["steps"]:
    for name, value in ins.items():
        s.setReal([var[name].valueReference], [value])
    s.doStep(t, h)
    rows.append(s.getReal(outs))
    blob = s.serializeFMUstate(s.getFMUstate())
    at = req["header"] + 8 * req["x_at"]
    xs.append(struct.unpack_from(f"<{req['x_len']}d", blob, at))
np.save(req["out"], np.array(rows))
np.save(req["out"] + ".x.npy", np.array(xs))
print(json.dumps([v.name for v in real]))
'''
HEADER = 8 + 4 * 4 + 6 * 4 + 8      # fmi2_native.c's state: magic, 4 words, 6 sizes, time


def _arrays(over):
    vals = sc.defaults("analytic")
    vals.update(over)
    T = np.array([float(vals[n]) for n in K.PARAM_NAMES])
    IN = np.array([float(vals[n]) for n in K.INPUT_NAMES])
    return T, IN, np.zeros(K.X_LEN), np.zeros(K.OUT_LEN), np.zeros(K.W_LEN)


def _ramp(i, v):
    return {"theta": v["theta"] + 1e-4 * i, "omega": v["omega"] * (1 + 1e-3 * i)}


SCENES = {   # name: (parameters and start inputs, the inputs at step i)
    "table": ({}, lambda i, v: {}),
    "march": ({}, _ramp),
    "three-rollers": ({"n_rollers": 3}, _ramp),
    "reverse": ({"omega": -60.0}, lambda i, v: {}),
    "coast-through-zero": ({"torque": -300.0}, lambda i, v: {"torque": -300.0 + 3 * i}),
    "eqs-18-27": ({"traverse": False, "n_rollers": 3}, _ramp),
    "plunge": ({"plunge_speed": 0.05}, _ramp),
    "launch": ({"torque": 3000.0, "theta": 0.4, "omega": 3.0}, _ramp),
    "by-angle": ({"drive_by_angle": True}, lambda i, v: {"shaft_angle": 62.8e-4 * (i + 1)}),
    "row-march": ({"needle_row": True, "n_rollers": 3}, _ramp),
    "row-coast-through-zero": ({"needle_row": True, "torque": -300.0},
                               lambda i, v: {"torque": -300.0 + 3 * i}),
    "row-launch": ({"needle_row": True, "torque": 3000.0, "theta": 0.14, "omega": 30.0}, _ramp),
    "row-reverse": ({"needle_row": True, "omega": -60.0}, lambda i, v: {}),
}


@pytest.mark.parametrize("name", sorted(SCENES))
def test_the_binary_and_python_give_the_same_bits(name, tmp_path):
    """init and 200 steps (a varying step size) with the inputs moving: every output and the
    state X after every step equal to the last bit, the FMU's binary in a fresh process (the
    kernel compiled, no Python) against the kernel as Python here."""
    over, inputs = SCENES[name]
    vals = dict(sc.defaults("analytic"), **over)
    T, IN, X, OUT, W = _arrays(over)
    assert K.init(T, IN, X, OUT, W) == 1
    rng = np.random.default_rng(1)
    t, steps, rows, xs = 0.0, [], [], []
    for i in range(200):
        h = float(rng.uniform(5e-5, 2e-4))
        ins = inputs(i, vals)
        for n, v in ins.items():
            IN[K.INPUT_NAMES.index(n)] = v
        assert K.step(T, IN, X, OUT, W, t, h) == 1
        steps.append((t, h, ins))
        rows.append(OUT.copy())
        xs.append(X.copy())
        t += h
    fmu = ensure_fmu("TripodRollerAnalytic")
    req = {"set": {n: over[n] for n in over}, "steps": steps, "out": str(tmp_path / "r.npy"),
           "header": HEADER, "x_at": len(T) + len(IN), "x_len": len(X)}
    p = subprocess.run([sys.executable, "-c", _NATIVE, str(fmu), json.dumps(req)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    native, native_x = np.load(req["out"]), np.load(req["out"] + ".x.npy")
    names = json.loads(p.stdout.strip().splitlines()[-1])
    slots = [_layout_and_model("TripodRollerAnalytic")[0]["arrays"][n][1] for n in names]
    python = np.array(rows)[:, slots]            # (the binary's outputs in their order)
    assert np.array_equal(native_x, np.array(xs))
    assert np.array_equal(native, python), _first_difference(native, python, names)
    assert np.ptp(python[:, names.index("Fz")]) > 0 and np.isfinite(native).all()


def _first_difference(native, python, names):
    i, j = np.argwhere(native != python)[0]
    return f"step {i}, {names[j]}: {native[i, j]!r} against {python[i, j]!r}"


def test_the_notes_word_what_the_reports_word():
    """The FMU's warning at the start names what the CLI's report names outside the checked
    range; a parameter relation is refused in the table's words (scene.validate)."""
    over = {"omega": 500.0, "torque": 13.2, "r_roller": 0.0185, "r_groove": 0.0188}
    T, IN, X, OUT, W = _arrays(over)
    assert K.init(T, IN, X, OUT, W) == 1
    [(level, text)] = K.notes_text(W)
    assert level == K.WARNING
    assert text.split(": ", 1)[1].split("; ") == \
        outside_checked(sc.validate(over, "analytic"))
    for bad in ({"r_groove": 0.018}, {"r_bore": 0.02}, {"n_rollers": 2}, {"mu_groove": 1.0}):
        T, IN, X, OUT, W = _arrays(bad)
        assert K.init(T, IN, X, OUT, W) == 3
        with pytest.raises(ValueError) as e:
            sc.validate(bad, "analytic")
        assert K.notes_text(W) == [(K.ERROR, str(e.value))]


def test_a_state_it_cannot_step_is_refused():
    """kernel.state_problem: a mode, flag or count the model never writes; an operating
    point's input out of range; a march row's p beyond mu_groove (|p| <= mu: T3); a step not
    above 0; the needle row's kept constants not its needles' or its kept offset not the one at
    its kept load (row_point takes them as they are).  A state the model wrote passes."""
    T, IN, X, OUT, W = _arrays({})
    K.init(T, IN, X, OUT, W)
    IN[K.THETA] += 0.01
    K.step(T, IN, X, OUT, W, 0.0, 1e-4)          # the march
    assert K.state_problem(T, X) == 0
    assert X[K.X_OP + K.O_RN] == T[K.N_NEEDLES] and X[K.X_OP + K.O_RA] > 0   # (the row kept)
    other = T.copy()
    other[K.N_NEEDLES] += 1                      # kept for other needles: recomputed, not read
    bad = X.copy()
    bad[K.X_OP + K.O_RC1] = 0.0
    assert K.state_problem(other, bad) == 0
    for slot, value, code in ((K.X_MODE, 7.0, 1), (K.X_HAS_DT, 0.5, 1),
                              (K.X_KEY + K.OMEGA, 2e4, 2),
                              (K.X_MARCH + K.R_P, 2 * T[K.MU_GROOVE], 3), (K.X_DT, -1e-4, 4),
                              (K.X_OP + K.O_RC1, X[K.X_OP + K.O_RC1] * (1 + 1e-12), 5),
                              (K.X_OP + K.O_RKR, 0.0, 5),
                              (K.X_OP + K.O_RA, X[K.X_OP + K.O_RA] * 1e3, 5),
                              (K.X_OP + K.O_RAF, 0.0, 5)):
        bad = X.copy()
        bad[slot] = value
        assert K.state_problem(T, bad) == code, K.STATE_PROBLEMS[code]


def test_a_step_too_long_is_refused_before_it_starts():
    """More than MAX_SUBSTEPS substeps of the table's spacing (the march): refused, the state
    untouched, the note naming the step and the substep."""
    T, IN, X, OUT, W = _arrays({})
    K.init(T, IN, X, OUT, W)
    IN[K.THETA] += 0.01
    K.step(T, IN, X, OUT, W, 0.0, 1e-4)
    before = X.copy()
    assert K.step(T, IN, X, OUT, W, 1e-4, 1e6) == 3
    [(level, text)] = K.notes_text(W)
    h = 2 * math.pi / (20 * math.pi * K.N_PER_CYCLE)
    assert level == K.ERROR and text.startswith(f"the communication step of 1e+06 s in "
                                                f"substeps of {h:.3g} s needs more than")
    assert np.array_equal(X, before)
