"""The analytic and the contact model side by side: both FMUs through FMPy, orders 1 and 3 of
Fz_mod over the last whole whirl cycle of a settled (periodic) run, differences, tolerance and
verdict.  Verification scenes (no traverse, ideal bearing) are judged against Eqs. (18)-(27);
physical scenes against the reduced traverse model, Eqs. (18)-(27) reported beside it; coast
and reverse whirl, which the closed forms do not cover, against the analytic FMU's own run."""
from __future__ import annotations

import math

import numpy as np

from reduced_model import scene as scene_mod
from reduced_model.analysis import analytic_report
from reduced_model.orders import last_cycle_orders

from .fmus import ensure_fmu
from .runs import default_dt, run_fmu, run_settled, settle_line
from .spider_superposition import format_spider, spider_comparison

# Tolerances and their physical reason (docs/validation.md, "compare's tolerances").
TOL_VERIFICATION = {"order1": {"amplitude_rel": 0.01, "phase_deg": 1.0},
                    "order3": {"amplitude_rel": 0.01, "phase_deg": 1.0}}
# against the reduced traverse model, ideal bearing: what it leaves out (the roller's inertia
# while it crosses the groove, a rocking mode near 1 kHz) costs up to 3.5 % in order 3 over the
# grid of docs/validation.md inside its checked range (median 0.7 %, phase within 1.8 deg),
# 8.3 % at the fastest and lightest scene of the earlier, narrower grid
TOL_PHYSICAL = {"order3": {"amplitude_rel": 0.10, "phase_deg": 3.0}}
# a needle bearing: compare pairs the analytic FMU with its needle row (analytic_counterpart),
# within 3.0 % (complex) of the resolved row's order 3 over the envelope grid inside the checked
# range (docs/validation.md: its phase within 1.7 deg there); the amplitude alone is judged, the
# phase reported: it has not been checked beyond the grid's scenes
TOL_BEARING = {"order3": {"amplitude_rel": 0.10}}
ORDERS = (1, 3)


def split_scene(overrides: dict) -> tuple[dict, dict]:
    """Validated contact scene and the analytic scene it implies
    (scene.analytic_counterpart)."""
    contact = scene_mod.validate(overrides, "contact")
    return contact, scene_mod.validate(scene_mod.analytic_counterpart(contact), "analytic")


def quadrant(scene: dict) -> str:
    """"drive", "coast", "reverse" or "coast in reverse": the pressing load's and the whirl's
    signs (docs/model.md, "Coast and reverse whirl")."""
    F = scene_mod.pressing_load(scene["F_press"], scene.get("torque", 0.0), scene["s"])
    return {(False, False): "drive", (True, False): "coast", (False, True): "reverse",
            (True, True): "coast in reverse"}[(F < 0, scene["omega"] < 0)]


def is_verification(contact: dict) -> bool:
    """No traverse and an ideal bearing: the limit Eqs. (18)-(27) describe."""
    return (not contact["traverse"]) and contact["bearing"] == scene_mod.BEARING_IDEAL


def _tolerance(contact: dict) -> dict:
    """The tolerance a scene is judged with against the reduced model (the module's TOL_)."""
    if is_verification(contact):
        return TOL_VERIFICATION
    return TOL_PHYSICAL if contact["bearing"] == scene_mod.BEARING_IDEAL else TOL_BEARING


BEARING_NAMES = {scene_mod.BEARING_IDEAL: "ideal bearing",
                 scene_mod.BEARING_LUMPED: "lumped needle row",
                 scene_mod.BEARING_RESOLVED: "needle-resolved row (the paper's full model)"}


def contact_model_name(scene: dict) -> str:
    """Which contact model a scene runs (the reference every report names): the contact FMU
    with its bearing, e.g. "contact FMU, lumped needle row (bearing = 1)"."""
    b = int(scene["bearing"])
    return f"contact FMU, {BEARING_NAMES[b]} (bearing = {b})"


