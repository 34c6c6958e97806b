"""`tripod-thrust stress`: the contact FMU well outside the paper's scene.

Each case reports the status, whether every output is finite, whether |Fz| stays within the
friction bound (mu_groove + mu_needle) Fx plus the roller's spin-inertia thrust and a 5 %
margin, the chatter flag and the wall time.  A case fails on a crash, a hang (timeout), a
non-finite output, a broken bound or chatter; invalid inputs must instead be refused with a
logged reason and a non-OK status.
"""
from __future__ import annotations

import math
import time

import numpy as np

from reduced_model import scene as scene_mod
from reduced_model.orders import last_cycle_orders
from tripod_model.budget import ADAPT_REFUSAL

from .fmus import ensure_fmu
from .runs import FmuRunError, run_fmu

DEG = math.pi / 180
HZ = 2 * math.pi
CHATTER_ORDER = 40
CHATTER_SHARE = 0.05   # power share above order 40 that flags chatter (docs/validation.md, "Stress test")
OUTS = ("Fx", "Fy", "Fz", "Fz_mod", "dFx", "contact_y", "contact_z", "slip_speed", "roller_spin")


def chatter_share(t, y, omega, whirl=None):
    """Power share of orders above CHATTER_ORDER in the last whole cycle of y (0..1).

    ``whirl`` [rad], when given, is the whirl angle at t (a speed that varies in time);
    otherwise omega * t.

    Numerical chatter (a substep too large for the friction or contact stiffness) puts power
    at the sampling rate; the physical content of Fz_mod sits in orders 1-10, plus the traverse
    ringing of the roller on the groove flank (about order 150 at 10 Hz, well below 1 %).
    """
    x = omega * np.asarray(t) if whirl is None else np.asarray(whirl)
    if x[-1] - x[0] < 2 * math.pi:
        return 0.0
    m = x >= x[-1] - 2 * math.pi - 1e-12
    n = int(m.sum()) - 1
    if n < 2 * CHATTER_ORDER + 4:
        return 0.0
    xs = x[-1] - 2 * math.pi + 2 * math.pi * np.arange(n) / n
    ys = np.interp(xs, x, y)
    X = np.abs(np.fft.rfft(ys - ys.mean())) ** 2
    total = X[1:].sum()
    return float(X[CHATTER_ORDER + 1:].sum() / total) if total > 0 else 0.0


def _bound(sv, Fx):
    d = scene_mod.defaults("contact")
    p = {**d, **sv}
    I = 0.5 * p["m_roller"] * (p["r_roller"] ** 2 + p["r_bore"] ** 2)
    th = abs(p["theta"]) if np.isscalar(p["theta"]) else max(map(abs, p["theta"]))
    w = abs(p["omega"]) if np.isscalar(p["omega"]) else max(map(abs, p["omega"]))
    spin = I / p["r_roller"] ** 2 * p["s"] * math.tan(th) * w ** 2
    mu = p["mu_groove"] + (p["mu_needle"] if p["bearing"] != scene_mod.BEARING_IDEAL else 0.0)
    return 1.05 * (mu * np.abs(Fx) + spin) + 1e-6   # (coast: Fx < 0)


