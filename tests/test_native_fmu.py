"""The FMUs that need nothing on their host (fmu_src/native_fmu.py): the powertrain's model
(driveline/mounts.py), the analytic joint's (reduced_model/analytic_kernel.py) and the contact
joint's (fmu_src/tripod_model/lifecycle.py) compiled ahead of time under the native FMI layer
(fmu_src/native/fmi2_native.c), binaries for linux64 and win64 and nothing else in them.  Each
held to the same model's functions run as Python in process (harness/inprocess.py) under the
same FMPy master, bit for bit; run by a
plain C host with no Python reachable on Linux, and cross-compiled under wine64 from a folder
named 'jürgen x'."""
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from harness.fmus import builder, ensure_fmu
from harness.inprocess import InProcess
from tripod_model.genalpha import GA_NTOL

ROOT = Path(__file__).resolve().parents[1]
HOST = ROOT / "tests" / "c_host" / "fmu_run.c"
WINE = "/usr/lib/wine/wine64"
# wine's own errors kept (its fixme notes dropped): a wine run of a fresh machine's first test
# run once exited 1 with nothing on stdout or stderr under "-all", and could not be told apart
WINE_DEBUG = "err+all,fixme-all"
DT = 1e-4


# per FMU under test: the inputs a master moves (name: offset, amplitude, rate [1/s]; None:
# every input at (k + 1) 100 sin((k + 1) 7 t)), the Integer parameters set, the parameter a
# foreign state differs in
ANALYTIC_INPUTS = {"theta": (0.17, 0.05, 3.0), "omega": (62.8, 20.0, 5.0),
                   "F_press": (1000.0, 300.0, 7.0), "plunge_speed": (0.0, 0.01, 11.0)}
# the contact FMU: a master moving the angle, the speed, the torque and the plunge
CONTACT_INPUTS = {"theta": (0.17, 0.03, 3.0), "omega": (62.8, 10.0, 5.0),
                  "torque": (300.0, 100.0, 7.0), "plunge_speed": (0.0, 0.01, 11.0)}
# (and the run's length [s]: the needle-resolved row's run is short)
CASES = {"Powertrain": (None, {}, ("mass", 200.0), 0.5),
         "TripodRollerAnalytic": (ANALYTIC_INPUTS, {}, ("mu_groove", 0.07), 0.5),
         "TripodRollerAnalytic-three": (ANALYTIC_INPUTS, {"n_rollers": 3}, ("mu_groove", 0.07),
                                        0.5),
         "TripodRoller": (CONTACT_INPUTS, {}, ("mu_groove", 0.07), 0.5),
         "TripodRoller-lumped-three": (CONTACT_INPUTS, {"bearing": 1, "n_rollers": 3},
                                       ("mu_groove", 0.07), 0.5),
         "TripodRoller-resolved": (CONTACT_INPUTS, {"bearing": 2, "n_needles": 12},
                                   ("mu_groove", 0.07), 0.03),
         # (its rollers stepped at once on the machine's cores: native_units.c)
         "TripodRoller-resolved-three": (CONTACT_INPUTS, {"bearing": 2, "n_needles": 12,
                                                          "n_rollers": 3},
                                         ("mu_groove", 0.07), 0.01),
         "TripodRoller-free-spider": (CONTACT_INPUTS, {"spider": 1, "n_rollers": 3},
                                      ("mu_groove", 0.07), 0.5)}


# the win64 run (whole, or resumed from a Linux state at 0.25 s) against the linux64 one [of
# each output's scale]: 1e-9.  Where the two libms' last bits flip where the generalized-alpha
# Newton stops (the lumped row's friction around the loaded arc: two tanh laws), the step left
# untaken moves a friction by at most 3 GA_NTOL of mu f_n (test_transients.ULP_NEWTON):
# measured, resumed, 2.5e-9 (three rollers on the lumped row, Fy_2) and 3.3e-9 (the floating
# spider with the lumped row, F_housing_x); 7.4e-12 and 8.5e-10 before the arc
WINE_BOUND = {"TripodRoller-free-spider-lumped": 3 * GA_NTOL,
              "TripodRoller-lumped-three": 3 * GA_NTOL}