def _o(a, p):
    return {"amplitude": float(a), "phase_deg": float(p)}


def _dphase(a, b):
    return float((a - b + 180.0) % 360.0 - 180.0)


def compare(overrides: dict | None = None, max_cycles: int | None = None,
            dt: float | None = None, rel_tol: float | None = None) -> dict:
    """Run both FMUs on a scene and judge the contact model against the analytic one.

    The contact FMU runs whole whirl cycles until Fz_mod (and each roller's Fz) is periodic
    within rel_tol (default reduced_model.steady.REL_TOL), at most max_cycles, at the
    communication step dt [s] (default harness.runs.default_dt: 1e-4 s or a 1000th of the
    whirl cycle when shorter).  Returns the
    JSON-ready result (docs/using-the-fmus.md); arrays of the runs under "_runs" (not JSON) for plotting.
    """
    contact_sc, analytic_sc = split_scene(overrides or {})
    omega = contact_sc["omega"]
    if omega == 0:
        raise ValueError("omega = 0: compare needs whole whirl cycles; allowed range "
                         "[-10000, 0) or (0, 10000] rad/s")
    dt = default_dt(abs(omega)) if dt is None else dt
    if quadrant(contact_sc) != "drive":
        return _compare_fmus(contact_sc, analytic_sc, dt, max_cycles, rel_tol)
    period = 2 * math.pi / omega
    ra = run_fmu(ensure_fmu("TripodRollerAnalytic"), analytic_sc, 2 * period, dt)
    signals = ["Fz_mod"] + (["Fz_2", "Fz_3"] if contact_sc["n_rollers"] == 3 else [])
    rc = run_settled(ensure_fmu("TripodRoller"), contact_sc, omega, signals, dt, max_cycles,
                     rel_tol, progress="contact FMU")
    oa = last_cycle_orders(ra["time"], ra["Fz_mod"], omega * ra["time"], ORDERS)
    oc = last_cycle_orders(rc["time"], rc["Fz_mod"], omega * rc["time"], ORDERS)
    rep = analytic_report(analytic_sc)
    cf = rep["closed_form"]
    eq27 = {k: (cf[f"order{k}"]["amplitude"], cf[f"order{k}"]["phase_deg"]) for k in ORDERS}
    trav = rep["traverse"]
    verification = is_verification(contact_sc)
    if verification or trav is None:
        ref, against, tol = eq27, "eqs_18_27", TOL_VERIFICATION if verification else {}
    else:
        ref = {k: (trav[f"order{k}"]["amplitude"], trav[f"order{k}"]["phase_deg"]) for k in ORDERS}
        against, tol = "traverse", _tolerance(contact_sc)
    diff27, _ = _judge(oc, eq27, {})
    analytic = {**_orders(ref), "closed_form": _orders(eq27),
                "traverse": None if trav is None else
                {f"order{k}": trav[f"order{k}"] for k in ORDERS},
                "fmu": _orders(oa)}
    # where the judge (the traverse model) was not checked against the contact model
    outside = trav["outside_checked"] if against == "traverse" else []
    r = _result(contact_sc, against, analytic, oc, ref, tol,
                {"analytic": ra, "contact": rc, "omega": omega},
                regime=rep["regime"], outside=outside, diff27=diff27,
                phase_lag=None if verification else -diff27["order3"]["phase_deg"],
                settled=rc["settle"]["settled"])
    r["spider"] = _spider_block(contact_sc, rc, dt, max_cycles, rel_tol)
    _add_joint(r, contact_sc, ra, rc, lambda run: omega * run["time"])
    return r


