"""What each FMU is, declared once: its description, default experiment and variables (from the
parameter tables), and its modelDescription.xml written from them.  The build writes the XML;
the tests' in-process runs (harness/inprocess.py) read the same variables from it."""
from __future__ import annotations

from typing import NamedTuple
from xml.etree import ElementTree as ET


class Model(NamedTuple):
    description: str
    stop_time: float        # [s] the default experiment's (it starts at 0)
    step_size: float        # [s] the default experiment's communication step


MODELS = {
    "TripodRoller": Model(
        "One roller of a tripod constant-velocity joint in its groove (Sugiura et al.): "
        "trunnion motions as driving constraints, Hertz contact, tanh friction, spin moment, "
        "ideal, lumped or needle-resolved bearing. Thrust Fz and modified thrust Fz_mod.",
        0.2, 1e-4),           # two whirl cycles of the paper's scene (10 Hz)
    "TripodRollerAnalytic": Model(
        "Reduced (analytic) thrust model of one tripod-joint roller: sliding velocities v1 + v2 "
        "(Eqs. 18-24), tanh friction, ftz = ft sin(phi), the roller spin-inertia thrust and "
        "(traverse = true) the roller's slide across the groove with micro-slip. Compiled: "
        "needs nothing on the host.", 0.2, 1e-4),
    "Powertrain": Model(
        "A transverse powertrain on its mounts (lateral, fore-aft, vertical, roll) driving one "
        "tripod joint through a vehicle launch: it gives the joint its angle, plunge speed, "
        "whirl speed and torque and takes the joint's forces on the housing.", 2.5, 1e-4),
}
AUTHOR = "tripod-thrust"
# the FMI 2.0 log categories the slaves and the native layer log under
LOG_CATEGORIES = (("logStatusWarning", "Log messages with fmi2Warning status."),
                  ("logStatusDiscard", "Log messages with fmi2Discard status."),
                  ("logStatusError", "Log messages with fmi2Error status."),
                  ("logStatusFatal", "Log messages with fmi2Fatal status."),
                  ("logAll", "Log all messages."))


class Variable(NamedTuple):
    name: str
    kind: str               # "real", "int" or "bool"
    causality: str          # "input", "parameter" or "output"
    start: object           # the table's default (None for an output: calculated)
    description: str

    @property
    def fmi(self) -> dict:
        """Its FMI 2.0 causality, variability and initial: inputs continuous, parameters fixed,
        outputs calculated at initialisation (continuous Reals, discrete Integers)."""
        if self.causality == "output":
            return dict(causality="output",
                        variability="continuous" if self.kind == "real" else "discrete",
                        initial="calculated")
        return dict(causality=self.causality,
                    variability="continuous" if self.causality == "input" else "fixed")


def variables(name) -> tuple[Variable, ...]:
    """The FMU's variables in value-reference order: the parameter table's entries the model
    uses (inputs and parameters, with their defaults), then its Real outputs, then its Integer
    outputs."""
    if name == "Powertrain":
        from driveline.powertrain import OUTPUTS, TABLE
        params, outs, ints = TABLE, OUTPUTS, ()
    else:
        from reduced_model.scene import CONTACT_ONLY_OUTPUTS, INT_OUTPUTS, OUTPUTS, params_for
        model = "contact" if name == "TripodRoller" else "analytic"
        params = params_for(model)
        outs = OUTPUTS if model == "contact" else \
            tuple(o for o in OUTPUTS if o[0] not in CONTACT_ONLY_OUTPUTS)
        ints = tuple((n, d) for n, d, owner in INT_OUTPUTS if owner == model)
    return (tuple(Variable(p.name, p.kind, p.causality, p.default, p.description)
                  for p in params) +
            tuple(Variable(n, "real", "output", None, d) for n, _u, d in outs) +
            tuple(Variable(n, "int", "output", None, d) for n, d in ints))


_TYPE = {"real": "Real", "int": "Integer", "bool": "Boolean"}


def _start(v: Variable) -> str:
    if v.kind == "real":
        return f"{v.start:.16g}"
    return str(v.start).lower() if v.kind == "bool" else str(int(v.start))


def raw_xml(name) -> bytes:
    """The model description without units, ranges or identity (the build adds them:
    build._units_and_ranges, build._identity)."""
    m = MODELS[name]
    root = ET.Element("fmiModelDescription", dict(
        fmiVersion="2.0", modelName=name, guid="", generationTool="",
        variableNamingConvention="structured", description=m.description, author=AUTHOR))
    ET.SubElement(root, "CoSimulation", dict(
        needsExecutionTool="false", canHandleVariableCommunicationStepSize="true",
        canInterpolateInputs="false", canBeInstantiatedOnlyOncePerProcess="false",
        canGetAndSetFMUstate="true", canSerializeFMUstate="true", modelIdentifier=name,
        canNotUseMemoryManagementFunctions="true"))
    cats = ET.SubElement(root, "LogCategories")
    for c, d in LOG_CATEGORIES:
        ET.SubElement(cats, "Category", name=c, description=d)
    ET.SubElement(root, "DefaultExperiment", startTime="0.0", stopTime=str(m.stop_time),
                  stepSize=str(m.step_size))
    mv = ET.SubElement(root, "ModelVariables")
    outputs = []
    for vr, v in enumerate(variables(name)):
        attrs = v.fmi
        if v.causality == "output":     # calculated at initialisation: no start value
            outputs.append(vr + 1)
        sv = ET.SubElement(mv, "ScalarVariable", dict(name=v.name, valueReference=str(vr),
                                                      description=v.description, **attrs))
        ET.SubElement(sv, _TYPE[v.kind], {} if v.start is None else {"start": _start(v)})
    structure = ET.SubElement(root, "ModelStructure")
    if outputs:
        out = ET.SubElement(structure, "Outputs")
        for i in outputs:
            ET.SubElement(out, "Unknown", index=str(i))
    return ET.tostring(root, encoding="utf-8")
