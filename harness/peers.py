"""Peers of the contact FMU on the same equations, for `tripod-thrust bench --peer`.

scipy's solve_ivp is what a Python user writes first: the roller's equations of the ideal
bearing with traverse (slide u along the trunnion axis, its rate, the spin rate; the whirl
angle w t drives the trunnion), the right-hand side the kernel's own compiled force evaluation
(kernel.ga_forces: Hertz contact, tanh friction, spin moment, driving accelerations), so the
two differ only in how they integrate.  Outputs Fz' at the communication instants from the
dense solution, like the FMU's.
"""
from __future__ import annotations

import math
import time

import numpy as np

from tripod_model import kernel as K
from tripod_model.model import ContactModel


def solve_ivp_run(method: str = "LSODA", rtol: float = 1e-6, params=None, cycles: float = 2.0,
                  dt_out: float = 1e-4):
    """``cycles`` whirl cycles of the scene (ideal bearing, traverse) by scipy.integrate.solve_ivp.

    rtol: solve_ivp's relative tolerance; atol is rtol x v_st [m/s] on the slide's rate and
    rtol x v_st / r [rad/s] on the spin (the friction's velocity scale) and rtol x 1 um on the
    slide.  Returns (t [s], Fz' [N], {"nfev", "status"}, wall time of solve_ivp [s]).
    """
    from scipy.integrate import solve_ivp
    m = ContactModel(dict(params or {}, bearing=0))
    p = m.p
    theta, w, F = float(p["theta"]), float(p["omega"]), float(p["F_press"])
    m.start(theta, w, F)
    vst = m.v_st(theta, w)
    m.P[K.P_VST] = vst
    x0 = m.pressing_offset(F)
    Y, P, L, res, Q, M = m.Y.copy(), m.P, m._L, m._res, m._b, m._GW[K.W_M]
    xs = Y[K.Y_X]

    def rhs(t, y):
        Y[K.Y_X] = xs + w * t
        Y[K.Y_U], Y[K.Y_UD], Y[K.Y_OM] = y
        K.ga_forces(Y, P, theta, w, x0, L, res, Q, M)
        return (y[1], Q[0] / M[0], Q[1] / M[1])

    n_out = int(round(cycles * 2 * math.pi / w / dt_out))
    t_eval = dt_out * np.arange(1, n_out + 1)
    y0 = (Y[K.Y_U], Y[K.Y_UD], Y[K.Y_OM])
    atol = rtol * np.array([1e-6, vst, vst / p["r_roller"]])
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, t_eval[-1]), y0, method=method, t_eval=t_eval, rtol=rtol,
                    atol=atol)
    wall = time.perf_counter() - t0
    out = np.full(n_out, np.nan)
    for k in range(sol.y.shape[1]):
        Y[K.Y_X] = xs + w * sol.t[k]
        Y[K.Y_U], Y[K.Y_UD], Y[K.Y_OM] = sol.y[:, k]
        K.ga_forces(Y, P, theta, w, x0, L, res, Q, M)
        out[k] = res[2] * F / res[0] if -res[0] > 1e-9 * max(F, 1.0) else 0.0
    return t_eval, out, {"nfev": sol.nfev, "status": sol.status}, wall
