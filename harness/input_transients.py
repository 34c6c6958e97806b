"""Transients under a driveline master, through the contact model in process (the kernel the
FMU compiles): input steps against a converged reference, and
order 3 per revolution along a run-up against the settled constant-speed value.  Used by
benchmarks/transients.py (the table in docs/benchmarks.md) and tests/test_transients.py.
"""
from __future__ import annotations

import math

import numpy as np

from reduced_model.orders import last_cycle_orders, order_spectrum
from reduced_model.scene import (BY_NAME, PARAMS, analytic_counterpart, check_value, defaults,
                                 validate)

DT = 1e-4
THETA, TORQUE = math.radians(8.0), 300.0
INPUTS = ("omega", "theta", "torque")
SIZES = (1.01, 0.99, 1.10, 0.90)
# the table's launch rows (benchmarks/transients.py; docgen checks its rows): the whole joint
# at a launch's load and angle
LAUNCH_ROW = "ideal, 3000 N m, 25 deg"
LAUNCH_THETA, LAUNCH_TORQUE = math.radians(25.0), 3000.0
# its needle-resolved rows: single samples; single samples against a 1e-15 twin; the 1 ms mean
RESOLVED_ROWS = ("needle-resolved", "needle-resolved, rounding (1e-15)",
                 "needle-resolved, 1 ms mean")
# and order 3 over the whirl cycle after each theta step (cycle_case; the other cells left out)
RESOLVED_CYCLE_ROW = "needle-resolved, order 3 over the cycle after"
# and its rows at a launch's torque (single samples): (label, theta [rad])
RESOLVED_LAUNCH = (("needle-resolved, 3000 N m, 8 deg", THETA),
                   ("needle-resolved, 3000 N m, 25 deg", LAUNCH_THETA))
# the same row with one Newton pass a substep (newton_passes = 1): single samples and the 1e-15 twin at 300 N m, single samples at a launch's
# torque and angle: (label, parameters, theta [rad], torque [N m], case's keywords)
ONE_PASS = {"bearing": 2, "newton_passes": 1}
RESOLVED_ONE_PASS = (("needle-resolved, one pass", ONE_PASS, THETA, TORQUE, {}),
                     ("needle-resolved, one pass, rounding (1e-15)", ONE_PASS, THETA, TORQUE,
                      {"perturb": 1e-15}),
                     ("needle-resolved, one pass, 3000 N m, 25 deg", ONE_PASS, LAUNCH_THETA,
                      LAUNCH_TORQUE, {}))


def _model(params, n_rollers, **extra):
    from tripod_model.model import JointModel
    return JointModel(validate(dict(defaults("contact"), n_rollers=n_rollers, **params, **extra),
                               "contact"))


def settle(params, n_rollers, f, cycles=2, theta=THETA, torque=TORQUE, nudge=0.0):
    """The model after ``cycles`` whirl cycles at f [Hz], theta [rad] and torque [N m], and
    order 3 of Fz_joint over the last [N].  ``nudge``: the first step's whirl scaled by
    1 + nudge, another realization of a chaotic row (as another CPU's rounding gives)."""
    m = _model(params, n_rollers)
    w = 2 * math.pi * f
    n = int(round(cycles / f / DT))
    y, x = [], []
    for i in range(n):
        o = m.step(DT, theta, w * (1.0 + nudge) if i == 0 else w, 0.0, torque)
        y.append(o["Fz_joint"])
        x.append(o["whirl_angle"])
    return m, last_cycle_orders(DT * np.arange(1, n + 1), y, x, (3,))[3][0]


def _outputs(m, inputs, steps, sub=1, before=None):
    """The model's outputs at the end of each of ``steps`` communication steps DT at
    ``inputs``, taken in steps of DT / sub.  ``before``: the inputs before a step; where the
    model ramps a load change over its step (model.Roller.load_ramped) the torque then follows
    that ramp over the first DT's sub steps, so a finer reference sees the same input history."""
    ramp = before is not None and sub > 1 and m.rollers[0].load_ramped
    for i in range(steps * sub):
        tq = inputs["torque"]
        if ramp and i < sub:
            tq = before["torque"] + (tq - before["torque"]) * (i + 1) / sub
        o = m.step(DT / sub, inputs["theta"], inputs["omega"], 0.0, tq)
        if (i + 1) % sub == 0:
            yield o


def response(m, inputs, steps, sub=1, before=None):
    """Fz_joint [N] at the end of each of ``steps`` communication steps DT (_outputs)."""
    return np.array([o["Fz_joint"] for o in _outputs(m, inputs, steps, sub, before)])


def _reference_model(params, n_rollers, state, h, refine):
    """The model at ``state`` with the substep h / refine, accelerations afresh."""
    r = _model(dict(params, max_substep=h / refine), n_rollers)
    r.set_state(state)
    from tripod_model.layout import H_GA   # (on the path _model put it)
    for roller in r.rollers:
        roller._hs[H_GA] = 0.0
    return r


