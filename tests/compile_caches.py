"""Fill the compile caches a test run reads, once, before pytest-xdist's workers start
(conftest.py): the in-process contact model's numba kernels (the ideal and lumped bearings, the
needle-resolved row, the floating spider) in this process, the FMUs' ahead-of-time build in a
second one beside it.  With the caches filled each worker loads what it needs; empty, every
worker compiled the same kernels at once on the machine's two cores.

Usage: python tests/compile_caches.py   (seconds with the caches filled)
"""
import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# every compiled set-up the tests step in process: numba specializes the kernel for the
# needle-resolved row's work arrays and for the floating spider's advance
SETUPS = ({"bearing": 0}, {"bearing": 1, "n_rollers": 3}, {"bearing": 2, "n_needles": 12},
          {"spider": 1, "n_rollers": 3})


def compile_in_process():
    """Step each of SETUPS once in this process (compiling, or loading, its kernels)."""
    from tripod_model.model import JointModel
    for over in SETUPS:
        JointModel(over).step(1e-3, math.radians(8.0), 20 * math.pi, 4500.0)


def main():
    build = subprocess.Popen([sys.executable, "-m", "harness.cli", "build"], cwd=ROOT,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        compile_in_process()
    finally:
        err = build.communicate()[1]
    if build.returncode != 0:   # the tests that build the FMUs report it in full
        print(f"compile_caches: tripod-thrust build failed: {err.strip().splitlines()[-1:]}",
              file=sys.stderr)
    return build.returncode


if __name__ == "__main__":
    sys.exit(main())