# runs in which a last bit grows: the needle-resolved row's impacts
LAST_BIT_GROWS = {"TripodRoller-resolved", "TripodRoller-resolved-three"}


@pytest.fixture(scope="module", params=sorted(CASES))
def fmus(request):
    name = request.param.split("-")[0]
    return ensure_fmu(name), None, request.param


# a state resumed in a fresh instance of another process (test_a_state_resumes_...): the joint
# at 300 N m (the master moving it by 100 N m), its parameters other than the defaults
RESUMED = {"TripodRoller-lumped-three": CASES["TripodRoller-lumped-three"],
           "TripodRoller-free-spider-lumped": (CONTACT_INPUTS, {"spider": 1, "n_rollers": 3,
                                                                "bearing": 1},
                                               ("mu_groove", 0.07), 0.5),
           "TripodRollerAnalytic-three": CASES["TripodRollerAnalytic-three"]}


def _case(fmus):
    return CASES[fmus[2]] if fmus[2] in CASES else RESUMED[fmus[2]]


def _model_id(fmu):
    return read_model_description(str(fmu)).coSimulation.modelIdentifier


def _signals(md, spec):
    """[(variable, offset, amplitude, rate)] of the inputs the master moves."""
    ins = _inputs(md)
    if spec is None:
        return [(v, 0.0, (i + 1) * 100.0, (i + 1) * 7.0) for i, v in enumerate(ins)]
    return [(v, *spec[v.name]) for v in ins if v.name in spec]


def _inputs(md):
    return [v for v in md.modelVariables if v.causality == "input"]


def _outputs(md):
    """The Real outputs (what the C host reads)."""
    return [v for v in md.modelVariables if v.causality == "output" and v.type == "Real"]


def test_the_fmu_holds_two_binaries_and_nothing_to_run_python(fmus):
    names = set(zipfile.ZipFile(fmus[0]).namelist())
    mid = _model_id(fmus[0])
    assert names == {"modelDescription.xml", f"binaries/linux64/{mid}.so",
                     f"binaries/win64/{mid}.dll"}
    assert validate_fmu(str(fmus[0])) == []


def test_fmpy_runs_it_as_its_functions_in_python_bit_for_bit(fmus):
    """A master moving the inputs every step (FMPy's input table, interpolated), 0.5 s: every
    output equal to the last bit to the same functions' run as Python in process (one source,
    mounts.py, analytic_kernel.py or lifecycle.py; the same libm)."""
    spec, ints, _, stop = _case(fmus)
    _bit_for_bit(fmus[0], spec, ints, stop)


# the contact FMU in coast (the torque negative: the rollers pressed on the groove's other
# flank) and through a reversal of the torque (drive to coast and back, 0.5 s)
@pytest.mark.parametrize("torque", [(-300.0, 100.0, 7.0), (0.0, 300.0, 7.0)],
                         ids=["coast", "reversing"])
@pytest.mark.parametrize("ints", [{}, {"bearing": 1, "n_rollers": 3},
                                  {"spider": 1, "n_rollers": 3}],
                         ids=["ideal", "lumped-three", "free-spider"])
def test_the_contact_fmu_in_coast_runs_as_its_functions_bit_for_bit(torque, ints):
    _bit_for_bit(ensure_fmu("TripodRoller"), dict(CONTACT_INPUTS, torque=torque), ints, 0.5)


def _bit_for_bit(fmu, spec, ints, stop):
    md = read_model_description(str(fmu))
    t = np.linspace(0.0, stop, 51)
    cols = [("time", t)] + [(v.name, o + a * np.sin(w * t)) for v, o, a, w in _signals(md, spec)]
    inp = np.array(list(zip(*[c for _, c in cols])), dtype=[(n, float) for n, _ in cols])
    kw = dict(stop_time=stop, output_interval=DT, input=inp, start_values=ints)
    a = simulate_fmu(str(fmu), **kw)
    b = simulate_fmu(str(fmu), fmu_instance=InProcess(fmu), fmi_type="CoSimulation", **kw)
    assert len(a) == len(b) == round(stop / DT) + 1
    for name in a.dtype.names:
        assert np.array_equal(a[name], b[name]), name
    moved = "acc_y" if "acc_y" in a.dtype.names else "Fz"    # (the run moved)
    assert np.ptp(a[moved]) > 1e-3


