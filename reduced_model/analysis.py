"""The analytic report of a scene: FFT of the time series beside the closed form."""
import math

import numpy as np

from . import scene as scene_mod
from .scene import load_text
from .orders import order_spectrum
from .thrust import closed_form, three_roller_thrust, time_series, transition_velocity
from .traverse import Traverse, outside_checked

N_PER_CYCLE = 1440   # samples per whirl cycle for the FFT (model.md asks for >= 400)


def _o(a_p):
    return {"amplitude": float(a_p[0]), "phase_deg": float(a_p[1])}


def traverse_report(sc) -> dict | None:
    """The reduced traverse model's orders of Fz_mod and Fz (one roller, three rollers), its
    regime and reach, what of the scene lies outside the range it was checked in
    ("outside_checked", traverse.CHECKED); None where it does not apply (omega = 0, no load, no friction, or
    mu_groove >= 1)."""
    if sc["omega"] <= 0 or sc["F_press"] <= 0 and sc.get("torque", 0.0) <= 0 or \
            not 0 < sc["mu_groove"] < 1 or transition_velocity(sc) <= 0:
        return None
    tr = Traverse(sc)
    o, oz, j = tr.orders("Fz_mod"), tr.orders("Fz"), tr.three_rollers("Fz_mod")
    return {"order1": _o(o[1]), "order3": _o(o[3]),
            "Fz": {"order1": _o(oz[1]), "order3": _o(oz[3])},
            "three_rollers": {"order1": _o(j[1]), "order3": _o(j[3])},
            "regime": tr.regime(), "friction_reach": tr.g_max,
            "Fx_max": float(tr.Fx.max()), "cycles": tr.cycles, "settled": bool(tr.settled),
            "mismatch": float(tr.mismatch), "outside_checked": outside_checked(sc)}


def analytic_report(overrides=None, n=N_PER_CYCLE):
    """Everything ``tripod-thrust analytic`` prints, as a JSON-ready dict (SI units, deg).

    "order1", "order3", "closed_form", "friction", "three_rollers": Eqs. (18)-(27) (FFT of
    the time series and closed form); "traverse": the reduced traverse model (always computed
    where it applies, so the regime is known); "model": which one the analytic FMU uses.
    """
    sc = scene_mod.validate(overrides, "analytic")
    scene_mod.check_drive(sc, "tripod-thrust analytic")
    x = 2.0 * np.pi * np.arange(n) / n
    ts = time_series(sc, x)
    cf = closed_form(sc)
    a, p = order_spectrum(ts["Fz"], 1, (1, 3))
    af, pf = order_spectrum(ts["ftz"], 1, (1, 3))
    aj, pj = order_spectrum(three_roller_thrust(sc, x), 1, (1, 3))
    c2, _ = order_spectrum(ts["ft"], 1, (2,))
    tr = traverse_report(sc)
    return {
        "scene": sc,
        "model": "traverse" if sc["traverse"] and tr is not None else "eqs_18_27",
        "regime": tr["regime"] if tr else "full slip",
        "traverse": tr,
        "A": cf["A"], "B": cf["B"], "v_st": cf["v_st"], "C": cf["C"], "C_fft": float(c2[0]),
        "alpha_deg": cf["alpha_deg"], "beta_deg": cf["beta_deg"],
        "order1": _o((a[0], p[0])), "order3": _o((a[1], p[1])),
        "closed_form": {"order1": _o(cf["total"][1]), "order3": _o(cf["total"][3])},
        "friction": {"order1": _o((af[0], pf[0])), "order3": _o((af[1], pf[1])),
                     "closed_form": {"order1": _o(cf["friction"][1]),
                                     "order3": _o(cf["friction"][3])}},
        "spin_inertia": {"order1": _o(cf["spin"][1])},
        "three_rollers": {"order1": _o((aj[0], pj[0])), "order3": _o((aj[1], pj[1])),
                          "closed_form": {"order1": _o((0.0, 0.0)),
                                          "order3": _o((3 * cf["total"][3][0], cf["total"][3][1]))}},
    }


