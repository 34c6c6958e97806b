"""The analytic and the contact model side by side: both FMUs through FMPy, orders 1 and 3 of
Fz_mod over the last whole whirl cycle, differences, tolerance and verdict."""
from __future__ import annotations

import math

import numpy as np

from reduced_model import scene as scene_mod
from reduced_model.analysis import analytic_report
from reduced_model.orders import last_cycle_orders

from .fmus import ensure_fmu
from .runs import run_fmu

# Tolerances and their physical reason (README, "Tolerances").
TOL_VERIFICATION = {"order1": {"amplitude_rel": 0.01, "phase_deg": 1.0},
                    "order3": {"amplitude_rel": 0.01, "phase_deg": 1.0}}
TOL_PHYSICAL = {"order3": {"amplitude_rel": 0.05}}
ORDERS = (1, 3)


def split_scene(overrides: dict) -> tuple[dict, dict]:
    """Validated contact scene and the analytic scene it implies (shared names only)."""
    contact = scene_mod.validate(overrides, "contact")
    analytic = {k: v for k, v in contact.items() if "analytic" in scene_mod.BY_NAME[k].models}
    return contact, scene_mod.validate(analytic, "analytic")


def is_verification(contact: dict) -> bool:
    """No traverse and an ideal bearing: the limit Eqs. (18)-(27) describe."""
    return (not contact["traverse"]) and contact["bearing"] == 0


def _o(a, p):
    return {"amplitude": float(a), "phase_deg": float(p)}


def _dphase(a, b):
    return float((a - b + 180.0) % 360.0 - 180.0)


def compare(overrides: dict | None = None, cycles: float = 2.0, dt: float = 1e-4) -> dict:
    """Run both FMUs on a scene and judge the contact model against the analytic one.

    Returns the JSON-ready result (see README); arrays of the runs under the key "_runs"
    (not JSON) for plotting.
    """
    contact_sc, analytic_sc = split_scene(overrides or {})
    omega = contact_sc["omega"]
    if omega <= 0:
        raise ValueError("omega = 0: compare needs whole whirl cycles; allowed range (0, 10000] rad/s")
    if cycles < 1.5:
        raise ValueError(f"cycles = {cycles}: at least 1.5 (the last whole cycle is analysed)")
    stop = cycles * 2 * math.pi / omega
    ra = run_fmu(ensure_fmu("TripodRollerAnalytic"), analytic_sc, stop, dt)
    rc = run_fmu(ensure_fmu("TripodRoller"), contact_sc, stop, dt)
    oa = last_cycle_orders(ra["time"], ra["Fz_mod"], omega * ra["time"], ORDERS)
    oc = last_cycle_orders(rc["time"], rc["Fz_mod"], omega * rc["time"], ORDERS)
    cf = analytic_report(analytic_sc)["closed_form"]
    ref = {k: (cf[f"order{k}"]["amplitude"], cf[f"order{k}"]["phase_deg"]) for k in ORDERS}
    verification = is_verification(contact_sc)
    tol = TOL_VERIFICATION if verification else TOL_PHYSICAL
    diff, ok = {}, True
    for k in ORDERS:
        key = f"order{k}"
        rel = oc[k][0] / ref[k][0] - 1 if ref[k][0] > 0 else (0.0 if oc[k][0] == 0 else math.inf)
        dp = _dphase(oc[k][1], ref[k][1])
        diff[key] = {"amplitude_rel": float(rel), "phase_deg": dp}
        t = tol.get(key, {})
        if "amplitude_rel" in t and not abs(rel) <= t["amplitude_rel"]:
            ok = False
        if "phase_deg" in t and not abs(dp) <= t["phase_deg"]:
            ok = False
    result = {
        "scene": contact_sc,
        "kind": "verification" if verification else "physical",
        "analytic": {**{f"order{k}": _o(*ref[k]) for k in ORDERS},
                     "closed_form": {f"order{k}": _o(*ref[k]) for k in ORDERS},
                     "fmu": {f"order{k}": _o(*oa[k]) for k in ORDERS}},
        "contact": {f"order{k}": _o(*oc[k]) for k in ORDERS},
        "difference": diff,
        "tolerance": tol,
        "phase_lag_deg": None if verification else -diff["order3"]["phase_deg"],
        "pass": bool(ok),
        "wall_s": {"analytic": float(ra["wall_s"]), "contact": float(rc["wall_s"])},
        "_runs": {"analytic": ra, "contact": rc, "omega": omega},
    }
    return result



def spectrum(run: dict, omega: float, name: str = "Fz_mod", orders=range(1, 11)):
    """Amplitudes [N] of orders 1-10 of one run's last whole cycle."""
    t = run["time"]
    res = last_cycle_orders(t, run[name], omega * t, tuple(orders))
    return np.array([res[k][0] for k in orders])


def format_table(r: dict) -> str:
    sc = r["scene"]
    a, c, d = r["analytic"], r["contact"], r["difference"]
    lines = [
        f"tripod-thrust compare: {r['kind']} scene (traverse = {str(sc['traverse']).lower()}, "
        f"bearing = {sc['bearing']}), theta = {math.degrees(sc['theta']):.2f} deg, "
        f"{sc['omega'] / (2 * math.pi):.3g} Hz, F_press = {sc['F_press']:.6g} N",
        "",
        "Fz_mod, last whole whirl cycle; order k = a sin(k w t + p)",
        f"{'':8s}{'analytic FMU':>22s}{'closed form':>22s}{'contact FMU':>22s}{'difference':>20s}{'tolerance':>20s}",
    ]
    for k in ORDERS:
        key = f"order{k}"
        t = r["tolerance"].get(key, {})
        ttxt = " / ".join(x for x in (f"{100 * t['amplitude_rel']:g} %" if "amplitude_rel" in t else "",
                                      f"{t['phase_deg']:g} deg" if "phase_deg" in t else "") if x) or "reported"
        lines.append(
            f"{'order ' + str(k):8s}"
            f"{a['fmu'][key]['amplitude']:9.3f} N {a['fmu'][key]['phase_deg']:7.2f}°"
            f"{a[key]['amplitude']:11.3f} N {a[key]['phase_deg']:7.2f}°"
            f"{c[key]['amplitude']:11.3f} N {c[key]['phase_deg']:7.2f}°"
            f"{100 * d[key]['amplitude_rel']:+10.2f} % {d[key]['phase_deg']:+6.2f}°"
            f"{ttxt:>20s}")
    if r["phase_lag_deg"] is not None:
        lines.append(f"physical effect (traverse, needle bearing): order 3 lags the analytic "
                     f"model by {r['phase_lag_deg']:.1f} deg (reported, not judged)")
    lines += ["", f"wall time: analytic FMU {r['wall_s']['analytic']:.2f} s, contact FMU "
              f"{r['wall_s']['contact']:.2f} s (FMPy in a subprocess)",
              f"verdict: {'PASS' if r['pass'] else 'FAIL'}"]
    return "\n".join(lines)
