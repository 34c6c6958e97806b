"""The stress subset CI runs, the chatter detector, and the Pareto logic of the benchmark."""
import math
import subprocess
import sys

import numpy as np
import pytest

from harness.bench import pareto, rel_err
from harness.stress import CHATTER_SHARE, chatter_share


def test_stress_quick_subset(tmp_path):
    p = subprocess.run([sys.executable, "-m", "harness.cli", "stress", "--quick", "--out",
                        str(tmp_path)], capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stdout + p.stderr[-2000:]
    assert "8 passed, 0 failed" in p.stdout
    assert (tmp_path / "stress.md").read_text().count("| PASS |") == 8


def test_chatter_share_separates_physics_from_sampling_noise():
    w = 20 * math.pi
    t = np.arange(1, 2001) * 1e-4
    x = w * t
    clean = 6 * np.sin(x + 0.9) + 6 * np.sin(3 * x - 2.3) + 0.2 * np.sin(150 * x)   # + ringing
    assert chatter_share(t, clean, w) < 0.01
    saw = clean + 8 * (-1.0) ** np.arange(t.size)          # period-2 oscillation: chatter
    assert chatter_share(t, saw, w) > CHATTER_SHARE


def test_pareto_and_error_measure():
    pts = [(1.0, 1e-2), (2.0, 1e-3), (3.0, 2e-3), (0.5, 5e-2), (2.0, 1e-2)]
    assert pareto(pts) == [0, 1, 3]
    ref = {1: (2.0, 10.0), 3: (4.0, -30.0)}
    e = rel_err({1: (2.0, 10.0), 3: (4.0 * 1.01, -30.0)}, ref)
    assert e[1] == 0.0 and e[3] == pytest.approx(0.01)
    # a pure phase error of 1 deg is |1 - e^(i 1 deg)| = 1.745 %
    e = rel_err({1: (2.0, 11.0), 3: (4.0, -30.0)}, ref)
    assert e[1] == pytest.approx(2 * math.sin(math.radians(0.5)))
