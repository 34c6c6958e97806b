"""The FMI 2.0 co-simulation call sequence as the Modelica Reference-FMUs enforce it (their
fmi2Functions.c masks, from the standard's state machine, section 4.2.4): each function is
allowed in these phases and refused with fmi2Error in the others (issue: untrusted input)."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from harness.fmus import ensure_fmu

WORKER = Path(__file__).with_name("call_states.py")
I, N, C, F, T, E = ("instantiated", "initialization", "step complete", "step failed",
                    "terminated", "error")
EVERY = {I, N, C, F, T, E}
ALLOWED = {
    "fmi2SetupExperiment": {I},
    "fmi2EnterInitializationMode": {I},
    "fmi2ExitInitializationMode": {N},
    "fmi2Terminate": {C, F},
    "fmi2Reset": EVERY,
    "fmi2GetReal": EVERY - {I}, "fmi2GetInteger": EVERY - {I},
    "fmi2GetBoolean": EVERY - {I}, "fmi2GetString": EVERY - {I},
    "fmi2SetReal": {I, N, C}, "fmi2SetInteger": {I, N, C},
    "fmi2SetBoolean": {I, N, C}, "fmi2SetString": {I, N, C},
    "fmi2DoStep": {C},
    "fmi2GetRealStatus": EVERY,     # fmi2LastSuccessfulTime: a status inquiry, any phase
    "fmi2GetFMUstate": EVERY, "fmi2SetFMUstate": EVERY, "fmi2FreeFMUstate": EVERY,
    "fmi2SerializedFMUstateSize": EVERY, "fmi2SerializeFMUstate": EVERY,
    "fmi2DeSerializeFMUstate": EVERY,
}


@pytest.mark.parametrize("name,spec", [
    ("TripodRoller", {}), ("TripodRollerAnalytic", {}),
    # the driveline example's powertrain: its input the joint's force, its outputs moving
    ("Powertrain", {"input": "Fz_joint", "outputs": ["torque", "omega", "acc_y"]})])
def test_call_sequence_table(name, spec):
    p = subprocess.run([sys.executable, str(WORKER), str(ensure_fmu(name)), json.dumps(spec)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    wrong = {(phase, fn): status for phase, row in r["table"].items()
             for fn, status in row.items() if (status < 3) != (phase in ALLOWED[fn])}
    assert not wrong, wrong
    assert set(r["table"]) == EVERY and all(set(row) == set(ALLOWED) for row in r["table"].values())
    # a checkpoint restored into a fresh instance (FMI allows fmi2SetFMUstate right after
    # fmi2Instantiate) continues the run it was taken from, bit for bit
    assert r["restored_before_init_identical"] and r["moved"]
    # a corrupt state is refused with fmi2Error and the instance stays in its phase
    assert r["refused_state_keeps_running"]
