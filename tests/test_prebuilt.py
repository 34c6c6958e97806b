"""The prebuilt kernel (fmu_src/aot.py, tripod_model/native.py): the contact FMU's reference
(the pythonfmu slave the compiled FMU is held to) carries its step compiled ahead of time, so a
scene without resolved needles runs without numba.  It must
be the same kernel: every output bit for bit against the FMU with numba compiling it
(TRIPOD_AOT=0), through Python and through the native fast path, one and three rollers, with
the inputs changing mid-run; and the process must not import numba at all."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from harness.fmus import reference_fmu

_RUN = r'''
import json, sys, numpy as np
from fmpy import simulate_fmu
req = json.loads(sys.argv[1])
logs = []
t = np.array([0.0, 0.05 - 1e-9, 0.05, 0.2])   # theta steps from 10 to 12 deg at 0.05 s
inputs = np.array(list(zip(t, np.radians([10, 10, 12, 12]))),
                  dtype=[("time", float), ("theta", float)])
r = simulate_fmu(req["fmu"], stop_time=0.2, output_interval=1e-4, start_values=req["sv"],
                 input=inputs, debug_logging=True,
                 logger=lambda c, n, s, cat, msg: logs.append(msg.decode()))
np.save(req["out"], np.column_stack([r[n] for n in r.dtype.names]))
print(json.dumps({"numba": "numba" in sys.modules,
                  "kernel": [m.split("kernel ")[-1] for m in logs if "; kernel " in m]}))
'''


def _run(tmp_path, sv, aot):
    out = str(tmp_path / f"r{aot}.npy")
    req = {"fmu": str(reference_fmu("TripodRoller")), "sv": sv, "out": out}
    p = subprocess.run([sys.executable, "-c", _RUN, json.dumps(req)], capture_output=True,
                       text=True, env=dict(os.environ, TRIPOD_AOT=aot), timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    return np.load(out), json.loads(p.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("sv", [{}, {"bearing": 1}, {"integrator": 1}, {"n_rollers": 3}],
                         ids=["default", "lumped", "integrator1", "three-rollers"])
def test_prebuilt_kernel_is_bitwise_the_numba_kernel(tmp_path, sv):
    jit, jit_info = _run(tmp_path, sv, "0")
    pre, pre_info = _run(tmp_path, sv, "1")
    assert jit_info["numba"] and jit_info["kernel"] == ["numba"]
    assert not pre_info["numba"], "the prebuilt kernel's process imported numba"
    assert pre_info["kernel"] == ["prebuilt (no numba at run time)"]
    assert np.isfinite(pre).all() and np.array_equal(pre, jit)


def test_the_build_rebuilds_the_prebuilt_kernel_from_the_sources_the_fmu_checks():
    # the FMU loads the library only when its content hash is today's sources' (the kernel's
    # package and the reduced model's modules it compiles): the build's freshness test is that
    # same hash (a change to reduced_model/scene.py once left a library the FMU then ignored,
    # stepping with numba instead)
    from harness.fmus import builder
    from tripod_model import native
    _, meta = builder().prebuilt_kernel()
    assert json.loads(meta.read_text())["hash"] == native.source_hash()