def reference(params, n_rollers, state, inputs, steps, h, refine=10, sub=10, before=None):
    """From ``state``, the same inputs with the substep h / refine and the communication step
    DT / sub, accelerations afresh; ``before``: the inputs before a step (_outputs)."""
    return response(_reference_model(params, n_rollers, state, h, refine), inputs, steps,
                    sub=sub, before=before)


# the needle-resolved row's output, read as its running mean over MEAN_SAMPLES communication
# steps (1 ms): with one linear solve a substep (newton_passes = 1) the row is chaotic on the
# scale of a few samples (a 1e-15 change of the state moves single samples of Fz_joint by up
# to 2.3 % of order 3 within 20 steps, and references 10 to 160 times finer part by up to
# 1.7 %), while the 1 ms mean converges (docs/benchmarks.md); the default's second pass
# takes most of that away (docs/integrators.md)
MEAN_SAMPLES = 10


def twin(state, eps):
    """A model state (get_state's) with the first roller's spin scaled by 1 + eps."""
    from tripod_model.fmu_arrays import X_Y
    from tripod_model.layout import Y_OM
    out = state.copy()
    out[X_Y + Y_OM] *= 1.0 + eps
    return out


def running_mean(y, samples):
    """The mean of each ``samples`` consecutive values of y (y itself for 1)."""
    return np.convolve(y, np.ones(samples) / samples, mode="valid")


def step_runs(params, n_rollers, f, name, factor, base, theta=THETA, torque=TORQUE,
              refines=(10,)):
    """Fz_joint [N] in the 20 steps after the input ``name`` steps by ``factor`` from the
    settled ``base`` (settle's, at the same f [Hz], theta [rad], torque [N m]): the default's,
    and {k: the reference's from the same state with the substep h / k} for k in refines."""
    m = base[0]
    st, h, inputs, before = _step_setup(m, f, name, factor, theta, torque)
    y = response(m, inputs, 20)
    m.set_state(st)
    return y, {k: reference(params, n_rollers, st, inputs, 20, h, k, before=before)
               for k in refines}


def _step_setup(m, f, name, factor, theta, torque):
    """The settled model m's state, its substep h [s] at the scene (f [Hz], theta [rad],
    torque [N m]), the inputs after the step and before it."""
    w = 2 * math.pi * f
    h = m.rollers[0].substep(theta, w, m.pressing(0.0, torque), m.rollers[0].v_st(theta, w))
    return (m.get_state(), h, stepped_inputs(f, theta, torque, name, factor),
            stepped_inputs(f, theta, torque, name, 1.0))


def stepped_inputs(f, theta, torque, name, factor):
    """The scene's inputs (whirl f [Hz], theta [rad], torque [N m]) with ``name`` scaled by
    ``factor``: what the master holds after the step."""
    inputs = {"theta": theta, "omega": 2 * math.pi * f, "torque": torque}
    inputs[name] *= factor
    return inputs


def deviation(y, ref, a3, mean=1):
    """The largest difference of y from ref [% of a3], both read as running means over
    ``mean`` samples."""
    return 100 * np.abs(running_mean(y, mean) - running_mean(ref, mean)).max() / a3


def case(params, n_rollers, f, name, factor, base, theta=THETA, torque=TORQUE, mean=1,
         refine=10, perturb=0.0):
    """The largest deviation of Fz_joint [% of order 3] in the 20 steps after the input
    ``name`` steps by ``factor`` from the settled ``base`` against the reference from the same
    state (substep cut ``refine`` times), both read as running means over ``mean`` samples
    (step_runs).  With ``perturb`` > 0, against the same model from the state with the
    roller's spin scaled by 1 + perturb instead: how far rounding alone moves it."""
    m, a3 = base
    if not perturb:
        y, refs = step_runs(params, n_rollers, f, name, factor, base, theta, torque, (refine,))
        return deviation(y, refs[refine], a3, mean)
    st = m.get_state()
    inputs = stepped_inputs(f, theta, torque, name, factor)
    y = response(m, inputs, 20)
    m.set_state(twin(st, perturb))
    ref = response(m, inputs, 20)
    m.set_state(st)
    return deviation(y, ref, a3, mean)


def checked_case(params, n_rollers, f, name, factor, base, theta=THETA, torque=TORQUE,
                 mean=1):
    """case's deviation [% of order 3] against the reference at h/20, and whether that
    reference has stopped moving: how far it is from the one at h/10 (the same units; a
    first-order error halves with the substep, so the h/20 reference is about that far from
    the limit or nearer).  (Not checked against coarser references: from a fresh start, h/2
    to h/5 take a 10 % theta step without the default's step-input substeps and miss by
    3-175 %.)"""
    y, refs = step_runs(params, n_rollers, f, name, factor, base, theta, torque, (10, 20))
    a3 = base[1]
    return deviation(y, refs[20], a3, mean), deviation(refs[10], refs[20], a3, mean)


