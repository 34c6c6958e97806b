"""A second FMI importer: libcosim (Open Simulation Platform) through libcosimpy.

Runs in a subprocess like the FMPy runs; same start-value and result conventions as runs.py.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from .runs import FmuRunError

_WORKER = r'''
import json, sys
import numpy as np
req = json.loads(sys.stdin.read())
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
log_output_level(CosimLogLevel.ERROR)
from libcosimpy.CosimEnums import CosimVariableType
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave
step = int(round(req["step"] * 1e9))
ex = CosimExecution.from_step_size(step_size=step)
idx = ex.add_local_slave(local_slave=CosimLocalSlave(fmu_path=req["fmu"], instance_name="fmu"))
infos = {v.name.decode(): v for v in ex.slave_variables(slave_index=idx)}
for name, value in req["start_values"].items():
    v = infos[name]
    t = v.type
    if t == CosimVariableType.REAL.value:
        ex.real_initial_value(slave_index=idx, variable_reference=v.reference, value=float(value))
    elif t == CosimVariableType.INTEGER.value:
        ex.integer_initial_value(slave_index=idx, variable_reference=v.reference, value=int(value))
    elif t == CosimVariableType.BOOLEAN.value:
        ex.boolean_initial_value(slave_index=idx, variable_reference=v.reference, value=bool(value))
n = int(round(req["stop_time"] / req["step"]))     # every step's sample: t = 0 .. stop - step
obs = CosimObserver.create_time_series(buffer_size=max(10000, 2 * n))   # (the default: 10,000)
ex.add_observer(observer=obs)
for name in req["outputs"]:
    obs.start_time_series(idx, value_reference=infos[name].reference, variable_type=CosimVariableType.REAL)
ok = ex.simulate_until(target_time=int(round(req["stop_time"] * 1e9)))
res = {}
for name in req["outputs"]:
    times, steps, vals = obs.time_series_real_samples(slave_index=idx, value_reference=infos[name].reference, from_step=0, sample_count=n + 10)
    res[name] = np.asarray(vals, float)
    res["time"] = np.asarray(times, float) * 1e-9
    if len(vals) != n or steps[0] != 0:
        json.dump({"ok": False, "why": f"libcosim kept {len(vals)} of the {n} samples of {name} (steps {steps[0]}-{steps[-1]}, t {times[0]}-{times[-1]} ns)"},
                  open(req["out"] + ".json", "w"))
        sys.exit(0)
np.savez(req["out"], **res)
with open(req["out"] + ".json", "w") as f:
    json.dump({"ok": bool(ok)}, f)
'''


def run_libcosim(fmu, start_values: dict | None = None, stop_time: float = 0.2,
                 step: float = 1e-4, outputs=("Fz_mod",), timeout: float = 600.0) -> dict:
    """Co-simulate one FMU with libcosim in a new process; returns {"time", <output>...}.

    libcosim samples the outputs at the start of each step (t = 0, step, ...), i.e. the values
    written by the previous doStep.  Every sample of the run is returned (the observer's buffer
    is sized for it), or FmuRunError says how many libcosim kept.
    """
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.npz")
        req = {"fmu": os.path.abspath(str(fmu)), "start_values": start_values or {},
               "stop_time": stop_time, "step": step, "outputs": list(outputs), "out": out}
        p = subprocess.run([sys.executable, "-c", _WORKER], input=json.dumps(req),
                           capture_output=True, text=True, timeout=timeout, cwd=tmp)
        if not os.path.exists(out + ".json"):
            raise FmuRunError(f"libcosim run failed (exit {p.returncode}): {p.stderr.strip()[-1500:]}")
        with open(out + ".json") as f:
            st = json.load(f)
        if not st["ok"]:
            raise FmuRunError(st.get("why", "libcosim simulate_until returned false"))
        return dict(np.load(out))
