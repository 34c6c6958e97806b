"""Bitwise regression references of the contact kernel: every bearing and integrator on short
runs of the paper's scene, outputs at every communication step written with 17 significant
digits (exact round trip).  Written before a change that must not alter results
(``python -m harness.regression --write``), checked for exact equality by
tests/test_regression.py.  Same machine class only: another libm or CPU may differ in the last
bit.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from .fmus import ROOT

DATA = ROOT / "tests" / "data"
DT = 1e-4   # communication step [s]
# name: (parameters, whirl cycles of the paper's scene at 10 Hz)
SCENES = {
    "ideal_genalpha": ({}, 1.0),
    "ideal_extrapolated": ({"integrator": 1}, 0.3),
    "ideal_adaptive": ({"integrator": 3}, 0.3),
    "ideal_linearly_implicit": ({"integrator": 0}, 0.2),
    "ideal_explicit": ({"integrator": 2}, 0.05),
    "ideal_no_traverse": ({"traverse": False}, 0.3),
    "lumped_genalpha": ({"bearing": 1}, 0.5),
    "lumped_adaptive": ({"bearing": 1, "integrator": 3}, 0.3),
    "resolved_12": ({"bearing": 2, "n_needles": 12}, 0.05),
    "resolved_12_split": ({"bearing": 2, "n_needles": 12, "integrator": 3}, 0.05),
    "three_rollers": ({"n_rollers": 3}, 0.2),
}
COLUMNS = ("Fx", "Fy", "Fz", "Fz_mod", "contact_y", "contact_z", "slip_speed", "roller_spin",
           "Fz_joint")


def run(name: str) -> np.ndarray:
    """The scene's outputs, one row per communication step (time first)."""
    sys.path.insert(0, str(ROOT / "fmu_src"))
    from tripod_model.model import simulate
    params, cycles = SCENES[name]
    r = simulate(params, cycles=cycles, dt=DT)
    return np.column_stack([r["t"]] + [r[c] for c in COLUMNS])


def path(name: str) -> Path:
    return DATA / f"kernel_{name}.csv"


def text(tab: np.ndarray) -> str:
    """The table as the CSV holds it (17 significant digits: every float64 exactly)."""
    head = ",".join(("time",) + COLUMNS)
    return head + "\n" + "\n".join(",".join(f"{v:.17g}" for v in row) for row in tab) + "\n"


if __name__ == "__main__":
    if "--write" not in sys.argv[1:]:
        sys.exit("usage: python -m harness.regression --write   (overwrites tests/data/kernel_*.csv)")
    DATA.mkdir(parents=True, exist_ok=True)
    for n in SCENES:
        path(n).write_text(text(run(n)))
        print(path(n))