def _joint_block(ra, rc, tol, angle):
    """n_rollers = 3: the housing's thrust Fz_joint, the contact FMU's orders against the
    analytic FMU's, order 3 judged within the rollers' order-3 tolerance; order 1, a sum of
    the three rollers' order 1 that cancels by symmetry, reported as its complex difference
    over the joint's order 3.  angle(run): the whirl angle the orders are taken against."""
    oa = last_cycle_orders(ra["time"], ra["Fz_joint"], angle(ra), ORDERS)
    oc = last_cycle_orders(rc["time"], rc["Fz_joint"], angle(rc), ORDERS)
    t3 = {"order3": tol["order3"]} if "order3" in tol else {}
    diff, ok = _judge(oc, oa, t3)
    z = lambda o: o[1][0] * np.exp(1j * math.radians(o[1][1]))     # order 1, complex
    diff["order1"] = {"of_order3": float(abs(z(oc) - z(oa)) / oa[3][0]) if oa[3][0] > 0
                      else math.inf}
    return {"analytic_fmu": _orders(oa), "contact": _orders(oc), "difference": diff,
            "tolerance": t3, "pass": bool(ok)}


def _add_joint(r, contact_sc, ra, rc, angle):
    """r["joint"]: _joint_block with three rollers (None with one), and the verdict with it."""
    r["joint"] = None
    if contact_sc["n_rollers"] == 3:
        r["joint"] = _joint_block(ra, rc, r["tolerance"], angle)
        r["pass"] = bool(r["pass"] and r["joint"]["pass"])


def _spider_block(contact_sc, rc, dt, max_cycles, rel_tol):
    """spider = 1: the prescribed joint on the same scene, run until periodic, and the free
    one against it (harness.spider_superposition.spider_comparison); else None."""
    if contact_sc["spider"] != scene_mod.SPIDER_FREE:
        return None
    rp = run_settled(ensure_fmu("TripodRoller"), dict(contact_sc, spider=0),
                     abs(contact_sc["omega"]), ["Fz_mod", "Fz_2", "Fz_3"], dt, max_cycles,
                     rel_tol, progress="contact FMU, prescribed spider")
    return spider_comparison(contact_sc, rc, rp)


def _compare_fmus(contact_sc, analytic_sc, dt, max_cycles, rel_tol) -> dict:
    """Coast or reverse whirl: the closed forms cover forward drive only, so the contact FMU is
    judged against the analytic FMU's own run (the reduced model through the model's symmetry,
    docs/model.md), both run until periodic, orders against the whirl angle's magnitude."""
    w = abs(contact_sc["omega"])
    signals = ["Fz_mod"] + (["Fz_2", "Fz_3"] if contact_sc["n_rollers"] == 3 else [])
    ra = run_settled(ensure_fmu("TripodRollerAnalytic"), analytic_sc, w, ["Fz_mod"], dt,
                     max_cycles, rel_tol, progress="analytic FMU")
    rc = run_settled(ensure_fmu("TripodRoller"), contact_sc, w, signals, dt, max_cycles, rel_tol,
                     progress="contact FMU")
    oa, oc = (last_cycle_orders(r["time"], r["Fz_mod"], np.abs(r["whirl_angle"]), ORDERS)
              for r in (ra, rc))
    fmu = _orders(oa)
    r = _result(contact_sc, "analytic_fmu",
                {**fmu, "closed_form": None, "traverse": None, "fmu": fmu}, oc, oa,
                _tolerance(contact_sc), {"analytic": ra, "contact": rc, "omega": w},
                settled=rc["settle"]["settled"] and ra["settle"]["settled"])
    r["spider"] = _spider_block(contact_sc, rc, dt, max_cycles, rel_tol)
    _add_joint(r, contact_sc, ra, rc, lambda run: np.abs(run["whirl_angle"]))
    return r


def _orders(o):
    """{"order1": {"amplitude", "phase_deg"}, ...} of orders {k: (amplitude, phase_deg)}."""
    return {f"order{k}": _o(*o[k]) for k in ORDERS}