def _host(compiler, out, extra=()):
    subprocess.run([compiler, "-std=c99", "-O2", f"-I{builder()._fmi_headers()}", str(HOST),
                    "-o", str(out), "-lm", *extra], check=True, capture_output=True)
    return out


def _windows(path):
    """A Linux path as wine's Windows programs see it (drive Z: is the root)."""
    return "Z:" + str(path).replace("/", "\\")


def _run(cmd, fmus, outfile, env, wine=False, theta_ulps=0, steps=None):
    """The C host's run (cmd) of the case's master (steps: 0.8 of the case's length unless
    given); theta_ulps: theta's offset moved by that many ulps."""
    fmu = fmus[0]
    md = read_model_description(str(fmu))
    spec, ints, _, stop = _case(fmus)
    steps = steps or round(0.8 * stop / DT)
    eps = float(np.finfo(float).eps)
    ins = ",".join(f"{v.valueReference}:{o * (1 + theta_ulps * eps if v.name == 'theta' else 1)!r}"
                   f":{a!r}:{w!r}" for v, o, a, w in _signals(md, spec))
    outs = ",".join(str(v.valueReference) for v in _outputs(md))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    sets = [",".join(f"{vr[k]}={v}" for k, v in ints.items())] if ints else []
    p = subprocess.run(cmd + [md.guid, str(steps), repr(DT),
                              _windows(outfile) if wine else str(outfile), ins, outs, *sets],
                       capture_output=True, text=True, timeout=300, env=env)
    rows = np.fromfile(outfile, dtype="<f8") if Path(outfile).exists() else np.zeros(0)
    return p, rows.reshape(steps, -1) if rows.size else rows


# FMPy stepping an FMU as fmu_run.c does: the inputs offset + amplitude sin(rate t) at each
# step's start t = k dt (libm's sin, as the C host's), every Real output after each step
_FMPY_AS_THE_HOST = r'''
import json, math, sys
import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
fmu, req = sys.argv[1], json.loads(sys.argv[2])
md = read_model_description(fmu)
s = FMU2Slave(guid=md.guid, unzipDirectory=extract(fmu),
              modelIdentifier=md.coSimulation.modelIdentifier, instanceName="a")
s.instantiate()
s.setupExperiment(startTime=0.0)
s.enterInitializationMode()
for vr, v in req["ints"]:
    s.setInteger([vr], [v])
s.exitInitializationMode()
ins = req["ins"]
rows = []
for k in range(req["steps"]):
    t = k * req["dt"]
    s.setReal([i[0] for i in ins], [o + a * math.sin(w * t) for _, o, a, w in ins])
    s.doStep(t, req["dt"])
    rows.append(s.getReal(req["outs"]))
np.save(req["out"], np.array(rows))
'''


def test_a_c_host_with_no_python_runs_it(fmus, tmp_path):
    """No Python reachable (an environment of one variable, PATH, naming an empty folder: no
    python on it, no TRIPOD_THRUST_PYTHON, no virtualenv): the host steps it under a master
    moving its inputs, rolls a state back bit for bit through serialise and deserialise, and no
    libpython is in its process; every output after every step is FMPy's run of the same FMU
    and master, bit for bit."""
    import json
    d = tmp_path / "fmu"
    d.mkdir()
    zipfile.ZipFile(fmus[0]).extractall(d)
    host = _host(os.environ.get("CC") or "cc", tmp_path / "fmu_run", ["-ldl"])
    (tmp_path / "empty").mkdir()
    p, rows = _run([str(host), str(d / f"binaries/linux64/{_model_id(fmus[0])}.so")], fmus,
                   tmp_path / "out.bin", {"PATH": str(tmp_path / "empty")})
    assert p.returncode == 0, p.stdout + p.stderr
    assert "FAILED" not in p.stdout and "check rollback bit for bit ok" in p.stdout
    assert "python-in-process no" in p.stdout
    assert np.isfinite(rows).all() and np.abs(rows).max() > 0
    md = read_model_description(str(fmus[0]))
    spec, ints, _, _ = _case(fmus)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    req = {"ins": [(v.valueReference, o, a, w) for v, o, a, w in _signals(md, spec)],
           "outs": [v.valueReference for v in _outputs(md)], "dt": DT, "steps": len(rows),
           "ints": [(vr[k], v) for k, v in ints.items()], "out": str(tmp_path / "fmpy.npy")}
    q = subprocess.run([sys.executable, "-c", _FMPY_AS_THE_HOST, str(fmus[0]), json.dumps(req)],
                       capture_output=True, text=True, timeout=600)
    assert q.returncode == 0, q.stderr[-3000:]
    assert np.array_equal(np.load(tmp_path / "fmpy.npy"), rows)