# order 3 over the whirl cycle that ends CYCLE_AFTER cycles after a step (the first tenth of a
# cycle left out): how a held theta step on the needle-resolved row is judged, whose single
# samples have no converged reference (docs/integrators.md#needle-resolved-bearing)
CYCLE_AFTER = 1.1


def cycle_order(m, inputs, f, sub=1, before=None):
    """Order 3 of Fz_joint [N] as a complex amplitude (phase from whirl angle 0) over the whirl
    cycle ending CYCLE_AFTER cycles at f [Hz] after a step to ``inputs`` (_outputs)."""
    steps = int(round(CYCLE_AFTER / f / DT))
    outs = list(_outputs(m, inputs, steps, sub, before))
    a, ph = last_cycle_orders(DT * np.arange(1, steps + 1), [o["Fz_joint"] for o in outs],
                              [o["whirl_angle"] for o in outs], (3,))[3]
    return a * np.exp(1j * math.radians(ph))


def cycle_case(params, n_rollers, f, name, factor, base, theta=THETA, torque=TORQUE):
    """checked_case's pair for order 3 over the cycle after the step (cycle_order): its
    distance [% of the settled order 3] from the reference's at h/20, and that reference's
    from the one at h/10."""
    m, a3 = base
    st, h, inputs, before = _step_setup(m, f, name, factor, theta, torque)
    y = cycle_order(m, inputs, f)
    m.set_state(st)
    refs = {k: cycle_order(_reference_model(params, n_rollers, st, h, k), inputs, f, 10, before)
            for k in (10, 20)}
    return 100 * abs(y - refs[20]) / a3, 100 * abs(refs[10] - refs[20]) / a3


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
    revs = revolution_orders(dt * np.arange(n + 1), np.array(x), np.array(y))
    return [(r["speed_hz"], r["order3"]) for r in revs]


# --- order tracking of both FMUs along an input history (tripod-thrust runup) -----------------
RUNUP_START = {"n_rollers": 3, "torque": 300.0, "theta": math.radians(8.0)}


def ramp_inputs(f0, f1, duration):
    """An FMPy input table: omega [rad/s] from f0 to f1 [Hz] over ``duration`` [s]."""
    return {"time": [0.0, duration], "omega": [2 * math.pi * f0, 2 * math.pi * f1]}


def with_plunge(inputs, stop, amplitude, hz, dt=DT):
    """``inputs`` (an FMPy input table, {name: list} with "time") with a harmonic plunge added:
    the spider at amplitude [m] sin(2 pi hz t), as the input plunge_speed [m/s] = 2 pi hz
    amplitude cos(2 pi hz t), every input given on a grid of dt [s] up to stop [s]."""
    import numpy as np
    t = np.arange(0.0, stop + 0.5 * dt, dt)
    out = {"time": t.tolist()}
    for k, v in inputs.items():
        if k != "time":
            out[k] = np.interp(t, inputs["time"], v).tolist()
    w = 2 * math.pi * hz
    out["plunge_speed"] = (w * amplitude * np.cos(w * t)).tolist()
    return out


def read_input_csv(path):
    """An input history in FMPy's CSV format (a ``time`` column, then input columns by name,
    SI units) as {name: list}."""
    import csv
    allowed = [p.name for p in PARAMS if p.causality == "input"]
    try:
        with open(path, newline="") as f:
            rows = [r for r in csv.reader(f) if r]
        head = [h.strip().strip('"') for h in rows[0]]
        cols = list(zip(*[[float(v) for v in r] for r in rows[1:]]))
    except (OSError, IndexError, ValueError) as e:
        raise ValueError(f"{path}: not an input CSV ({e.__class__.__name__}: {e})") from None
    if head[0] != "time":
        raise ValueError(f"{path}: the first column must be 'time' (FMPy's input format)")
    for h in head[1:]:
        if h not in allowed:
            raise ValueError(f"{path}: column '{h}' is no input; inputs: {', '.join(allowed)}")
    if len(cols) != len(head) or len(cols[0]) < 2:
        raise ValueError(f"{path}: need at least two rows of {len(head)} numbers")
    return {h: list(c) for h, c in zip(head, cols)}


