"""The needle row's contacts run on two threads (needles.needle_forces_2): each thread writes
only its own needles and its own side buffers, summed in a fixed order, so a run does not
depend on how many threads numba has.  A race would show as runs that differ bit for bit."""
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RUN = """
import json, sys
sys.path[:0] = [{root!r}, {root!r} + "/fmu_src"]
from tripod_model.model import simulate
r = simulate({{"bearing": 2, "n_needles": 12}}, cycles=0.15)
print(json.dumps([float(x).hex() for x in (r["Fz_mod"][-1], r["Fx"][-1], r["Fy"][-1])]))
"""


def _run(threads):
    env = dict(os.environ, NUMBA_NUM_THREADS=str(threads))
    p = subprocess.run([sys.executable, "-c", RUN.format(root=str(ROOT))], env=env,
                       capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stderr[-2000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


def test_needle_row_bitwise_the_same_on_one_or_two_threads():
    two = _run(2)
    assert _run(1) == two
    assert _run(2) == two   # and run to run
