"""The FMUs' native layers in the hosts that load them: a plain C host (dlopen, no libpython
linked or preloaded, a clean environment), FMPy in fresh processes whose exit status must be 0,
and the call sequence and status codes of FMI 2.0.  The FMUs run compiled
(fmu_src/native/fmi2_native.c) and start no Python."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import extract, read_model_description

from harness.fmus import ROOT, ensure_fmu

NAMES = ("TripodRoller", "TripodRollerAnalytic")
HOST_SRC = Path(__file__).with_name("c_host") / "fmi2_host.c"
# a C host's environment: no virtualenv, no PYTHONPATH, no LD_PRELOAD
CLEAN_ENV = {"PATH": "/usr/bin:/bin", "HOME": os.environ.get("HOME", "/root")}


@pytest.fixture(scope="module")
def c_host(tmp_path_factory):
    """The C host, compiled with the system compiler against the FMI 2.0 headers."""
    import fmpy
    exe = tmp_path_factory.mktemp("host") / "fmi2_host"
    cc = os.environ.get("CC") or "cc"
    subprocess.run(cc.split()[:1] + ["-std=c11", "-O2", "-Wall", "-Wextra", "-Werror",
                                     f"-I{Path(fmpy.__file__).parent / 'c-code'}",
                                     str(HOST_SRC), "-o", str(exe), "-ldl", "-lpthread"],
                   check=True)
    return exe


def _unzipped(name):
    fmu = ensure_fmu(name)
    md = read_model_description(str(fmu))
    return md, extract(str(fmu)), {v.name: v.valueReference for v in md.modelVariables}


def _host(c_host, name, out, *ints, env=None):
    md, d, vr = _unzipped(name)
    return subprocess.run([str(c_host), d, md.coSimulation.modelIdentifier, md.guid,
                           str(vr["Fz"]), "0.2", "1e-4", str(out)] + [f"{vr[k]}={v}" for k, v in ints],
                          capture_output=True, text=True, timeout=600, env=env or CLEAN_ENV)


@pytest.mark.parametrize("name", NAMES)
def test_c_host_matches_fmpy(c_host, tmp_path, name):
    """Two whirl cycles, state rollback and serialisation, unload and reload, a second run from
    another thread, two instances: every check of the host holds, and its Fz is FMPy's to
    1e-12 (the same code in the same process kind: in fact bit for bit)."""
    p = _host(c_host, name, tmp_path / "fz.txt")
    assert p.returncode == 0, p.stdout + p.stderr[-3000:]
    checks = [ln for ln in p.stdout.splitlines() if ln.startswith("check ")]
    assert len(checks) >= 12 and all(ln.endswith(" ok") for ln in checks), p.stdout
    assert "unloaded ok" in p.stdout and "second_round_from_thread ok" in p.stdout
    fz_c = np.loadtxt(tmp_path / "fz.txt")
    from harness.runs import run_fmu
    fz_py = run_fmu(ensure_fmu(name), {}, stop_time=0.2, output_interval=1e-4)["Fz"][1:]
    assert fz_c.shape == fz_py.shape == (2000,)
    assert np.allclose(fz_c, fz_py, rtol=0, atol=1e-12 * np.abs(fz_py).max())


def test_c_host_invalid_parameter_is_error_not_fatal(c_host, tmp_path):
    p = _host(c_host, "TripodRoller", tmp_path / "fz.txt", ("bearing", 7))
    assert p.returncode == 0, p.stderr
    assert "exit_initialization_status 3 (set 0)" in p.stdout      # fmi2Error = 3, not Fatal
    assert "do_step_after_failed_init_status 3" in p.stdout        # the instance is in error
    assert "invalid parameter: bearing = 7 is outside the allowed range" in p.stderr


def test_fresh_processes_exit_clean():
    """20 fresh Python processes of each FMU through fmpy.simulate_fmu and 5 through `fmpy
    simulate`: every exit status 0 (benchmarks/exit_clean.py runs the issue's 300 + 50)."""
    p = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "exit_clean.py"),
                        "--runs", "20", "--cli-runs", "5"],
                       capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stdout + p.stderr
    for name in NAMES:
        assert f"| {name} | simulate_fmu | 20 | 0 | 0 |" in p.stdout, p.stdout
        assert f"| {name} | fmpy simulate | 5 | 0 | 0 |" in p.stdout, p.stdout


@pytest.mark.parametrize("name", NAMES)
def test_c_host_under_a_non_ascii_folder(c_host, tmp_path, name):
    # a C host that never calls setlocale runs in the "C" locale: a resource folder named
    # 'jürgen x' works
    import shutil
    md, d, vr = _unzipped(name)
    where = tmp_path / "jürgen x"
    shutil.copytree(d, where)
    p = subprocess.run([str(c_host), str(where), md.coSimulation.modelIdentifier, md.guid,
                        str(vr["Fz"]), "0.01", "1e-4", str(tmp_path / "fz.txt")],
                       capture_output=True, text=True, timeout=600, env=CLEAN_ENV)
    assert p.returncode == 0, p.stdout + p.stderr[-3000:]
    assert "check no_error_logged ok" in p.stdout


_GET_EARLY = r'''
import sys
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
fmu = sys.argv[1]
md = read_model_description(fmu)
s = FMU2Slave(guid=md.guid, unzipDirectory=extract(fmu),
              modelIdentifier=md.coSimulation.modelIdentifier, instanceName="a")
s.instantiate()
vr = [v.valueReference for v in md.modelVariables if v.name == "Fz"]
try:
    s.getReal(vr)
    print("answered")
except Exception:
    print("refused")
s.setupExperiment(startTime=0.0)
s.enterInitializationMode()
s.getReal(vr)                      # allowed from initialisation mode on
print("init ok")
'''


@pytest.mark.parametrize("name", NAMES)
def test_get_before_initialisation_mode_is_refused(name):
    # the FMI 2.0 co-simulation state machine (as the Reference-FMUs implement it): fmi2GetReal
    # right after fmi2Instantiate is an error, from initialisation mode on it answers
    p = subprocess.run([sys.executable, "-c", _GET_EARLY, str(ensure_fmu(name))],
                       capture_output=True, text=True, timeout=120)
    said = [ln for ln in p.stdout.splitlines() if not ln.startswith("[")]
    assert said == ["refused", "init ok"], p.stdout + p.stderr[-2000:]
    assert "fmi2GetReal is not allowed in phase 'instantiated'" in p.stdout
