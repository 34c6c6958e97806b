"""The analytic report of a scene: FFT of the time series beside the closed form."""
import numpy as np

from . import scene as scene_mod
from .orders import order_spectrum
from .thrust import closed_form, three_roller_thrust, time_series

N_PER_CYCLE = 1440   # samples per whirl cycle for the FFT (model.md asks for >= 400)


def _o(a_p):
    return {"amplitude": float(a_p[0]), "phase_deg": float(a_p[1])}


def analytic_report(overrides=None, n=N_PER_CYCLE):
    """Everything ``tripod-thrust analytic`` prints, as a JSON-ready dict (SI units, deg)."""
    sc = scene_mod.validate(overrides, "analytic")
    x = 2.0 * np.pi * np.arange(n) / n
    ts = time_series(sc, x)
    cf = closed_form(sc)
    a, p = order_spectrum(ts["Fz"], 1, (1, 3))
    af, pf = order_spectrum(ts["ftz"], 1, (1, 3))
    aj, pj = order_spectrum(three_roller_thrust(sc, x), 1, (1, 3))
    c2, _ = order_spectrum(ts["ft"], 1, (2,))
    return {
        "scene": sc,
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