def cases(quick=False):
    """(name, start values, time-varying inputs, stop [s], comm step [s], expect_ok)."""
    c = []
    add = lambda *a: c.append(a)  # noqa: E731
    for deg in (0, 5, 15, 25):
        add(f"joint angle {deg} deg", {"theta": deg * DEG}, None, 0.2, 1e-4, True)
    for hz in (0, 1, 50):
        add(f"whirl {hz} Hz", {"omega": hz * HZ}, None, 0.2 if hz else 0.05, 1e-4, True)
    for F in (0.0, 5000.0, 20000.0, 50000.0):
        add(f"load {F:g} N", {"F_press": F}, None, 0.2, 1e-4, True)
    # the driveline envelope: coast, reverse whirl, a launch, torque through zero, plunging
    add("coast -1000 N", {"F_press": -1000.0}, None, 0.2, 1e-4, True)
    add("reverse whirl -10 Hz", {"omega": -10 * HZ}, None, 0.2, 1e-4, True)
    add("coast in reverse, -20 kN, -5 Hz, lumped bearing",
        {"F_press": -20000.0, "omega": -5 * HZ, "bearing": 1}, None, 0.4, 1e-4, True)
    add("launch 3000 N m, 25 deg, three rollers",
        {"torque": 3000.0, "theta": 25 * DEG, "n_rollers": 3}, None, 0.2, 1e-4, True)
    add("launch from standstill: 0 -> 5 Hz and 0 -> 3000 N m in 1 s, 20 deg",
        {"theta": 20 * DEG, "n_rollers": 3},
        {"time": [0.0, 1.0], "omega": [0.0, 5 * HZ], "torque": [0.0, 3000.0]}, 1.0, 1e-4, True)
    add("torque reversal 300 -> -300 N m over 0.2 s", {"n_rollers": 3},
        {"time": [0.0, 0.05, 0.25, 0.3], "torque": [300.0, 300.0, -300.0, -300.0]}, 0.3, 1e-4,
        True)
    add("torque reversal 300 -> -300 N m over 0.2 s, lumped bearing", {"bearing": 1},
        {"time": [0.0, 0.05, 0.25, 0.3], "torque": [300.0, 300.0, -300.0, -300.0]}, 0.3, 1e-4,
        True)
    add("torque reversal 300 -> -300 N m over 0.1 s, needle-resolved bearing, running "
        "clearance 1 mm", {"bearing": 2, "running_clearance": 1e-3},
        {"time": [0.0, 0.03, 0.13, 0.15], "torque": [300.0, 300.0, -300.0, -300.0]}, 0.15,
        1e-4, True)
    add("tip-out at a launch's torque: 3000 -> -3000 N m over 0.2 s, running clearance 1 mm, "
        "20 deg", {"n_rollers": 3, "theta": 20 * DEG, "running_clearance": 1e-3},
        {"time": [0.0, 0.05, 0.25, 0.3], "torque": [3000.0, 3000.0, -3000.0, -3000.0]}, 0.3,
        1e-4, True)
    # the floating spider (spider = 1): a launch and a torque reversal, both bearings it takes
    add("free spider: launch 3000 N m, 25 deg", {"torque": 3000.0, "theta": 25 * DEG,
                                                 "n_rollers": 3, "spider": 1}, None, 0.2, 1e-4,
        True)
    add("free spider: launch 3000 N m, 25 deg, lumped bearing",
        {"torque": 3000.0, "theta": 25 * DEG, "n_rollers": 3, "spider": 1, "bearing": 1}, None,
        0.2, 1e-4, True)
    add("free spider: torque reversal 300 -> -300 N m over 0.2 s", {"n_rollers": 3, "spider": 1},
        {"time": [0.0, 0.05, 0.25, 0.3], "torque": [300.0, 300.0, -300.0, -300.0]}, 0.3, 1e-4,
        True)
    # a known limit, held to a clean refusal (docs/model.md, "The floating spider")
    add("free spider: torque reversal 300 -> -300 N m over 0.2 s, lumped bearing (a known "
        "limit: the step refused where the rows land on the coast flank)",
        {"n_rollers": 3, "spider": 1, "bearing": 1},
        {"time": [0.0, 0.05, 0.25, 0.3], "torque": [300.0, 300.0, -300.0, -300.0]}, 0.3, 1e-4,
        False)
    for vp in (0.1, 0.5):
        add(f"plunge {vp:g} m/s", {"plunge_speed": vp}, None, 0.2, 1e-4, True)
    for mu in (0.0, 0.3):
        add(f"friction {mu:g}", {"mu_groove": mu}, None, 0.2, 1e-4, True)
    for vst in (1e-5, 1e-3, 1.0):
        add(f"v_st {vst:g} m/s", {"v_st": vst}, None, 0.2, 1e-4, True)
    for dt in (1e-6, 1e-3, 1e-2):
        add(f"communication step {dt:g} s", {}, None, 0.02 if dt < 1e-5 else 0.2, dt, True)
    add("lumped bearing", {"bearing": 1}, None, 0.2, 1e-4, True)
    add("needle-resolved bearing, 46 needles", {"bearing": 2}, None, 0.2, 1e-4, True)
    add("needle-resolved bearing, 5 kN", {"bearing": 2, "F_press": 5000.0}, None, 0.1, 1e-4, True)
    # where the roller's spin flipped every substep while BDF2 took its friction by the
    # tangent (docs/integrators.md)
    add("needle-resolved bearing, 15 kN", {"bearing": 2, "F_press": 15e3}, None, 0.1, 1e-4, True)
    add("needle-resolved bearing, a launch's 45 kN", {"bearing": 2, "F_press": 45e3}, None, 0.1,
        1e-4, True)
    t = [0.0, 0.099, 0.1, 0.3]
    add("torque step 0 -> 200 N m at 0.1 s", {}, {"time": t, "torque": [0.0, 0.0, 200.0, 200.0]},
        0.3, 1e-4, True)
    add("speed ramp 5 -> 20 Hz", {}, {"time": [0.0, 0.4], "omega": [5 * HZ, 20 * HZ]}, 0.4, 1e-4, True)
    add("joint angle 5 -> 15 deg during the run", {},
        {"time": [0.0, 0.1, 0.3], "theta": [5 * DEG, 5 * DEG, 15 * DEG]}, 0.3, 1e-4, True)
    add("invalid parameter theta = 2 rad", {"theta": 2.0}, None, 0.01, 1e-4, False)
    add("invalid input F_press > 1e5 N during the run", {},
        {"time": [0.0, 0.01, 0.02], "F_press": [1000.0, 1000.0, 2e5]}, 0.03, 1e-4, False)
    if quick:
        keep = {"joint angle 25 deg", "whirl 0 Hz", "load 0 N", "v_st 1e-05 m/s",
                "communication step 0.01 s", "torque step 0 -> 200 N m at 0.1 s",
                "invalid parameter theta = 2 rad", "invalid input F_press > 1e5 N during the run",
                "torque reversal 300 -> -300 N m over 0.2 s"}
        c = [x for x in c if x[0] in keep]
    else:
        add("1000 whirl cycles (drift of order 3)", {}, None, 100.0, 1e-3, True)
    return c