def _fmt_o(o):
    return f"{o['amplitude']:9.4f} N  {o['phase_deg']:8.2f} deg"


def format_analytic(r: dict) -> str:
    """analytic_report's report as `tripod-thrust analytic` prints it."""
    sc = r["scene"]
    lines = [
        "tripod-thrust analytic: reduced model, Eqs. (18)-(27) and the traverse (one roller "
        "unless stated)",
        f"scene: theta = {math.degrees(sc['theta']):.3f} deg, omega = {sc['omega']:.4g} rad/s "
        f"({sc['omega'] / (2 * math.pi):.4g} Hz), {load_text(sc)}, "
        f"mu_groove = {sc['mu_groove']:g}",
        "",
        f"  A      = {r['A'] * 1e3:9.4f} mm/s   (pitching, Eq. 19)",
        f"  B      = {r['B'] * 1e3:9.4f} mm/s   (rolling, Eq. 20)",
        f"  v_st   = {r['v_st'] * 1e3:9.4f} mm/s   ({'automatic, sqrt(A^2+B^2)/4' if sc['v_st'] == 0 else 'set'})",
        f"  C      = {r['C']:9.4f} N      (2nd order of ft, Eq. 25; FFT {r['C_fft']:.4f} N)",
        f"  beta   = {r['beta_deg']:9.4f} deg    (Eq. 27)",
        "",
        f"  {'':28s}{'FFT':>26s}   {'closed form':>26s}",
        f"  {'friction ftz order 1':28s}{_fmt_o(r['friction']['order1'])}   {_fmt_o(r['friction']['closed_form']['order1'])}",
        f"  {'friction ftz order 3':28s}{_fmt_o(r['friction']['order3'])}   {_fmt_o(r['friction']['closed_form']['order3'])}",
        f"  {'spin inertia order 1':28s}{'':26s}   {_fmt_o(r['spin_inertia']['order1'])}",
        f"  {'thrust Fz order 1':28s}{_fmt_o(r['order1'])}   {_fmt_o(r['closed_form']['order1'])}",
        f"  {'thrust Fz order 3':28s}{_fmt_o(r['order3'])}   {_fmt_o(r['closed_form']['order3'])}",
        f"  {'three rollers order 1':28s}{_fmt_o(r['three_rollers']['order1'])}   {_fmt_o(r['three_rollers']['closed_form']['order1'])}",
        f"  {'three rollers order 3':28s}{_fmt_o(r['three_rollers']['order3'])}   {_fmt_o(r['three_rollers']['closed_form']['order3'])}",
        "",
    ]
    t = r.get("traverse")
    if t:
        use = "in use" if r["model"] == "traverse" else "not in use: traverse = false"
        lines += [
            f"reduced traverse model ({use}; docs/model.md): regime {t['regime']}, friction "
            f"reaches {100 * t['friction_reach']:.1f} % of mu_groove F",
            *([] if t["settled"] else [
                f"  NOT periodic: s(2 pi) - s(0) = {t['mismatch']:.2e} m/s after {t['cycles']} "
                "cycles of the cycle map (the table is the best cycle run)"]),
            *([f"  OUTSIDE the range it was checked against the contact model in "
               f"(docs/validation.md): {'; '.join(t['outside_checked'])}"]
              if t["outside_checked"] else []),
            f"  {'Fz_mod order 1':28s}{_fmt_o(t['order1'])}",
            f"  {'Fz_mod order 3':28s}{_fmt_o(t['order3'])}",
            f"  {'three rollers order 3':28s}{_fmt_o(t['three_rollers']['order3'])}",
            ""]
    lines.append("order k is a_k sin(k w t + p_k), t = 0 where pitching is 0 and rising (model.md).")
    return "\n".join(lines)