def _result(scene, against, analytic, oc, ref, tol, runs, *, settled, regime=None, outside=(),
            diff27=None, phase_lag=None) -> dict:
    """compare's JSON-ready result (docs/using-the-fmus.md), one shape for every quadrant:
    the contact FMU's orders oc judged against the orders ref within tol (``against`` names
    them; ``analytic`` holds them and their sources); runs: {"analytic", "contact": the runs,
    "omega": the whirl rate [rad/s]} (their arrays under "_runs", not JSON)."""
    diff, ok = _judge(oc, ref, tol)
    ra, rc = runs["analytic"], runs["contact"]
    st = rc["settle"]
    return {
        "scene": scene, "quadrant": quadrant(scene),
        "kind": "verification" if is_verification(scene) else "physical",
        "against": against, "contact_model": contact_model_name(scene),
        "regime": regime, "outside_checked": list(outside),
        "analytic": analytic,
        "contact": _orders(oc),
        "difference": diff, "difference_eqs_18_27": diff27, "tolerance": tol,
        "phase_lag_deg": phase_lag,
        "cycles": st["cycles"], "settled": settled, "cycle_change": st["worst"],
        "pass": bool(ok and settled),
        "wall_s": {"analytic": float(ra["wall_s"]), "contact": float(rc["wall_s"])},
        "_runs": {**runs, "settle": st},
    }


def _judge(got, ref, tol):
    """Differences of orders 1 and 3 of ``got`` from ``ref`` and whether they are within tol."""
    diff, ok = {}, True
    for k in ORDERS:
        key = f"order{k}"
        rel = got[k][0] / ref[k][0] - 1 if ref[k][0] > 0 else (0.0 if got[k][0] == 0 else math.inf)
        dp = _dphase(got[k][1], ref[k][1])
        diff[key] = {"amplitude_rel": float(rel), "phase_deg": dp}
        t = tol.get(key, {})
        if "amplitude_rel" in t and not abs(rel) <= t["amplitude_rel"]:
            ok = False
        if "phase_deg" in t and not abs(dp) <= t["phase_deg"]:
            ok = False
    return diff, ok


def spectrum(run: dict, omega: float, name: str = "Fz_mod", orders=range(1, 11)):
    """Amplitudes [N] of orders 1-10 of one run's last whole cycle."""
    t = run["time"]
    res = last_cycle_orders(t, run[name], omega * t, tuple(orders))
    return np.array([res[k][0] for k in orders])


def _cell(orders, key):
    """One order's amplitude and phase in format_table's columns; "-" where ``orders`` is None
    (no closed form or traverse model for the scene)."""
    if not orders:
        return f"{'-':>22s}"
    return f"{orders[key]['amplitude']:11.3f} N {orders[key]['phase_deg']:7.2f}°"


def _tol_text(t: dict) -> str:
    return " / ".join(x for x in (f"{100 * t['amplitude_rel']:g} %" if "amplitude_rel" in t else "",
                                  f"{t['phase_deg']:g} deg" if "phase_deg" in t else "") if x)


def _joint_lines(j: dict) -> list[str]:
    """format_table's block of the housing's thrust (three rollers)."""
    a, c, d = j["analytic_fmu"], j["contact"], j["difference"]
    lines = ["Fz_joint, the housing's thrust (three rollers), last whole whirl cycle; judged "
             "against the analytic FMU's",
             f"{'':8s}{'analytic FMU':>22s}{'contact FMU':>22s}{'difference':>24s}"
             f"{'tolerance':>20s}"]
    for k in ORDERS:
        key = f"order{k}"
        if k == 1:   # cancels by symmetry: its difference against the joint's order 3
            dtxt, ttxt = f"{100 * d[key]['of_order3']:.2f} % of order 3", "reported"
        else:
            dtxt = f"{100 * d[key]['amplitude_rel']:+10.2f} % {d[key]['phase_deg']:+6.2f}°"
            ttxt = _tol_text(j["tolerance"].get(key, {})) or "reported"
        lines.append(f"{'order ' + str(k):8s}{_cell(a, key)}{_cell(c, key)}{dtxt:>24s}"
                     f"{ttxt:>20s}")
    lines.append(f"joint: {'PASS' if j['pass'] else 'FAIL'}")
    return lines


