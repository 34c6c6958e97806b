"""The bare FMI boundary as a compiled model: BareSlave's variables (the inputs theta, omega,
torque; the output Fz) over functions that do nothing but write Fz, for the native FMI layer
(harness.bench.bare_native_fmu).  What the layer alone costs a step, beside the compiled
FMUs' steps (benchmarks/native_fmu_speed.py)."""

P_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN = 1, 3, 1, 1, 1


def init(P, IN, X, OUT, W):
    """Fz = 0 at the start.  Returns 1."""
    OUT[0] = 0.0
    return 1


def step(P, IN, X, OUT, W, t, h):
    """Nothing to step: Fz = 0.  Returns 1."""
    OUT[0] = 0.0
    return 1


def c_functions():
    """init and step as the native layer's C functions (reduced_model/cfuncs.py)."""
    import numba as nb

    from reduced_model.cfuncs import c_functions as wrap
    return wrap({"init": nb.njit(init), "step": nb.njit(step)},
                (P_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN))


def native_layout() -> dict:
    """Where BareSlave's variables live in the arrays (fmu_src/native_fmu.py)."""
    return {"by_name": {}, "check_order": [],
            "arrays": {"theta": ("IN_IN", 0), "omega": ("IN_IN", 1), "torque": ("IN_IN", 2),
                       "Fz": ("IN_OUT", 0)},
            "sizes": {"P": P_LEN, "IN": IN_LEN, "X": X_LEN, "OUT": OUT_LEN, "W": W_LEN, "TH": 2}}
