"""The bare FMI boundary as a compiled model: the inputs a driveline master moves (theta, omega,
torque) and one output (Fz) over functions that do nothing but write Fz, under the FMUs' native
FMI layer (harness.bench.bare_fmu).  What the layer alone costs a step, beside the compiled
FMUs' steps (`tripod-thrust bench`)."""

T_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN = 1, 3, 1, 1, 1


def init(T, IN, X, OUT, W):
    """Fz = 0 at the start.  Returns 1."""
    OUT[0] = 0.0
    return 1


def step(T, IN, X, OUT, W, t, h):
    """Nothing to step: Fz = 0.  Returns 1."""
    OUT[0] = 0.0
    return 1


def c_functions():
    """init and step as the native layer's C functions (reduced_model/cfuncs.py)."""
    import numba as nb

    from reduced_model.cfuncs import c_functions as wrap
    return wrap({"init": nb.njit(init), "step": nb.njit(step)},
                (T_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN))


def model_description() -> bytes:
    """Its modelDescription.xml (FMI 2.0 co-simulation, the GUID fixed: nothing derives it)."""
    ins = "".join(
        f'<ScalarVariable name="{n}" valueReference="{k}" causality="input" '
        f'variability="continuous"><Real start="{v!r}"/></ScalarVariable>'
        for k, (n, v) in enumerate((("theta", 0.1745), ("omega", 62.83), ("torque", 66.0))))
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n<fmiModelDescription fmiVersion="2.0" '
        'modelName="BareSlave" guid="{00000000-0000-0000-0000-000000000001}" '
        'generationTool="tripod-thrust harness/bare_model.py" '
        'variableNamingConvention="structured"><CoSimulation modelIdentifier="BareSlave" '
        'canHandleVariableCommunicationStepSize="true" canGetAndSetFMUstate="true" '
        'canSerializeFMUstate="true"/><ModelVariables>' + ins +
        '<ScalarVariable name="Fz" valueReference="3" causality="output" '
        'variability="continuous" initial="exact"><Real start="0.0"/></ScalarVariable>'
        '</ModelVariables><ModelStructure><Outputs><Unknown index="4"/></Outputs>'
        '</ModelStructure></fmiModelDescription>\n').encode()


def native_layout() -> dict:
    """Where its variables live in the arrays (fmu_src/native_fmu.py)."""
    return {"by_name": {}, "check_order": [],
            "arrays": {"theta": ("IN_IN", 0), "omega": ("IN_IN", 1), "torque": ("IN_IN", 2),
                       "Fz": ("IN_OUT", 0)},
            "sizes": {"T": T_LEN, "IN": IN_LEN, "X": X_LEN, "OUT": OUT_LEN, "W": W_LEN, "TH": 2}}
