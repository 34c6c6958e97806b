"""The contact kernel's results against the references in tests/data (written by
`python -m harness.regression --write` before a refactor that must not change results): bit for
bit under the numerics they were written with (tests/data/fingerprint.json: package versions,
libm, CPU features); on any machine within what a few ulps grow into in that scene."""
import numpy as np
import pytest

from harness import regression


def _table(text):
    return np.array([[float(v) for v in ln.split(",")] for ln in text.splitlines()[1:]])


@pytest.mark.parametrize("name", sorted(regression.SCENES))
def test_kernel_reproduces_reference(name):
    ref = regression.path(name).read_text()
    now = regression.text(regression.run(name))
    assert now.count("\n") == ref.count("\n")
    # any machine: a run differs from the reference by what the scene makes of a difference in
    # the last bits (a 4-ulp change of the joint angle, measured here) at every step: each
    # step may add one, and in the roller's undamped rocking mode they add up at most linearly,
    # so the margin is the number of steps (at least 100)
    t = _table(now)
    tol = max(100, len(t)) * regression.rounding_spread(name)
    dev = np.abs(t - _table(ref)).max(axis=0)
    assert (dev <= tol).all(), dict(zip(("time",) + regression.COLUMNS, dev / tol))
    if regression.same_numerics():
        bad = [i for i, (a, b) in enumerate(zip(now.splitlines(), ref.splitlines())) if a != b]
        assert not bad, f"{len(bad)} rows differ, first: row {bad[0]}\nnow {now.splitlines()[bad[0]]}\nref {ref.splitlines()[bad[0]]}"


def test_fingerprint_names_what_decides_the_last_bit():
    f = regression.fingerprint()
    assert {"numpy", "numba", "llvmlite", "libc", "cpu"} <= set(f)