def format_table(r: dict) -> str:
    sc = r["scene"]
    a, c, d = r["analytic"], r["contact"], r["difference"]
    ref_name = {"traverse": "traverse model", "eqs_18_27": "Eqs. 18-27",
                "analytic_fmu": "analytic FMU (the closed forms cover forward drive)"}[r["against"]]
    regime = (f"regime (reduced traverse model): {r['regime']}" if r["regime"] else
              f"{r['quadrant']}: both FMUs run until periodic")
    lines = [
        f"tripod-thrust compare: {r['kind']} scene, {r['quadrant']} (traverse = "
        f"{str(sc['traverse']).lower()}, bearing = {sc['bearing']}), theta = "
        f"{math.degrees(sc['theta']):.2f} deg, {sc['omega'] / (2 * math.pi):.3g} Hz, "
        f"{scene_mod.load_text(sc)}",
        f"{regime}; contact FMU: "
        + settle_line({"cycles": r["cycles"], "settled": r["settled"], "worst": r["cycle_change"],
                       "rel_tol": r["_runs"]["settle"]["rel_tol"],
                       "max_cycles": r["_runs"]["settle"]["max_cycles"]}),
        *([f"the traverse model is OUTSIDE the range it was checked against the contact model "
           f"in (docs/validation.md): {'; '.join(r['outside_checked'])}"]
          if r.get("outside_checked") else
          ["the scene is inside the range the traverse model was checked against the contact "
           "model in (docs/validation.md)"] if r.get("against") == "traverse" else []),
        "",
        f"contact model: {r['contact_model']}",
        f"Fz_mod, last whole whirl cycle; order k = a sin(k w t + p); judged against the {ref_name}",
        f"{'':8s}{'analytic FMU':>22s}{'Eqs. 18-27':>22s}{'traverse model':>22s}{'contact FMU':>22s}"
        f"{'difference':>20s}{'tolerance':>20s}",
    ]
    for k in ORDERS:
        key = f"order{k}"
        t = r["tolerance"].get(key, {})
        ttxt = _tol_text(t) or "reported"
        lines.append(
            f"{'order ' + str(k):8s}"
            f"{a['fmu'][key]['amplitude']:9.3f} N {a['fmu'][key]['phase_deg']:7.2f}°"
            f"{_cell(a['closed_form'], key)}{_cell(a['traverse'], key)}{_cell(c, key)}"
            f"{100 * d[key]['amplitude_rel']:+10.2f} % {d[key]['phase_deg']:+6.2f}°"
            f"{ttxt:>20s}")
    t3 = r["tolerance"].get("order3", {})
    if "amplitude_rel" in t3 and "phase_deg" not in t3:
        lines.append(f"order 3's phase not judged with the {BEARING_NAMES[int(sc['bearing'])]}: "
                     f"the analytic FMU ran with its needle row ({d['order3']['phase_deg']:+.1f} "
                     f"deg here; within 1.7 deg over the envelope grid, not checked beyond it: "
                     f"docs/validation.md)")
    if r["phase_lag_deg"] is not None:
        d27 = r["difference_eqs_18_27"]["order3"]
        lines.append(f"against Eqs. (18)-(27) (reported, not judged): order 3 "
                     f"{100 * d27['amplitude_rel']:+.1f} %, lagging by {r['phase_lag_deg']:.1f} deg")
    if r.get("joint"):
        lines += ["", *_joint_lines(r["joint"])]
    if r.get("spider"):
        lines += ["", format_spider(r["spider"])]
    lines += ["", f"wall time: analytic FMU {r['wall_s']['analytic']:.2f} s, contact FMU "
              f"{r['wall_s']['contact']:.2f} s (FMPy in a subprocess)",
              f"verdict: {'PASS' if r['pass'] else 'FAIL'}"
              + ("" if r["settled"] else " (the run did not settle within the cap)")]
    return "\n".join(lines)
