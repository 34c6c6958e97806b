"""Runs one FMU through FMPy in its own process (so the built FMU's bundled code is what runs).

Reads a JSON request on stdin, writes an .npz of the result and a status JSON, and exits as
any script does; the exit status is 0 exactly when the run succeeded."""
import json
import sys
import time
import traceback


class SettleWatch:
    """FMPy step_finished callback: at each whole whirl cycle from ``min_cycles`` on, stops the
    run once every watched signal is periodic (reduced_model.steady.settled)."""

    def __init__(self, omega, signals, rel_tol, min_cycles, max_cycles):
        self.T = 2 * 3.141592653589793 / omega
        self.omega, self.signals, self.rel_tol = omega, signals, rel_tol
        self.min_cycles, self.max_cycles = min_cycles, max_cycles
        self.next = min_cycles
        self.changes, self.cycles, self.settled = None, 0, False

    def __call__(self, t, recorder):
        if t < self.next * self.T * (1 - 1e-9):
            return True
        import numpy as np
        from reduced_model.steady import cycle_change, settled
        names = [c[0] for c in recorder.cols]
        rows = np.array(recorder.rows, dtype=float)
        tt = rows[:, 0]
        self.changes = {s: cycle_change(tt, rows[:, names.index(s)], self.omega * tt)
                        for s in self.signals}
        self.cycles = self.next
        self.next += 1
        self.settled = all(settled(c, self.rel_tol) for c in self.changes.values())
        return not self.settled

    def report(self):
        from reduced_model.steady import worst
        return {"cycles": self.cycles, "settled": self.settled, "rel_tol": self.rel_tol,
                "max_cycles": self.max_cycles,
                "cycle_change": {s: {f"order{k}": v for k, v in c.items()}
                                 for s, c in (self.changes or {}).items()},
                "worst": worst(self.changes) if self.changes else None}


class Progress:
    """FMPy step_finished callback: every PROGRESS_EVERY s of wall time, one line on stderr,
    "progress <simulated time [s]> <stop time [s]> <whole cycles so far>" (harness.runs reads
    it); then the settle watch's verdict, when there is one."""
    PROGRESS_EVERY = 0.5

    def __init__(self, stop, watch):
        self.stop, self.watch, self.last = stop, watch, time.perf_counter()

    def __call__(self, t, recorder):
        go = self.watch(t, recorder) if self.watch else True
        now = time.perf_counter()
        if now - self.last >= self.PROGRESS_EVERY:
            self.last = now
            cycles = int(t / self.watch.T + 1e-9) if self.watch else 0
            print(f"progress {t!r} {self.stop!r} {cycles}", file=sys.stderr, flush=True)
        return go


def main():
    req = json.loads(sys.stdin.read())
    status = {"ok": False}
    try:
        import numpy as np
        from fmpy import read_model_description, simulate_fmu
        logs = []

        def logger(component, instanceName, st, category, message):
            logs.append(message.decode("utf-8", "replace") if isinstance(message, bytes) else str(message))

        md = read_model_description(req["fmu"])
        inp = None
        if req.get("inputs"):
            cols = req["inputs"]
            names = ["time"] + [k for k in cols if k != "time"]
            inp = np.zeros(len(cols["time"]), dtype=[(n, np.float64) for n in names])
            for n in names:
                inp[n] = cols[n]
        settle = req.get("settle")
        # the project's own analysis, imported before the FMU puts its bundled copy of the
        # project on sys.path
        import reduced_model.steady  # noqa: F401
        watch = SettleWatch(**settle) if settle else None
        t0 = time.perf_counter()
        res = simulate_fmu(req["fmu"], model_description=md,
                           start_values=req.get("start_values", {}),
                           stop_time=req["stop_time"], output_interval=req["output_interval"],
                           output=req.get("outputs"), debug_logging=True, logger=logger,
                           terminate=True, input=inp,
                           step_finished=Progress(req["stop_time"], watch))
        wall = time.perf_counter() - t0
        np.savez(req["out"], **{n: res[n] for n in res.dtype.names})
        status = {"ok": True, "wall_s": wall, "log": logs[-50:]}
        if watch:
            status["settle"] = watch.report()
    except Exception as e:   # reported to the caller, never a traceback on the user's screen
        status = {"ok": False, "error": f"{type(e).__name__}: {e}",
                  "traceback": traceback.format_exc(), "log": locals().get("logs", [])[-50:]}
    with open(req["out"] + ".json", "w") as f:
        json.dump(status, f)
    sys.exit(0 if status["ok"] else 1)


if __name__ == "__main__":
    main()
