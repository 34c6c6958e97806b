"""Transients under a driveline master, through the contact model in process (the kernel the
FMU runs, bit for bit: tests/test_prebuilt.py): input steps against a converged reference, and
order 3 per revolution along a run-up against the settled constant-speed value.  Used by
benchmarks/transients.py (the table in docs/benchmarks.md) and tests/test_transients.py.
"""
from __future__ import annotations

import math

import numpy as np

from reduced_model.orders import order_spectrum
from reduced_model.scene import defaults, validate

from .fmus import ROOT

DT = 1e-4
THETA, TORQUE = math.radians(8.0), 300.0
INPUTS = ("omega", "theta", "torque")
SIZES = (1.01, 0.99, 1.10, 0.90)


def _model(params, n_rollers, **extra):
    import sys
    sys.path.insert(0, str(ROOT / "fmu_src"))
    from tripod_model.model import JointModel
    return JointModel(validate(dict(defaults("contact"), n_rollers=n_rollers, **params, **extra),
                               "contact"))


def settle(params, n_rollers, f, cycles=2):
    """The model after ``cycles`` whirl cycles at f [Hz], and order 3 of Fz_joint over the last
    [N]."""
    m = _model(params, n_rollers)
    w = 2 * math.pi * f
    n = int(round(cycles / f / DT))
    y, x = [], []
    for _ in range(n):
        o = m.step(DT, THETA, w, 0.0, TORQUE)
        y.append(o["Fz_joint"])
        x.append(o["whirl_angle"])
    x, y = np.array(x), np.array(y)
    xs = x[-1] - 2 * math.pi + 2 * math.pi * np.arange(720) / 720
    return m, order_spectrum(np.interp(xs, x, y), 1, (3,))[0][0]


def response(m, inputs, steps, sub=1):
    out = []
    for i in range(steps * sub):
        o = m.step(DT / sub, inputs["theta"], inputs["omega"], 0.0, inputs["torque"])
        if (i + 1) % sub == 0:
            out.append(o["Fz_joint"])
    return np.array(out)


def reference(params, n_rollers, state, inputs, steps, h):
    """From ``state``, the same inputs with the substep h / 10 and the communication step
    DT / 10, accelerations afresh."""
    r = _model(params, n_rollers, max_substep=h / 10)
    r.set_state(state)
    for roller in r.rollers:
        roller._hs[3] = 0.0
    return response(r, inputs, steps, sub=10)


def case(params, n_rollers, f, name, factor, base):
    m, a3 = base
    st = m.get_state()
    h = m.rollers[0].substep(THETA, 2 * math.pi * f, TORQUE / (3 * m.p["s"]),
                             m.rollers[0].v_st(THETA, 2 * math.pi * f))
    inputs = {"theta": THETA, "omega": 2 * math.pi * f, "torque": TORQUE}
    inputs[name] *= factor
    y = response(m, inputs, 20)
    m.set_state(st)
    ref = reference(params, n_rollers, st, inputs, 20, h)
    return 100 * np.abs(y - ref).max() / a3



def order3_per_revolution(x, y):
    """[(mean whirl speed index range, order 3 amplitude)] per whole revolution of whirl angle x
    [rad] (samples y, x rising): each revolution resampled uniformly in angle."""
    out = []
    k = 1
    while k * 2 * math.pi <= x[-1]:
        xs = (k - 1) * 2 * math.pi + 2 * math.pi * np.arange(720) / 720
        i0, i1 = np.searchsorted(x, (k - 1) * 2 * math.pi), np.searchsorted(x, k * 2 * math.pi)
        out.append(((i0, i1), order_spectrum(np.interp(xs, x, y), 1, (3,))[0][0]))
        k += 1
    return out


def runup(params, n_rollers, f0, f1, T, dt=DT):
    """Whirl from f0 to f1 [Hz] in T [s], the master setting omega at the start of each step
    and holding it: [(mean speed [Hz], order 3 of Fz_joint [N])] per revolution."""
    m = _model(params, n_rollers)
    n = int(round(T / dt))
    x, y = [0.0], [m.initial_outputs(THETA, 2 * math.pi * f0, 0.0, TORQUE)["Fz_joint"]]
    for i in range(n):
        w = 2 * math.pi * (f0 + (f1 - f0) * i * dt / T)
        o = m.step(dt, THETA, w, 0.0, TORQUE)
        x.append(o["whirl_angle"])
        y.append(o["Fz_joint"])
    x, y = np.array(x), np.array(y)
    return [((x[i1] - x[i0]) / ((i1 - i0) * dt) / (2 * math.pi), a)
            for (i0, i1), a in order3_per_revolution(x, y)]