def revolution_orders(t, x, y, orders=(1, 3)):
    """Per whole revolution of the whirl angle x [rad] (from 0): its mean speed [Hz] (angle over
    time, the window's speed changes within it in a run-up; negative in reverse whirl) and the
    orders' (amplitude [unit of y], phase [deg]) of y resampled uniformly in the angle
    travelled, phase referred to the revolution's start.  Reverse whirl (x falling) counts the
    revolutions of -x; a whirl that changes direction is refused (no revolution to count
    across the turn)."""
    x = np.asarray(x, dtype=float)
    s = -1.0 if x[-1] < x[0] else 1.0
    u = s * x
    back = np.flatnonzero(np.diff(u) < 0.0)
    if back.size:
        raise ValueError(f"the whirl changes direction at t = {t[back[0] + 1]:g} s: order "
                         "tracking per revolution needs the whirl one way (split the history "
                         "there)")
    out = []
    k = 1
    while k * 2 * math.pi <= u[-1]:
        a, b = (k - 1) * 2 * math.pi, k * 2 * math.pi
        xs = a + 2 * math.pi * np.arange(720) / 720
        amp, ph = order_spectrum(np.interp(xs, u, y), 1, orders)
        ta, tb = np.interp([a, b], u, t)
        out.append({"revolution": k, "speed_hz": s / (tb - ta),
                    **{f"order{o}": float(m) for o, m in zip(orders, amp)},
                    **{f"order{o}_deg": float(p) for o, p in zip(orders, ph)}})
        k += 1
    return out


def start_values_by_model(start_values):
    """{"contact": ..., "analytic": ...}: each FMU's share of ``start_values`` (a parameter goes
    to the models that have it, scene.py; the analytic model's needle row paired with the
    contact model's bearing: scene.analytic_counterpart), each checked against its model's
    ranges.  Raises
    ValueError naming a parameter neither model has, or a value out of range."""
    for name, value in start_values.items():
        check_value(name, value)
    out = {"contact": {k: v for k, v in start_values.items() if "contact" in BY_NAME[k].models},
           "analytic": analytic_counterpart(start_values)}
    for model in out:
        validate(out[model], model)
    return out


def runup_signal(start_values):
    """The output a run-up tracks: Fz_joint for the whole joint, Fz_mod (the paper's modified
    thrust, section 3.2) for one roller."""
    n = start_values.get("n_rollers", BY_NAME["n_rollers"].default)
    return "Fz_joint" if int(n) == 3 else "Fz_mod"


def runup_fmus(start_values, inputs, stop_time, dt=DT):
    """Both FMUs through FMPy (fresh processes) along the input history ``inputs``, each with
    the start values its model has (start_values_by_model); order 1 and 3 of runup_signal's
    output [N] per revolution of each FMU's own whirl_angle, and the difference of the
    analytic FMU's order 3 from the contact FMU's [%]."""
    from .fmus import ensure_fmu
    from .runs import run_fmu
    res = {}
    by_model = start_values_by_model(start_values)
    signal = runup_signal(start_values)
    for model, name in (("contact", "TripodRoller"), ("analytic", "TripodRollerAnalytic")):
        r = run_fmu(ensure_fmu(name), by_model[model], stop_time=stop_time, output_interval=dt,
                    outputs=[signal, "whirl_angle"], inputs=inputs, progress=f"{model} FMU")
        res[model] = revolution_orders(r["time"], r["whirl_angle"], r[signal])
    rows = []
    for c, a in zip(res["contact"], res["analytic"]):
        rows.append({"revolution": c["revolution"], "speed_hz": c["speed_hz"], "signal": signal,
                     "contact_order1": c["order1"], "contact_order3": c["order3"],
                     "analytic_order1": a["order1"], "analytic_order3": a["order3"],
                     "order3_diff_pct": 100 * (a["order3"] / c["order3"] - 1)
                     if c["order3"] > 0 else float("nan")})
    return rows


def write_runup(rows, out):
    """runup.csv, runup.json and runup.png (order cuts against speed) into ``out``."""
    import csv
    import json
    from pathlib import Path
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "runup.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    (out / "runup.json").write_text(json.dumps(rows, indent=1) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    f = [r["speed_hz"] for r in rows]
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7, 6), sharex=True,
                                 gridspec_kw={"height_ratios": [3, 1]})
    for k, style in ((3, "-"), (1, "--")):
        ax.plot(f, [r[f"contact_order{k}"] for r in rows], "C0" + style + "o", ms=3,
                label=f"order {k}, contact FMU")
        ax.plot(f, [r[f"analytic_order{k}"] for r in rows], "C1" + style + "s", ms=3,
                label=f"order {k}, analytic FMU")
    ax.set(ylabel=f"amplitude of {rows[0]['signal']} [N]",
           title="order cuts along the input history")
    ax.legend()
    bx.plot(f, [r["order3_diff_pct"] for r in rows], "C2o-", ms=3)
    bx.axhline(0.0, color="k", lw=0.5)
    bx.set(xlabel="whirl speed, mean over the revolution [Hz]",
           ylabel="order 3: analytic - contact [%]")
    fig.tight_layout()
    fig.savefig(out / "runup.png", dpi=110)
    plt.close(fig)
    return out
