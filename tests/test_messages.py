"""Values inside their declared ranges that the model cannot compute with are refused at
initialisation with one readable line, never a traceback (a host's log shows it as it is)."""
import json
import subprocess
import sys

import pytest

from harness.fmus import ensure_fmu

_RUN = r'''
import json, math, sys
from fmpy import simulate_fmu
fmu, sv = sys.argv[1], json.loads(sys.argv[2])
logs = []
try:
    r = simulate_fmu(fmu, stop_time=0.002, output_interval=1e-4, start_values=sv,
                     debug_logging=True, logger=lambda c, n, s, cat, msg: logs.append(msg.decode()))
    print(json.dumps({"ok": all(math.isfinite(v) for v in r["Fz"])}))
except Exception:
    print(json.dumps({"refused": [m for m in logs if "invalid" in m or "failed" in m]}))
'''


@pytest.mark.parametrize("name", ["TripodRoller", "TripodRollerAnalytic"])
@pytest.mark.parametrize("sv", [{"omega": 1e-310}, {"F_press": 5e-324}, {"v_st": 5e-324},
                                {"m_roller": 1e-12}, {"torque": 2.2e-308},
                                {"m_roller": 1e-310}])
def test_edge_values_run_finite_or_are_refused_in_one_line(name, sv):
    p = subprocess.run([sys.executable, "-c", _RUN, str(ensure_fmu(name)), json.dumps(sv)],
                       capture_output=True, text=True, timeout=120)
    r = json.loads(p.stdout.strip().splitlines()[-1])
    (var, value), = sv.items()
    if 0 < abs(value) < 2.2250738585072014e-308:   # a subnormal: refused, naming it
        assert any(f"{var} = {value!r} is" in m for m in r.get("refused", [])), r
    if "ok" in r:
        assert r["ok"] is True
    else:
        assert r["refused"], p.stderr[-2000:]
        for m in r["refused"]:
            assert "Traceback" not in m and "\n" not in m and "invalid parameter" in m, m


@pytest.mark.parametrize("name,sv", [("TripodRoller", {"v_st": 1e-12}),
                                     ("TripodRoller", {"max_substep": 1e-300}),
                                     ("TripodRoller", {"integrator": 3, "step_tolerance": 1e-300}),
                                     ("TripodRollerAnalytic", {"v_st": 1e-12})])
def test_values_that_would_step_for_hours_are_refused(name, sv):
    # inside the declared [min, max] (FMI cannot state "0 or at least m") but below what the
    # integrators can serve: v_st = 1e-12 and step_tolerance = 1e-300 had not finished one
    # 1e-4 s step after 120 s, max_substep = 1e-300 overflowed the substep count
    p = subprocess.run([sys.executable, "-c", _RUN, str(ensure_fmu(name)), json.dumps(sv)],
                       capture_output=True, text=True, timeout=120)
    r = json.loads(p.stdout.strip().splitlines()[-1])
    (key,) = sv.keys() - {"integrator"}
    assert any(key in m and "0 (automatic) or [" in m for m in r.get("refused", [])), r
