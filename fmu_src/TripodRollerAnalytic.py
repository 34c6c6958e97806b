"""pythonfmu slave of the reduced (analytic) thrust model: numpy only.

traverse = true (default): the reduced traverse model's periodic solution, tabulated over the
whirl angle once per operating point (reduced_model/traverse.py); false: Eqs. (18)-(27).
Same variable names as TripodRoller.fmu where the meaning is the same, so it can replace the
contact FMU when only the thrust excitation is needed.  The whirl angle integrates omega.
"""
import copy
import math

from pythonfmu import DefaultExperiment, Fmi2Slave

from reduced_model.scene import REGIME_CODES, check_value, pressing_load, validate
from reduced_model.thrust import Thrust
from reduced_model.traverse import Traverse
from slavekit import Guarded, PickleState, register_table

_INPUTS = ("theta", "omega", "F_press", "torque")
# outputs the reduced model defines (no contact point, no roller spin state)
_OUT = ("Fx", "Fy", "Fz", "Fz_mod", "dFx", "slip_speed", "Fz_joint", "Fz_2", "Fz_3")


class TripodRollerAnalytic(Guarded, PickleState, Fmi2Slave):
    author = "tripod-thrust"
    description = ("Reduced (analytic) thrust model of one tripod-joint roller: sliding "
                   "velocities v1 + v2 (Eqs. 18-24), tanh friction, ftz = ft sin(phi), the "
                   "roller spin-inertia thrust and (traverse = true) the roller's slide across "
                   "the groove with micro-slip. Needs numpy only.")
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.2, step_size=1e-4)

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self._params = register_table(self, "analytic", _OUT)
        self._scene = None
        self._x = [0.0]   # whirl angle of each roller [rad]

    def _initialise(self):
        self._scene = validate({p.name: getattr(self, p.name) for p in self._params}, "analytic")
        n = self._scene["n_rollers"]
        self._x = [2.0 * math.pi * i / 3.0 for i in range(n)]   # rollers at 0, 120, 240 deg
        self._key = None
        self._thrust = None
        self._table = None
        self._prepare()
        self._write_outputs()   # the outputs at the start time, not their declared zeros

    def _prepare(self):
        """Check the inputs and, when the operating point changed, re-derive the constants and
        the traverse model's table (about 0.1 s): at initialisation and on an input change."""
        key = (self.theta, self.omega, self.F_press, self.torque)
        if key == self._key:
            return
        for name, value in zip(_INPUTS, key):
            check_value(name, value)
            self._scene[name] = float(value)
        self._thrust = Thrust(self._scene)
        self._table = None
        sc = self._scene
        if sc["traverse"] and sc["omega"] > 0 and sc["mu_groove"] > 0 and \
                pressing_load(sc["F_press"], sc["torque"], sc["s"]) > 0:
            self._table = Traverse(sc)
            self.regime = REGIME_CODES.index(self._table.regime())
        else:
            self.regime = 0
        self._key = key

    def _get_fmu_state(self):
        return {"vars": super()._get_fmu_state(), "x": list(self._x),
                "scene": copy.deepcopy(self._scene)}

    def _set_fmu_state(self, state):
        super()._set_fmu_state(state["vars"])
        self._x = list(state["x"])
        if state["scene"] != self._scene:      # else the table of this operating point stays
            self._key = None
        self._scene = copy.deepcopy(state["scene"])

    def _advance(self, current_time, step_size):
        self._prepare()
        w = self._scene["omega"] * step_size
        for i in range(len(self._x)):
            self._x[i] += w
        self._write_outputs()
        return True

    def _write_outputs(self):
        """Every output at the rollers' present whirl angles self._x [rad]."""
        F = pressing_load(self._scene["F_press"], self._scene["torque"], self._scene["s"])
        fz = []
        if self._table is not None:
            at = self._table.at
            for i, x in enumerate(self._x):
                r = at(x)
                if i == 0:
                    Fz, Fz_mod, Fx, Fy, slip = r
                fz.append(r[0])
            self.Fz, self.Fz_mod, self.Fx, self.Fy = Fz, Fz_mod, Fx, Fy
            self.dFx = Fx - F
            self.slip_speed = slip
        else:
            at = self._thrust.at
            for i, x in enumerate(self._x):
                r = at(x)
                if i == 0:
                    _, _, ft, V, phi, _ = r
                fz.append(r[0])
            self.Fz = fz[0]
            self.Fy = ft * math.cos(phi)
            self.Fx = F
            self.dFx = 0.0
            self.Fz_mod = self.Fz          # Fx = F_press in Eqs. (18)-(27)
            self.slip_speed = abs(V)
        self.Fz_joint = sum(fz)
        self.Fz_2 = fz[1] if len(fz) > 1 else 0.0
        self.Fz_3 = fz[2] if len(fz) > 2 else 0.0
