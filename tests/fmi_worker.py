"""Runs FMI-level checks on a built FMU in its own process (called by test_driveline.py).

Usage: python fmi_worker.py FMU CHECK [INTEGER_START_VALUES_JSON]; prints one JSON object
and exits normally (the caller checks the exit status).
"""
import json
import sys

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

fmu, check = sys.argv[1], sys.argv[2]
INTS = json.loads(sys.argv[3]) if len(sys.argv) > 3 else {}
md = read_model_description(fmu)
d = extract(fmu)
vr = {v.name: v.valueReference for v in md.modelVariables}
OUT = ["Fx", "Fy", "Fz", "Fz_mod", "Fz_joint"] + [n for n in ("contact_y", "roller_spin") if n in vr]


def make(name="a", theta=None):
    s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=name)
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    if theta is not None:
        s.setReal([vr["theta"]], [theta])
    for k, v in INTS.items():
        s.setInteger([vr[k]], [int(v)])
    s.exitInitializationMode()
    return s


def run(s, n, t0=0.0, dt=1e-4):
    rows = []
    for i in range(n):
        s.doStep(t0 + i * dt, dt)
        rows.append(s.getReal([vr[k] for k in OUT]))
    return rows


res = {}
if check == "state":
    s = make()
    run(s, 500)
    st = s.getFMUstate()
    a = run(s, 300, 0.05)
    s.setFMUstate(st)
    b = run(s, 300, 0.05)
    blob = s.serializeFMUstate(st)
    st2 = s.deSerializeFMUstate(blob)
    s.setFMUstate(st2)
    c = run(s, 300, 0.05)
    res = {"rollback_identical": a == b, "serialized_identical": a == c, "n": len(a),
           "differs_from_start": a[0] != run(make("fresh"), 1)[0]}
elif check == "state-moving":
    # a master moving the pressing load every step; states taken before and after the inputs
    # first moved (the analytic FMU then steps its slide in time) and rolled back to
    def moving(s, i0, n, dt=1e-4):
        rows = []
        for i in range(i0, i0 + n):
            s.setReal([vr["F_press"]], [1000.0 + (2.0 * i if i >= 100 else 0.0)])
            s.doStep(i * dt, dt)
            rows.append(s.getReal([vr[k] for k in OUT]))
        return rows
    s = make()
    moving(s, 0, 50)
    st0 = s.getFMUstate()             # inputs not moved yet
    a0 = moving(s, 50, 150)
    st1 = s.getFMUstate()             # moving
    a1 = moving(s, 200, 300)
    s.setFMUstate(st1)
    b1 = moving(s, 200, 300)
    s.setFMUstate(st0)
    b0 = moving(s, 50, 150)
    c1 = moving(s, 200, 300)
    res = {"rollback_identical": a1 == b1, "before_identical": a0 == b0 and a1 == c1,
           "moves": a1[0] != a1[-1]}
elif check == "instances":
    a1 = run(make("solo_a", theta=0.10), 400)
    b1 = run(make("solo_b", theta=0.20), 400)
    x, y = make("x", theta=0.10), make("y", theta=0.20)
    a2, b2 = [], []
    for i in range(400):
        a2 += run(x, 1, i * 1e-4)
        b2 += run(y, 1, i * 1e-4)
    res = {"a_identical": a1 == a2, "b_identical": b1 == b2, "a_differs_b": a1 != b1}
elif check == "reset-moving":
    # a reset after a master moved the inputs (the analytic FMU was stepping its slide in
    # time): the run after it is the fresh instance's run
    s = make()
    for i in range(200):
        s.setReal([vr["F_press"]], [1000.0 + i])
        s.doStep(i * 1e-4, 1e-4)
    s.reset()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    res = {"reset_identical": run(s, 300) == run(make("fresh"), 300)}
elif check == "reset":
    s = make()
    a = run(s, 300)
    s.reset()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    b = run(s, 300)
    res = {"reset_identical": a == b}
print(json.dumps(res))
