"""The bare FMI boundary: one input, one output, a do_step that does nothing.  Built on the
FMUs' native layer by harness/bench.py to measure what the FMI boundary alone costs a step."""
from pythonfmu import Fmi2Causality, Fmi2Initial, Fmi2Slave, Fmi2Variability, Real


class BareSlave(Fmi2Slave):
    description = "trivial slave: the cost of the pythonfmu/FMI boundary alone"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.theta = 0.0
        self.Fz = 0.0
        self.register_variable(Real("theta", causality=Fmi2Causality.input,
                                    variability=Fmi2Variability.continuous))
        self.register_variable(Real("Fz", causality=Fmi2Causality.output,
                                    variability=Fmi2Variability.continuous,
                                    initial=Fmi2Initial.exact))

    def do_step(self, current_time, step_size):
        return True