def test_the_win64_binary_under_wine_runs_as_the_linux_one(fmus, tmp_path):
    """The DLL imports only KERNEL32 and msvcrt; the same host, cross-compiled, loads it from a
    folder named 'jürgen x' under wine64 (the path as a UTF-16 Windows path): checks pass, no
    Python in the process, the outputs within 1e-9 of each output's scale of the Linux run
    (the two C runtimes' sin, cos, pow and tanh may differ in the last bit; the mounts and the
    joint's groove contact are damped, so a last bit stays a last bit).  Where a last bit
    grows (LAST_BIT_GROWS: the needle-resolved row's impacts, benchmarks/needle_chaos.py) the
    first step agrees within 1e-9 and the run within ten times the Linux run's own spread when
    theta moves by 4 ulps (what another libm's last bit grows into)."""
    assert shutil.which("x86_64-w64-mingw32-gcc") and os.path.exists(WINE), \
        "mingw-w64 and wine64 missing: make test installs them (make cross-tools)"
    aot = builder().build_module("aot")
    d = tmp_path / "jürgen x"
    d.mkdir()
    zipfile.ZipFile(fmus[0]).extractall(d)
    mid = _model_id(fmus[0])
    dll = d / f"binaries/win64/{mid}.dll"
    assert sorted(aot.dll_imports(dll)) == ["KERNEL32.dll", "msvcrt.dll"]
    lin = _host(os.environ.get("CC") or "cc", tmp_path / "fmu_run", ["-ldl"])
    win = _host("x86_64-w64-mingw32-gcc", tmp_path / "fmu_run.exe",
                ["-static-libgcc", "-lpsapi", "-lshell32"])
    pl, rl = _run([str(lin), str(d / f"binaries/linux64/{mid}.so")], fmus,
                  tmp_path / "lin.bin", {"PATH": "/usr/bin:/bin"})
    env = dict(os.environ, WINEPREFIX=str(ROOT / "build" / "wine-prefix"), WINEDEBUG=WINE_DEBUG)
    pw, rw = _run([WINE, str(win), _windows(dll)], fmus, tmp_path / "win.bin", env, wine=True)
    assert pl.returncode == 0 and pw.returncode == 0, pw.stdout + pw.stderr
    assert "FAILED" not in pw.stdout and "check rollback bit for bit ok" in pw.stdout
    assert "python-in-process no" in pw.stdout
    scale = np.abs(rl).max(axis=0)
    if fmus[2] not in LAST_BIT_GROWS:
        assert (np.abs(rw - rl).max(axis=0) <= WINE_BOUND.get(fmus[2], 1e-9) * scale).all()
        return
    assert (np.abs(rw[0] - rl[0]) <= 1e-9 * scale).all()
    _, rp = _run([str(lin), str(d / f"binaries/linux64/{mid}.so")], fmus, tmp_path / "p.bin",
                 {"PATH": "/usr/bin:/bin"}, theta_ulps=4)
    spread = np.abs(rp - rl).max(axis=0)
    assert (np.abs(rw - rl).max(axis=0) <= 10 * spread + 1e-9 * scale).all()


