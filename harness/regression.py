"""Bitwise regression references of the contact kernel: every bearing and integrator on short
runs of the paper's scene, outputs at every communication step written with 17 significant
digits (exact round trip).  Written before a change that must not alter results
(``python -m harness.regression --write``), checked by tests/test_regression.py.

Bit for bit holds only for the same numerics: the same numpy, numba and llvmlite (uv.lock pins
them), the same libm (glibc picks its sin, exp, pow by CPU) and the same CPU features.  The
references carry a fingerprint of those (``fingerprint.json``); where today's differs, a run
may differ in the last bits of a transcendental function, and what that grows into is the
scene's own sensitivity to a few-ulp perturbation (``rounding_spread``).
"""
from __future__ import annotations

import json
import platform
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
    "resolved_12_one_pass": ({"bearing": 2, "n_needles": 12, "newton_passes": 1}, 0.05),
    "resolved_12_split": ({"bearing": 2, "n_needles": 12, "integrator": 3}, 0.05),
    "three_rollers": ({"n_rollers": 3}, 0.2),
}
COLUMNS = ("Fx", "Fy", "Fz", "Fz_mod", "contact_y", "contact_z", "slip_speed", "roller_spin",
           "Fz_joint")


FINGERPRINT = DATA / "fingerprint.json"
# CPU features that change which code glibc's libm and numba run
_FLAGS = ("sse4_2", "avx", "avx2", "fma", "avx512f")


def fingerprint() -> dict:
    """What decides the last bit of a run: package versions, libm, CPU features."""
    import llvmlite
    import numba
    try:
        words = next(ln for ln in open("/proc/cpuinfo") if ln.startswith("flags")).split()
    except (OSError, StopIteration):
        words = []
    return {"machine": platform.machine(), "libc": "-".join(platform.libc_ver()),
            "python": platform.python_version_tuple()[0] + "." + platform.python_version_tuple()[1],
            "numpy": np.__version__, "numba": numba.__version__,
            "llvmlite": llvmlite.__version__, "cpu": [f for f in _FLAGS if f in words]}


def same_numerics() -> bool:
    """True when the references were written under today's fingerprint (python aside: the
    kernel's arithmetic is numba's and libm's, not the interpreter's)."""
    try:
        ref = json.loads(FINGERPRINT.read_text())
    except (OSError, ValueError):
        return False
    now = fingerprint()
    return all(ref.get(k) == now[k] for k in now if k != "python")


def run(name: str, perturb: float = 0.0) -> np.ndarray:
    """The scene's outputs, one row per communication step (time first); ``perturb`` scales
    the joint angle by (1 + perturb)."""
    from tripod_model.simulate import simulate
    params, cycles = SCENES[name]
    if perturb:
        from reduced_model.scene import BY_NAME
        params = dict(params, theta=params.get("theta", BY_NAME["theta"].default) * (1 + perturb))
    r = simulate(params, cycles=cycles, dt=DT)
    return np.column_stack([r["t"]] + [r[c] for c in COLUMNS])


def rounding_spread(name: str, ulps: int = 4) -> np.ndarray:
    """Per column, how far the scene moves when the joint angle moves by ``ulps`` ulps: the
    scene's own amplification of a few-ulp difference (what another libm's last bit of a sine
    grows into), plus those ulps of each column's scale for the columns the angle leaves
    alone."""
    a, b = run(name), run(name, perturb=ulps * np.finfo(float).eps)
    scale = np.abs(a).max(axis=0)
    return np.abs(a - b).max(axis=0) + ulps * np.finfo(float).eps * scale


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
    FINGERPRINT.write_text(json.dumps(fingerprint(), indent=1) + "\n")
    print(FINGERPRINT)
