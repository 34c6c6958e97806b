"""The generalized-alpha step stepped from Python, the way a general multibody engine runs it:
an implicit fixed step whose Newton iterations call back for the forces.

For the side-by-side of `tripod-thrust bench` (our integrators against explicit
stepping and against such an engine at equal order-3 error).  It runs the very step of the
default integrator (genalpha.ga_step, its plain-Python source) and only the force evaluations
(genalpha._ga_residual -> ga_forces) are compiled: a lower bound of what a Python force callback
costs, so the difference to integrator 4 is what stepping in a host language costs.  Run with
the ideal bearing, the scene of the side-by-side.
"""
from __future__ import annotations

import math
import time

import numpy as np

from reduced_model.thrust import fz_mod
from tripod_model import steplib, genalpha, layout as LY
from tripod_model.model import ContactModel


def simulate(h, params=None, cycles=2.0, dt_out=1e-4):
    """Two (``cycles``) whirl cycles of the scene at a fixed step h [s], stepped in Python.

    Inputs from the parameter table; dt_out [s] a whole number of steps (or h when larger).
    Returns (t [s], Fz' [N], counts {steps, failed}, wall time of the stepping [s]).
    """
    m = ContactModel(dict(params or {}, bearing=0, integrator=4, max_substep=h))
    p = m.p
    theta, w, F = float(p["theta"]), float(p["omega"]), float(p["F_press"])
    m.start(theta, w, F)
    m.P[LY.P_VST_OP] = m.v_st(theta, w)
    x0 = m.pressing_offset(F)
    every = max(1, int(round(dt_out / h)))
    if abs(every * h - max(dt_out, h)) > 1e-9 * h:
        raise ValueError(f"dt_out = {dt_out:g} s is not a whole number of steps h = {h:g} s")
    n_out = int(round(cycles * 2 * math.pi / w / (every * h)))
    Y, P, W = m.Y, m.P, m._W
    drive = LY.Drive(theta, w, x0, 0.0)
    step = genalpha.ga_step.py_func          # the step in Python; its force evaluations compiled
    out = np.zeros(n_out)
    failed = 0
    t0 = time.perf_counter()
    for k in range(n_out):
        reuse = False     # the Jacobian kept within a communication step, as genalpha.ga_steps
        for _ in range(every):
            reuse = step(Y, P, drive, h, W, reuse)
            if not reuse:
                failed += 1           # integrator 4 would hand this step to integrator 3
                W.hs[LY.H_GA] = 0.0
                steplib.adaptive_steps(Y, P, drive, h, 0.25 * h, W, None)
        genalpha.ga_forces(Y, P, drive, W.L, W.res, W.b, W.GW[LY.W_M])
        out[k] = fz_mod(-W.res[LY.R_FX], -W.res[LY.R_FZ], F)
    wall = time.perf_counter() - t0
    t = every * h * np.arange(1, n_out + 1)
    return t, out, {"steps": n_out * every, "failed": failed}, wall