@pytest.mark.parametrize("case", sorted(RESUMED))
def test_a_state_resumes_in_a_fresh_instance_of_another_process(case, tmp_path):
    """As fmusim restores a state: serialised halfway through one process's run, set in
    another process right after fmi2Instantiate (no start value: its parameters, three rollers,
    a bearing, a floating spider, come with the state) and stepped on: the same outputs bit
    for bit; the win64 binary under wine resuming the linux64 state within the wine test's
    bound of each output's scale."""
    assert shutil.which("x86_64-w64-mingw32-gcc") and os.path.exists(WINE), \
        "mingw-w64 and wine64 missing: make test installs them (make cross-tools)"
    fm = (ensure_fmu(case.split("-")[0]), None, case)
    d = tmp_path / "fmu"
    d.mkdir()
    zipfile.ZipFile(fm[0]).extractall(d)
    mid = _model_id(fm[0])
    so, dll = d / f"binaries/linux64/{mid}.so", d / f"binaries/win64/{mid}.dll"
    lin = _host(os.environ.get("CC") or "cc", tmp_path / "fmu_run", ["-ldl"])
    win = _host("x86_64-w64-mingw32-gcc", tmp_path / "fmu_run.exe",
                ["-static-libgcc", "-lpsapi", "-lshell32"])
    state = tmp_path / "state.bin"
    env = {"PATH": "/usr/bin:/bin"}
    p, full = _run([str(lin), str(so)], fm, tmp_path / "full.bin",
                   dict(env, FMU_RUN_STATE_OUT=str(state)))
    assert p.returncode == 0 and state.stat().st_size > 0, p.stdout + p.stderr
    q, resumed = _run([str(lin), str(so)], fm, tmp_path / "resumed.bin",
                      dict(env, FMU_RUN_STATE_IN=str(state)))
    assert q.returncode == 0 and "FAILED" not in q.stdout, q.stdout + q.stderr
    half = len(full) // 2
    assert np.array_equal(resumed[half:], full[half:])
    assert np.ptp(full[half:], axis=0).max() > 0          # (the run moved)
    wenv = dict(os.environ, WINEPREFIX=str(ROOT / "build" / "wine-prefix"), WINEDEBUG=WINE_DEBUG,
                FMU_RUN_STATE_IN=_windows(state))
    w, rw = _run([WINE, str(win), _windows(dll)], fm, tmp_path / "win.bin", wenv, wine=True)
    assert w.returncode == 0 and "FAILED" not in w.stdout, w.stdout + w.stderr
    scale = np.abs(full[half:]).max(axis=0)
    bound = WINE_BOUND.get(case, 1e-9)
    off = np.abs(rw[half:] - full[half:])
    assert (off[0] <= 1e-9 * scale).all()       # the state itself carried over exactly
    worst = off.max(axis=0) / np.where(scale > 0, scale, 1.0)
    assert (worst <= bound).all(), {i: float(v) for i, v in enumerate(worst) if v > bound}


@pytest.mark.skipif(shutil.which("valgrind") is None, reason="valgrind not installed "
                    "(make native-check installs it)")
def test_the_linux_binary_is_valgrind_clean(fmus, tmp_path):
    """The host's whole run (instantiate, steps, state get, serialise, deserialise, set, free)
    under memcheck: no invalid access, nothing lost."""
    d = tmp_path / "fmu"
    d.mkdir()
    zipfile.ZipFile(fmus[0]).extractall(d)
    host = _host(os.environ.get("CC") or "cc", tmp_path / "fmu_run", ["-ldl"])
    # (the contact FMU: 200 steps, each path of its step taken; three needle-resolved rollers:
    # 40, each step their threads started and joined; the analytic FMU: 400, its table at the
    # start, then the march under the master from the first step on; memcheck runs 50x slower)
    p, _ = _run(["valgrind", "--leak-check=full", "--errors-for-leak-kinds=definite",
                 "--error-exitcode=9", "-q", str(host),
                 str(d / f"binaries/linux64/{_model_id(fmus[0])}.so")],
                fmus, tmp_path / "out.bin", {"PATH": "/usr/bin:/bin"},
                steps=40 if fmus[2] == "TripodRoller-resolved-three"
                else 200 if fmus[2].startswith("TripodRoller-") or fmus[2] == "TripodRoller"
                else 400 if fmus[2].startswith("TripodRollerAnalytic") else None)
    assert p.returncode == 0, p.stderr[-3000:]


