"""FMU runs through FMPy in a fresh subprocess; results as numpy arrays."""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np


class FmuRunError(RuntimeError):
    """The FMU run failed: the message carries the FMU's logged reason."""


DT = 1e-4                 # default communication step [s]
SAMPLES_PER_CYCLE = 1000  # ... or shorter, so that a whirl cycle holds at least this many


def default_dt(omega: float) -> float:
    """Communication step [s] for a run at whirl speed omega [rad/s]: DT, or a
    SAMPLES_PER_CYCLE-th of the whirl cycle when that is shorter (a fast whirl sampled at
    1e-4 s, 105 samples a cycle at 600 rad/s, moved the order-3 estimate of an exactly
    periodic signal by 0.5 % from one cycle to the next: interpolation, not settling)."""
    return min(DT, 2.0 * math.pi / omega / SAMPLES_PER_CYCLE) if omega > 0 else DT


def run_fmu(fmu: str | Path, start_values: dict | None = None, stop_time: float = 0.2,
            output_interval: float = 1e-4, outputs: list[str] | None = None,
            timeout: float = 900.0, inputs: dict | None = None,
            settle: dict | None = None, progress: str | None = None) -> dict:
    """Simulate ``fmu`` with FMPy in a new Python process.

    start_values: {name: value} in SI units; stop_time, output_interval [s].
    inputs: time-varying inputs {"time": [...], name: [...]} (FMPy interpolates between rows).
    settle: run until periodic instead of to stop_time, {"omega" [rad/s], "signals": [names],
    "rel_tol", "min_cycles", "max_cycles"} (see ``settle_request``); the result then carries
    "settle": {"cycles", "settled", "cycle_change", "worst", ...}.
    Returns {"time": array, <output>: array, ..., "wall_s": simulate time [s] in the worker,
    "log": the FMU's last log lines}.  Raises FmuRunError with the FMU's log on failure.
    progress: a label; on a terminal, a run longer than PROGRESS_AFTER s shows how far it got
    under it (one line on stderr, overwritten, cleared at the end).
    """
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "result.npz")
        req = {"fmu": str(Path(fmu).resolve()), "start_values": start_values or {},
               "stop_time": stop_time, "output_interval": output_interval,
               "outputs": outputs, "out": out, "settle": settle,
               "inputs": {k: [float(x) for x in v] for k, v in (inputs or {}).items()}}
        p = _worker(req, timeout, tmp, progress)
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
    if "settle" in status:
        data["settle"] = status["settle"]
    return data


PROGRESS_AFTER = 2.0   # [s] of wall time before a run shows its progress


class Ticker:
    """For work that reports no simulated time (the example's SSP runs): on a terminal, after
    PROGRESS_AFTER s, ``label`` and the wall time so far on one line of stderr, updated every
    half second and cleared at the end.  Nothing without a label or a terminal."""

    def __init__(self, label: str | None):
        self.label = label if label is not None and sys.stderr.isatty() else None
        self.done = threading.Event()
        self.thread = None

    def _tick(self):
        t0 = time.monotonic()
        shown = False
        while not self.done.wait(0.5):
            if time.monotonic() - t0 >= PROGRESS_AFTER:
                sys.stderr.write(f"\r{self.label}, {time.monotonic() - t0:.0f} s ")
                sys.stderr.flush()
                shown = True
        if shown:
            sys.stderr.write("\r\033[K")
            sys.stderr.flush()

    def __enter__(self):
        if self.label is not None:
            self.thread = threading.Thread(target=self._tick, daemon=True)
            self.thread.start()
        return self

    def __exit__(self, *exc):
        self.done.set()
        if self.thread is not None:
            self.thread.join()


