"""pythonfmu slave of a powertrain on its mounts driving one tripod joint through a vehicle
launch: a thin adapter over driveline.powertrain (its table gives the variables)."""
import math

import numpy as np

from pythonfmu import Fmi2Slave
from pythonfmu.enums import Fmi2Status

from driveline.powertrain import INPUTS, TABLE, PowertrainModel
from reduced_model.scene import check_param
from slavekit import DataState, Guarded, StateError, describe, register, same_layout


@describe
class Powertrain(Guarded, DataState, Fmi2Slave):
    STRUCTURAL = tuple(p.name for p in TABLE if p.causality != "input")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        register(self)
        self.model = None

    def _values(self, params):
        for p in params:
            check_param(p, getattr(self, p.name))
        return {p.name: getattr(self, p.name) for p in params}

    def _initialise(self):
        self.model = PowertrainModel(self._values(TABLE))
        self._write(self.model.outputs())

    def _write(self, out):
        for k, v in out.items():
            setattr(self, k, v)

    def _advance(self, current_time, step_size):
        out = self.model.step(current_time, step_size, self._values(INPUTS))
        if not math.isfinite(sum(out.values())):
            self.log(f"non-finite output at t = {current_time:g} s; step rejected",
                     Fmi2Status.error)
            return False
        self._write(out)
        return True

    # FMU state: the variables and the mounts' state (data only, slavekit)
    def _get_fmu_state(self):
        return {"vars": super()._get_fmu_state(),
                "x": None if self.model is None else self.model.x.copy()}

    def _check_state(self, state):
        if not isinstance(state, dict) or set(state) != {"vars", "x"}:
            raise StateError("expected the keys ['vars', 'x']")
        same_layout(state["vars"], super()._get_fmu_state(), "vars")
        self._check_structural(state["vars"])
        if state["x"] is not None:
            same_layout(state["x"], np.zeros(8), "x")

    def _set_fmu_state(self, state):
        self._check_state(state)
        super()._set_fmu_state(state["vars"])
        if state["x"] is None:
            self.model, self._ready = None, False
            return
        if self.model is None:
            self._initialise()
            self._ready = True
        self.model.x = state["x"].copy()
