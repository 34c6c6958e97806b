"""Where the FMUs are and how to (re)build them: a thin wrapper over fmu_src/build.py."""
from __future__ import annotations

import importlib.util
from functools import lru_cache
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FMU_NAMES = ("TripodRoller", "TripodRollerAnalytic")


@lru_cache(maxsize=1)
def builder():
    """fmu_src/build.py as a module (fmu_src is not a package: it is what goes into the FMUs)."""
    spec = importlib.util.spec_from_file_location("tripod_fmu_build", ROOT / "fmu_src" / "build.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def ensure_fmu(name: str = "TripodRoller", force: bool = False) -> Path:
    """Path of build/<name>.fmu, built first when missing, stale or forced."""
    return builder().build(name, force=force)


def reference_fmu(name: str) -> Path:
    """build/reference/<name>.fmu, built first when missing or stale: the pythonfmu slave's FMU
    of a model whose FMU ships compiled (the analytic FMU, the powertrain), which the tests
    hold the compiled FMU to."""
    ensure_fmu(name)
    return builder().reference_path(name)