def _worker(req: dict, timeout: float, cwd: str, label: str | None):
    """harness.fmu_worker on ``req``: the finished process (stdout, stderr without the progress
    lines).  With ``label`` and a terminal on stderr, the worker's progress lines become one
    line there after PROGRESS_AFTER s."""
    show = label is not None and sys.stderr.isatty()
    proc = subprocess.Popen([sys.executable, "-m", "harness.fmu_worker"], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=cwd)
    t0 = time.monotonic()
    out = []

    def read_stderr():
        shown = False
        for line in proc.stderr:
            if not line.startswith("progress "):
                out.append(line)
                continue
            if show and time.monotonic() - t0 >= PROGRESS_AFTER:
                t, stop, cycles = line.split()[1:]
                cyc = f", whirl cycle {cycles} done" if int(cycles) else ""
                sys.stderr.write(f"\r{label}: {float(t):.3f} of at most {float(stop):.3f} s "
                                 f"simulated{cyc}, {time.monotonic() - t0:.0f} s ")
                sys.stderr.flush()
                shown = True
        if shown:
            sys.stderr.write("\r\033[K")
            sys.stderr.flush()

    reader = threading.Thread(target=read_stderr, daemon=True)
    reader.start()
    watchdog = threading.Timer(timeout, proc.kill)
    watchdog.start()
    try:
        proc.stdin.write(json.dumps(req))
        proc.stdin.close()
        stdout = proc.stdout.read()
        proc.wait()
    finally:
        watchdog.cancel()
        reader.join()
    if time.monotonic() - t0 >= timeout and proc.returncode < 0:
        raise subprocess.TimeoutExpired(proc.args, timeout)
    return subprocess.CompletedProcess(proc.args, proc.returncode, stdout, "".join(out))


def settle_request(omega: float, signals, rel_tol: float | None = None,
                   max_cycles: int | None = None, min_cycles: int | None = None) -> tuple[dict, float]:
    """(settle request, stop time [s]) for ``run_fmu``: run whole whirl cycles at omega [rad/s]
    until ``signals`` are periodic within rel_tol, at most max_cycles."""
    from reduced_model import steady
    rel_tol = steady.REL_TOL if rel_tol is None else float(rel_tol)
    if not 0 < rel_tol < 1:
        raise ValueError(f"settle tolerance = {rel_tol}: allowed range (0, 1)")
    max_cycles = steady.MAX_CYCLES if max_cycles is None else int(max_cycles)
    min_cycles = steady.MIN_CYCLES if min_cycles is None else int(min_cycles)
    if max_cycles < min_cycles:
        raise ValueError(f"max-cycles = {max_cycles}: allowed range [{min_cycles}, 1000]")
    req = {"omega": omega, "signals": list(signals), "rel_tol": rel_tol,
           "min_cycles": min_cycles, "max_cycles": max_cycles}
    return req, max_cycles * 2 * math.pi / omega


def run_settled(fmu, start_values: dict, omega: float, signals, dt: float = 1e-4,
                max_cycles: int | None = None, rel_tol: float | None = None,
                progress: str | None = None) -> dict:
    """run_fmu for whole whirl cycles until ``signals`` are periodic (or the cap): the result
    carries "settle" (cycles used, settled, the last cycle-to-cycle change)."""
    if rel_tol is None:
        from reduced_model.steady import tolerance_for
        rel_tol = tolerance_for(start_values)
    req, stop = settle_request(omega, signals, rel_tol, max_cycles)
    return run_fmu(fmu, start_values, stop_time=stop, output_interval=dt, settle=req,
                   progress=progress)


def settle_line(st: dict) -> str:
    """One line on how a run settled (for tables and logs)."""
    w = st["worst"]
    last = (f"last cycle-to-cycle change {100 * w['complex_rel']:.3g} % ({w['signal']} order "
            f"{w['order']}: amplitude {100 * w['amplitude_rel']:+.3g} %, phase "
            f"{w['phase_deg']:+.3g} deg)") if w else ""
    if st["settled"]:
        return f"settled after {st['cycles']} whirl cycles (tolerance {100 * st['rel_tol']:g} %); {last}"
    return (f"NOT SETTLED: the cap of {st['max_cycles']} whirl cycles was hit; {last} "
            f"(raise --max-cycles)")
