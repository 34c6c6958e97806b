"""The contact kernel's results are bitwise those of the references in tests/data (written by
`python -m harness.regression --write` before a refactor that must not change results)."""
import pytest

from harness import regression


@pytest.mark.parametrize("name", sorted(regression.SCENES))
def test_kernel_reproduces_reference_bitwise(name):
    ref = regression.path(name).read_text()
    now = regression.text(regression.run(name))
    assert now.count("\n") == ref.count("\n")
    bad = [i for i, (a, b) in enumerate(zip(now.splitlines(), ref.splitlines())) if a != b]
    assert not bad, f"{len(bad)} rows differ, first: row {bad[0]}\nnow {now.splitlines()[bad[0]]}\nref {ref.splitlines()[bad[0]]}"