_ABUSE = r'''
import json, math, random, struct, sys, zlib
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
fmu, ints, (other, value) = sys.argv[1], json.loads(sys.argv[2]), json.loads(sys.argv[3])
md = read_model_description(fmu)
d = extract(fmu)
vr = {v.name: v.valueReference for v in md.modelVariables}
OUT = [v.valueReference for v in md.modelVariables
       if v.causality == "output" and v.type == "Real"]
HEADER = 8 + 4 * 4 + 6 * 4 + 8      # fmi2_native.c: magic, 4 words, 6 sizes, time


def make(name, foreign=False):
    s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=name)
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    for k, v in ints.items():
        s.setInteger([vr[k]], [v])
    if foreign:      # a state of other parameters
        s.setReal([vr[other]], [value])
    s.exitInitializationMode()
    for i in range(50):
        s.doStep(i * 1e-4, 1e-4)
    return s


def seal(body):
    return body + struct.pack("<I", zlib.crc32(body))


def outcome(s, blob):
    try:
        s.setFMUstate(s.deSerializeFMUstate(blob))
    except FMICallException:
        return "refused"
    try:
        for i in range(20):
            s.doStep(0.1 + i * 1e-4, 1e-4)
    except FMICallException:
        return "refused-later"
    return "finite" if all(map(math.isfinite, s.getReal(OUT))) else "non-finite"


src = make("src")
good = bytes(src.serializeFMUstate(src.getFMUstate()))
n = (len(good) - HEADER - 4) // 8
rng = random.Random(3)
cases = {"good": good, "empty": b"", "other-parameters": bytes(
    make("m", True).serializeFMUstate(make("m2", True).getFMUstate()))}
for k in range(0, len(good), 7):
    cases[f"truncated-{k}"] = good[:k]
cases["longer"] = good + b"\0" * 8
for k in range(200):
    b = bytearray(good)
    i = rng.randrange(len(b))
    b[i] ^= 1 << rng.randrange(8)
    cases[f"flip-{i}-{k}"] = bytes(b)
for k in range(300):     # values changed, checksum made valid: what reaches the checks
    b = bytearray(good[:-4])
    i = rng.randrange(n)
    x = rng.choice([math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, 0.5, 3.0, -3.0, 1e6])
    struct.pack_into("<d", b, HEADER + 8 * i, x)
    cases[f"value-{i}-{k}-{'finite' if math.isfinite(x) else 'nonfinite'}"] = seal(bytes(b))
for name, at, word in (("phase-99", 12, 99), ("version-2", 8, 2), ("size-huge", 24, 1 << 30),
                       ("guid", 20, 0)):
    b = bytearray(good[:-4])
    struct.pack_into("<I", b, at, word)
    cases[name] = seal(bytes(b))
target = make("target")
res = {}
for name, blob in cases.items():
    res[name] = outcome(target, blob)
    if res[name] != "refused":
        target.freeInstance()
        target = make("target")
res_good_after = outcome(target, good)
print(json.dumps({"cases": res, "good_after": res_good_after}))
'''


