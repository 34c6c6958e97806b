"""FMU runs through FMPy in a fresh subprocess; results as numpy arrays."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np


class FmuRunError(RuntimeError):
    """The FMU run failed: the message carries the FMU's logged reason."""


def run_fmu(fmu: str | Path, start_values: dict | None = None, stop_time: float = 0.2,
            output_interval: float = 1e-4, outputs: list[str] | None = None,
            timeout: float = 900.0, inputs: dict | None = None) -> dict:
    """Simulate ``fmu`` with FMPy in a new Python process.

    start_values: {name: value} in SI units; stop_time, output_interval [s].
    inputs: time-varying inputs {"time": [...], name: [...]} (FMPy interpolates between rows).
    Returns {"time": array, <output>: array, ..., "wall_s": simulate time [s] in the worker,
    "log": the FMU's last log lines}.  Raises FmuRunError with the FMU's log on failure.
    """
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "result.npz")
        req = {"fmu": str(Path(fmu).resolve()), "start_values": start_values or {},
               "stop_time": stop_time, "output_interval": output_interval,
               "outputs": outputs, "out": out,
               "inputs": {k: [float(x) for x in v] for k, v in (inputs or {}).items()}}
        p = subprocess.run([sys.executable, "-m", "harness.fmu_worker"], input=json.dumps(req),
                           capture_output=True, text=True, timeout=timeout,
                           cwd=tmp)
        status_file = out + ".json"
        if not os.path.exists(status_file):
            raise FmuRunError(f"FMU process died (exit {p.returncode}): {p.stderr.strip()[-2000:]}")
        with open(status_file) as f:
            status = json.load(f)
        if not status["ok"]:
            log = "; ".join(status.get("log", [])[-5:])
            raise FmuRunError(f"{status['error']}" + (f" | FMU log: {log}" if log else ""))
        data = dict(np.load(out))
    data["wall_s"] = status["wall_s"]
    data["log"] = status.get("log", [])
    return data
