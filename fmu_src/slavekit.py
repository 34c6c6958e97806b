"""What both pythonfmu slaves share: variables generated from the parameter table, and an FMU
state serialised with pickle (numpy arrays included).  Bundled into each FMU's resources/."""
import pickle
import traceback

from pythonfmu import Boolean, Fmi2Causality, Fmi2Initial, Fmi2Variability, Integer, Real
from pythonfmu.enums import Fmi2Status

from reduced_model.scene import INT_OUTPUTS, OUTPUTS, params_for

_TYPES = {"real": Real, "int": Integer, "bool": Boolean}


def register_table(slave, model, outputs=None):
    """Register the ``model``'s parameters (inputs continuous, parameters fixed) with their
    defaults, and the outputs named in ``outputs`` (all of OUTPUTS if None), on ``slave``.
    Returns the parameter declarations."""
    params = params_for(model)
    for p in params:
        setattr(slave, p.name, p.default)
        if p.causality == "input":
            caus, var = Fmi2Causality.input, Fmi2Variability.continuous
        else:
            caus, var = Fmi2Causality.parameter, Fmi2Variability.fixed
        slave.register_variable(_TYPES[p.kind](p.name, causality=caus, variability=var,
                                               description=p.description))
    # outputs are calculated at initialisation (the model's values at the start time; the
    # build lists them as InitialUnknowns), so they declare no start value
    for name, _unit, desc in OUTPUTS:
        if outputs is None or name in outputs:
            setattr(slave, name, 0.0)
            slave.register_variable(Real(name, causality=Fmi2Causality.output,
                                         variability=Fmi2Variability.continuous,
                                         initial=Fmi2Initial.calculated, description=desc))
    for name, desc, owner in INT_OUTPUTS:
        if owner == model:
            setattr(slave, name, 0)
            slave.register_variable(Integer(name, causality=Fmi2Causality.output,
                                            variability=Fmi2Variability.discrete,
                                            initial=Fmi2Initial.calculated, description=desc))
    return params


class Guarded:
    """The project's error contract for a slave; subclasses supply ``_initialise()`` (raise
    ValueError on a bad parameter) and ``_advance(t, h)`` (raise ValueError on a bad input).

    A bad parameter fails initialisation: the ValueError reaches the native layer, which logs
    its message and returns fmi2Error.  A bad input or any other exception in a step is logged
    here and the step returns Discard.  No output is changed by a failed step.
    """
    _ready = False

    def exit_initialization_mode(self):
        self._ready = False
        try:
            self._initialise()
        except ValueError as e:
            raise ValueError(f"invalid parameter: {e}") from None
        self._ready = True

    def do_step(self, current_time, step_size):
        if not self._ready:
            self.log("doStep before a successful initialisation", Fmi2Status.error)
            return False
        try:
            return self._advance(current_time, step_size)
        except ValueError as e:
            self.log(f"invalid input at t = {current_time:g} s: {e}", Fmi2Status.error)
            return False
        except Exception:   # no exception may escape into the host
            self.log(traceback.format_exc(), Fmi2Status.error)
            return False


class PickleState:
    """FMU state to and from bytes with pickle (pythonfmu's default JSON drops numpy arrays)."""

    @staticmethod
    def _fmu_state_to_bytes(state):
        return pickle.dumps(state, protocol=pickle.HIGHEST_PROTOCOL)

    @staticmethod
    def _fmu_state_from_bytes(data):
        return pickle.loads(data)