def test_states_a_host_hands_it_are_checked(fmus, tmp_path):
    """Bytes into C: every truncation (a seventh of them), 200 bit flips, 300 values changed
    with the checksum made valid (NaN, inf, 1e308, subnormal, plausible-looking), a wrong
    version, phase, size or GUID: each is refused at deserialise or set, or steps 20 times to
    finite outputs or is refused at a step; none crashes the host; the good state still
    restores after them all.  A state of other parameters (valid ones) is taken with them and
    steps to finite outputs."""
    import json
    _, ints, other, _ = _case(fmus)
    p = subprocess.run([sys.executable, "-c", _ABUSE, str(fmus[0]), json.dumps(ints),
                        json.dumps(other)], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    cases = r["cases"]
    assert cases.pop("good") == "finite" and r["good_after"] == "finite"
    wrong = {k: v for k, v in cases.items() if v not in ("refused", "finite", "refused-later")}
    assert not wrong, wrong
    for k in ("empty", "longer", "phase-99", "version-2", "size-huge", "guid"):
        assert cases[k] == "refused", k
    assert cases["other-parameters"] == "finite"
    assert all(v == "refused" for k, v in cases.items() if k.startswith(("truncated", "flip")))
    values = {k: v for k, v in cases.items() if k.startswith("value-")}
    assert len(values) == 300
    # a non-finite value anywhere in a state is refused when it is set
    assert all(v == "refused" for k, v in values.items() if k.endswith("nonfinite"))


# a contact FMU's state after 50 steps with one of its values set (the checksum made valid),
# set into the instance it came from ("same") or into a fresh one ("fresh"), then stepped
_CRAFTED = r'''
import json, struct, sys, zlib
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
fmu, at, value, where = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
md = read_model_description(fmu)
d = extract(fmu)
def instance(name):
    s = FMU2Slave(guid=md.guid, unzipDirectory=d,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
    s.instantiate(loggingOn=True)
    return s
s = instance("a")
s.setupExperiment(startTime=0.0)
s.enterInitializationMode()
s.exitInitializationMode()
for i in range(50):
    s.doStep(i * 1e-4, 1e-4)
b = bytearray(bytes(s.serializeFMUstate(s.getFMUstate()))[:-4])
struct.pack_into("<d", b, 8 + 4 * 4 + 6 * 4 + 8 + 8 * at, value)
b += struct.pack("<I", zlib.crc32(bytes(b)))
if where == "fresh":
    s = instance("fresh")
try:
    s.setFMUstate(s.deSerializeFMUstate(bytes(b)))
    for i in range(20):
        s.doStep(0.1 + i * 1e-4, 1e-4)
    print("OUTCOME stepped")
except FMICallException:
    print("OUTCOME refused")
'''


@pytest.mark.parametrize("slide,outcome,said", [
    (0.5, "refused", "fmi2SetFMUstate: corrupt state: a roller's slide u is beyond half the "
                     "needle length"),
    (3e-3, "refused", " s: roller 1: the adaptive substeps stopped at")])
def test_a_crafted_contact_state_is_refused_or_meets_the_budget(slide, outcome, said):
    """The roller's slide u in a serialised state (checksum made valid): at 0.5 m (the joint is
    0.022 m) refused when set, naming the bound; at 3 mm (inside the 6 mm bound, runs reach
    0.1 mm) taken, and one of its next two steps refused once the adaptive substeps have
    tried their budget, with one line saying so (budget.py; measured: the first, at 0.1 s;
    with Newton given 30 iterations, tried, the second)."""
    from tripod_model import layout as K, lifecycle as LC
    at = LC.T_LEN + LC.IN_LEN + LC.X_Y + K.Y_U   # (the state's arrays: P, IN, X, ...)
    p = subprocess.run([sys.executable, "-c", _CRAFTED, str(ensure_fmu("TripodRoller")),
                        str(at), repr(slide), "same"], capture_output=True, text=True,
                       timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    assert f"OUTCOME {outcome}" in p.stdout and said in p.stdout, p.stdout[-3000:]
    if slide == 3e-3:
        assert "the substeps tried reached their budget" in p.stdout
        assert "step refused at t = 0.1 s" in p.stdout or "step refused at t = 0.1001 s" in p.stdout


@pytest.mark.parametrize("name,value,said", [
    ("r_bore", 0.02, "fmi2SetFMUstate: invalid parameter in the state: "),
    ("n_rollers", 2.0, "fmi2SetFMUstate: invalid parameter in the state: "),
    ("bearing", 0.5, "fmi2SetFMUstate: invalid parameter in the state: bearing = 0.5 is not an "
                     "integer"),
    ("mu_groove", 7.0, "fmi2SetFMUstate: invalid parameter in the state: mu_groove = 7.0 is "
                       "outside the allowed range [0, 1]")])
def test_a_states_parameters_meet_the_checks_of_initialisation(name, value, said):
    """A state's parameters set into a fresh instance pass what fmi2SetInteger, fmi2SetReal and
    initialisation check: a bore wider than the roller and two rollers (each in its range, the
    relation refused, the model's own message), a Real where an Integer belongs, a value out of
    range: refused with one line.  (Valid other parameters come with a state that was taken
    with them: test_a_state_resumes_in_a_fresh_instance_of_another_process.)"""
    from tripod_model import lifecycle as LC
    at = LC.PARAM_NAMES.index(name)         # (the state's arrays: P first)
    p = subprocess.run([sys.executable, "-c", _CRAFTED, str(ensure_fmu("TripodRoller")),
                        str(at), repr(value), "fresh"], capture_output=True, text=True,
                       timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    assert "OUTCOME refused" in p.stdout and said in p.stdout, p.stdout[-3000:]
    line = next(x for x in p.stdout.splitlines() if said in x)
    assert name in line
