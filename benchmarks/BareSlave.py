"""The bare FMI boundary: the inputs a driveline master moves (theta, omega, torque), one
output, a do_step that does nothing.  Built on the FMUs' native layer by harness/bench.py to
measure what the FMI boundary alone costs a step, with and without a master setting inputs."""
from pythonfmu import Fmi2Causality, Fmi2Initial, Fmi2Slave, Fmi2Variability, Real


class BareSlave(Fmi2Slave):
    description = "trivial slave: the cost of the pythonfmu/FMI boundary alone"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.theta, self.omega, self.torque = 0.1745, 62.83, 66.0
        self.Fz = 0.0
        for name in ("theta", "omega", "torque"):
            self.register_variable(Real(name, causality=Fmi2Causality.input,
                                        variability=Fmi2Variability.continuous))
        self.register_variable(Real("Fz", causality=Fmi2Causality.output,
                                    variability=Fmi2Variability.continuous,
                                    initial=Fmi2Initial.exact))

    def do_step(self, current_time, step_size):
        return True
