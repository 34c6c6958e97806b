"""Runs one FMU through FMPy in its own process (so the built FMU's bundled code is what runs).

Reads a JSON request on stdin, writes an .npz of the result and a status JSON, and exits as
any script does; the exit status is 0 exactly when the run succeeded."""
import json
import sys
import time
import traceback


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
        t0 = time.perf_counter()
        res = simulate_fmu(req["fmu"], model_description=md,
                           start_values=req.get("start_values", {}),
                           stop_time=req["stop_time"], output_interval=req["output_interval"],
                           output=req.get("outputs"), debug_logging=True, logger=logger,
                           terminate=True, input=inp)
        wall = time.perf_counter() - t0
        np.savez(req["out"], **{n: res[n] for n in res.dtype.names})
        status = {"ok": True, "wall_s": wall, "log": logs[-50:]}
    except Exception as e:   # reported to the caller, never a traceback on the user's screen
        status = {"ok": False, "error": f"{type(e).__name__}: {e}",
                  "traceback": traceback.format_exc(), "log": locals().get("logs", [])[-50:]}
    with open(req["out"] + ".json", "w") as f:
        json.dump(status, f)
    sys.exit(0 if status["ok"] else 1)


if __name__ == "__main__":
    main()
