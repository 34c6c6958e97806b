"""How far the adaptive substeps run from their budget (tripod_model/budget.py) in ordinary
scenes: the largest share of a step's budget of tries used, and the largest ratio of the floor
to a substep tried (both 1 where the budget binds).  benchmarks/step_budget.py prints the table;
docs/integrators.md carries it.

Each scene runs one whirl cycle at 10 Hz and 1e-4 s steps, then takes a step in each input
(theta +10 %, omega +10 %, torque -10 %, and the torque reversed) and runs a tenth of a cycle
after each: the adaptive substeps run throughout with integrator 3, and after each step input
and Newton failure with the default integrator.
"""
from __future__ import annotations

import math
import time

from reduced_model.scene import DEG
from tripod_model import layout as K
from tripod_model.model import JointModel

DT = 1e-4
OMEGA = 2 * math.pi * 10.0
SCENES = [   # label, parameters, theta [deg], torque [N m]
    ("ideal, default integrator, 8 deg, 300 N m", {}, 8.0, 300.0),
    ("ideal, adaptive (integrator 3), 8 deg, 300 N m", {"integrator": 3}, 8.0, 300.0),
    ("lumped, default integrator, 8 deg, 300 N m", {"bearing": 1}, 8.0, 300.0),
    ("lumped, adaptive, 8 deg, 300 N m", {"bearing": 1, "integrator": 3}, 8.0, 300.0),
    ("ideal, default integrator, launch: 25 deg, 3000 N m", {}, 25.0, 3000.0),
    ("lumped, default integrator, launch: 25 deg, 3000 N m", {"bearing": 1}, 25.0, 3000.0),
    ("lumped, default integrator, 44 deg, 6000 N m", {"bearing": 1}, 44.0, 6000.0),
    ("lumped, adaptive, 44 deg, 6000 N m", {"bearing": 1, "integrator": 3}, 44.0, 6000.0),
    ("ideal, three rollers, 8 deg, 300 N m", {"n_rollers": 3}, 8.0, 300.0),
    ("needle-resolved (12), adaptive, 8 deg, 300 N m",
     {"bearing": 2, "n_needles": 12, "integrator": 3}, 8.0, 300.0),
]


def budget_use(params: dict, theta_deg: float, torque: float, cycles: float = 1.0) -> dict:
    """Run the scene and its input steps (module docstring) in-process; returns the largest
    share of a step's tries used and the largest floor / substep over every roller, and the
    adaptive substeps taken."""
    theta = theta_deg * DEG
    m = JointModel(dict(params, theta=theta, omega=OMEGA, F_press=0.0, torque=torque))
    n = int(round(cycles * 2 * math.pi / OMEGA / DT))
    after = max(1, n // 10)
    inputs = [(theta, OMEGA, torque, n), (1.1 * theta, OMEGA, torque, after),
              (1.1 * theta, 1.1 * OMEGA, torque, after),
              (1.1 * theta, 1.1 * OMEGA, 0.9 * torque, after),
              (1.1 * theta, 1.1 * OMEGA, -0.9 * torque, 3 * after)]
    for th, w, tq, k in inputs:
        for _ in range(k):
            m.step(DT, th, w, 0.0, tq)
    hs = [r._hs for r in m.rollers]
    return {"tries": max(h[K.H_USE_TRIES] for h in hs),
            "floor": max(h[K.H_USE_FLOOR] for h in hs),
            "taken": sum(int(h[K.H_TAKEN]) for h in hs)}


def table(scenes=SCENES) -> str:
    lines = ["| scene | largest share of a step's tries used | largest floor / substep tried "
             "| run [s] |", "|---|---|---|---|"]
    for label, params, theta, torque in scenes:
        t0 = time.perf_counter()
        u = budget_use(params, theta, torque)
        lines.append(f"| {label} | {u['tries']:.3g} | {u['floor']:.3g} | "
                     f"{time.perf_counter() - t0:.1f} |")
    return "\n".join(lines)
