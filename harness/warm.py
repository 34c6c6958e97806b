"""Compile once, before many processes need it: the FMUs (fmu_src/build.py, ahead of time) and
the contact model's kernel as numba runs it in process (its on-disk cache), in two processes
side by side.  A test session of several workers calls this first (tests/conftest.py): else
each worker compiles the same kernel itself on its first in-process run, a minute or two of
CPU apiece, while a third process builds the FMUs.
"""
from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# the in-process configurations whose compiled code differs (the kernel's entry points each
# configuration reaches): each bearing, one and three rollers, the floating spider
IN_PROCESS = ({}, {"n_rollers": 3}, {"bearing": 1}, {"bearing": 2, "n_needles": 12},
              {"spider": 1, "n_rollers": 3, "bearing": 1})

_BUILD = "from harness.fmus import ensure_fmu\nfor n in ('TripodRoller', " \
         "'TripodRollerAnalytic', 'Powertrain'):\n    ensure_fmu(n)\n"
_COMPILE = "from harness.warm import run_in_process\nrun_in_process()\n"


def run_in_process(steps: int = 3) -> None:
    """A few communication steps of each IN_PROCESS configuration at the paper's scene (and a
    state taken and restored), so numba compiles and caches what they reach."""
    import math

    from reduced_model.scene import defaults, validate
    from tripod_model.model import JointModel
    for params in IN_PROCESS:
        m = JointModel(validate(dict(defaults("contact"), **params), "contact"))
        for _ in range(steps):
            m.step(1e-4, math.radians(8.0), 2 * math.pi * 10, 0.0, 300.0)
        m.set_state(m.get_state())


def warm_up(timeout: float = 1800.0) -> str:
    """Build the FMUs and compile the in-process kernel, in two processes at once; returns one
    line saying what each took.  Either failing is only reported: the tests that need it then
    fail with their own message."""
    t0 = time.perf_counter()
    procs = {what: subprocess.Popen([sys.executable, "-c", code], cwd=ROOT,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                    text=True)
             for what, code in (("the FMUs", _BUILD), ("the in-process kernel", _COMPILE))}
    said = []
    for what, p in procs.items():
        try:
            _, err = p.communicate(timeout=max(1.0, timeout - (time.perf_counter() - t0)))
        except subprocess.TimeoutExpired:
            p.kill()
            p.communicate()
            said.append(f"{what}: stopped after {timeout:.0f} s")
            continue
        took = time.perf_counter() - t0
        said.append(f"{what} {took:.0f} s" if p.returncode == 0 else
                    f"{what} failed ({err.strip().splitlines()[-1] if err.strip() else p.returncode})")
    return "compiled before the tests: " + ", ".join(said)