# what a run refused mid-way must have logged (run_case): an input out of range, or the step
# budget's refusal (its wording's start)
REFUSALS = ("invalid input", ADAPT_REFUSAL.split(" at ")[0])


def run_case(name, sv, inputs, stop, dt, expect_ok):
    row = {"case": name, "status": "", "finite": None, "bound": None, "chatter": None,
           "wall_s": None, "pass": False, "note": ""}
    t0 = time.perf_counter()
    try:
        r = run_fmu(ensure_fmu("TripodRoller"), sv, stop_time=stop, output_interval=dt,
                    inputs=inputs, timeout=1200, progress=f"stress: {name}")
    except FmuRunError as e:
        row["wall_s"] = time.perf_counter() - t0
        row["status"] = "refused"
        msg = str(e)
        logged = "invalid" in msg and ("allowed" in msg or "range" in msg)
        row["note"] = msg.split("|")[-1].strip()[:160]
        row["pass"] = (not expect_ok) and logged
        return row
    except Exception as e:   # timeout = hang
        row["wall_s"] = time.perf_counter() - t0
        row["status"] = f"crash/hang: {type(e).__name__}"
        return row
    row["wall_s"] = time.perf_counter() - t0
    row["status"] = "ok" if len(r["time"]) >= int(stop / dt * 0.999) else "stopped early"
    if not expect_ok:
        # an invalid input mid-run, or a known limit, must stop the run (Discard) with a logged
        # reason: the input's range or the step budget's refusal
        said = [m for m in r["log"] if any(k in m for k in REFUSALS)]
        row["pass"] = row["status"] == "stopped early" and bool(said)
        row["note"] = (said[0] if said else "")[:160]
        row["finite"] = all(np.all(np.isfinite(r[k])) for k in OUTS)
        return row
    row["finite"] = all(np.all(np.isfinite(r[k])) for k in OUTS)
    svb = dict(sv)
    if inputs:
        for k, v in inputs.items():
            if k != "time":
                svb[k] = max(v, key=abs)
    if svb.get("torque", 0) != 0:
        s = svb.get("s", scene_mod.BY_NAME["s"].default)
        svb["F_press"] = scene_mod.pressing_load(svb.get("F_press", 0.0), svb["torque"], s)
    row["bound"] = bool(np.all(np.abs(r["Fz"]) <= _bound(svb, r["Fx"])))
    omega = abs(sv.get("omega", scene_mod.BY_NAME["omega"].default))   # (reverse: the same)
    whirl = None
    if inputs and "omega" in inputs:   # the whirl angle integrates the speed input
        w_t = np.abs(np.interp(r["time"], inputs["time"], inputs["omega"]))
        whirl = np.concatenate([[0.0], np.cumsum(0.5 * (w_t[1:] + w_t[:-1]) * np.diff(r["time"]))])
    share = chatter_share(r["time"], r["Fz_mod"], omega, whirl)
    row["chatter"] = share > CHATTER_SHARE
    row["note"] = f"share above order {CHATTER_ORDER}: {100 * share:.2f} %"
    if stop >= 50:   # long run: order 3 of the second cycle against the last
        T = 2 * math.pi / omega
        first = r["time"] <= 2 * T + 1e-9
        a = last_cycle_orders(r["time"][first], r["Fz_mod"][first], omega * r["time"][first], (3,))[3][0]
        b = last_cycle_orders(r["time"], r["Fz_mod"], omega * r["time"], (3,))[3][0]
        drift = abs(b / a - 1)
        row["note"] += f"; order 3 drift over the run {100 * drift:.3f} %"
        if drift > 1e-3:
            row["bound"] = False
    row["pass"] = row["status"] == "ok" and row["finite"] and row["bound"] and not row["chatter"]
    return row


def stress(quick=False, log=print):
    rows = []
    for case in cases(quick):
        row = run_case(*case)
        rows.append(row)
        log(f"[{'PASS' if row['pass'] else 'FAIL'}] {row['case']}: status {row['status']}, "
            f"finite {row['finite']}, bound {row['bound']}, chatter {row['chatter']}, "
            f"{row['wall_s']:.2f} s; {row['note']}")
    return rows


def write_report(rows, out):
    from pathlib import Path
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    lines = ["| case | status | finite | |Fz| bound | chatter | wall [s] | pass | note |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['status']} | {r['finite']} | {r['bound']} | "
                     f"{r['chatter']} | {r['wall_s']:.2f} | {'PASS' if r['pass'] else 'FAIL'} | "
                     f"{r['note']} |")
    (out / "stress.md").write_text("\n".join(lines) + "\n")
    return out / "stress.md"
