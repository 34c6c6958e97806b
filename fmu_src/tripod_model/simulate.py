"""Runs of the in-process model at constant inputs, for tests, the regression data and quick
looks (users run the FMU)."""
import math

import numpy as np

from reduced_model import scene as scene_mod
from reduced_model.scene import OUTPUTS

from .model import JointModel


def simulate(params=None, theta=None, omega=None, F_press=None, cycles=2.0, dt=1e-4,
             duration=None):
    """Run the model in-process at constant inputs; returns dict of arrays incl. t and whirl.

    Runs ``cycles`` whirl cycles, or ``duration`` [s] when given (needed at omega = 0).
    For tests and quick looks; users run the FMU.  Inputs default to the parameter table.
    """
    d = scene_mod.defaults("contact")
    theta = d["theta"] if theta is None else theta
    omega = d["omega"] if omega is None else omega
    F_press = d["F_press"] if F_press is None else F_press
    params = {k: v for k, v in (params or {}).items() if k not in ("theta", "omega", "F_press")}
    m = JointModel(dict(params, theta=theta, omega=omega, F_press=F_press))
    if duration is None:
        duration = cycles * 2 * math.pi / omega
    nsteps = int(round(duration / dt))
    rec = {k: np.empty(nsteps) for k, _, _ in OUTPUTS}
    t = np.arange(1, nsteps + 1) * dt
    for i in range(nsteps):
        o = m.step(dt, theta, omega, F_press)
        for k in rec:
            rec[k][i] = o[k]
    rec["t"] = t
    rec["whirl"] = omega * t
    rec["substeps"] = m.rollers[0].substeps
    rec["params"] = m.p
    return rec
