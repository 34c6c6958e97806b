"""Each FMU runs its own code: the FMUs, compiled, carry no Python, so FMUs in one process never
run each other's modules or an installed copy of the project."""
import json
import subprocess
import sys
import zipfile
from pathlib import Path


from harness.fmus import ensure_fmu

SEQ = [("TripodRoller", {"bearing": 0}), ("TripodRoller", {"bearing": 1}),
       ("TripodRoller", {"bearing": 2, "n_needles": 12}), ("TripodRollerAnalytic", {}),
       ("TripodRoller", {"bearing": 0})]
_RUN = r'''
import json, sys
from fmpy import simulate_fmu
out = []
for fmu, sv in json.loads(sys.argv[1]):
    logs = []
    r = simulate_fmu(fmu, stop_time=0.003, output_interval=1e-4, start_values=sv,
                     debug_logging=True, logger=lambda c, n, s, cat, m: logs.append(m.decode()))
    out.append({"Fz": [float(v) for v in r["Fz"]], "log": logs})
print(json.dumps({"runs": out, "project": [m for m in sys.modules
                                           if m.split(".")[0] in ("tripod_model", "reduced_model")]}))
'''


def _bare_python(tmp_path):
    """A virtual environment with numpy, numba and FMPy (this one's site-packages on its path,
    unprocessed: the project's editable install is not in it)."""
    venv = tmp_path / "bare"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    site = next(venv.glob("lib/python3.*/site-packages"))
    ours = next(p for p in sys.path if p.endswith("site-packages") and Path(p).is_dir())
    (site / "deps.pth").write_text(ours + "\n")
    return venv / "bin" / "python"


def _run(python, jobs):
    p = subprocess.run([str(python), "-c", _RUN, json.dumps(jobs)], capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


def test_any_sequence_of_both_fmus_in_one_process(tmp_path):
    # in a Python without the project: the contact FMU (bearings 0, 1, 2), the analytic FMU and
    # the contact FMU again in one process (FMPy deletes each run's extraction folder while its
    # modules stay loaded), each result bit for bit the run in a process of its own
    py = _bare_python(tmp_path)
    jobs = [(str(ensure_fmu(n)), sv) for n, sv in SEQ]
    together = _run(py, jobs)
    assert together["project"] == []       # nothing imported under the project's own names
    for job, run in zip(jobs, together["runs"]):
        alone = _run(py, [job])["runs"][0]
        assert run["Fz"] == alone["Fz"], job
