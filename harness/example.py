"""The driveline example: a vehicle launch, the joint FMU beside the powertrain FMU in one
standard system file (SSP), run unchanged by FMPy's ``simulate_ssp`` and by libcosim.

``write_ssp`` writes the system (both FMUs inside, every connection and start value in its
SystemStructure.ssd); ``run_system`` runs it with either tool in a fresh process;
``launch_report`` reads a launch the way a driveline engineer does (peak lateral acceleration,
order map against wheel speed, the joint's thrust orders).  docs/driveline-example.md.
"""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from driveline import powertrain as pt
from reduced_model.scene import check_param, parse_param

JOINTS = {"contact": "TripodRoller", "analytic": "TripodRollerAnalytic"}
# the joint models paired as the cross-check pairs them (scene.analytic_counterpart): the
# contact FMU's default, the ideal bearing, and the analytic FMU without its needle row.  With
# the row (and the contact FMU's lumped row) the launch's peak is 37 % higher on the paper's
# joint (docs/driveline-example.md)
JOINT_VALUES = {"contact": {}, "analytic": {"needle_row": False}}
TO_JOINT = ("theta", "plunge_speed", "omega", "torque")      # powertrain outputs -> joint inputs
TO_POWERTRAIN = tuple(p.name for p in pt.INPUTS)             # joint outputs -> powertrain inputs
RECORD = {"powertrain": ("acc_y", "acc_x", "acc_z", "disp_y", "roll", "plunge"),
          "joint": ("T_housing", "F_roller")}
STOP, STEP = 2.5, 1e-4          # s: the launch through the shudder band; communication step
TOOLS = ("fmpy", "libcosim")


def joint_start(p: dict, s: float = 0.022) -> dict:
    """The joint's start values, consistent with the powertrain at t = 0: three rollers, the
    rest angle, standstill, creep torque.  F_press carries the creep load per roller because
    FMPy's simulate_ssp hands every input 0 in the first step (the load is then F_press)."""
    return {"n_rollers": 3, "theta": p["theta0"], "omega": 0.0, "torque": p["torque_creep"],
            "F_press": p["torque_creep"] / (3.0 * s), "plunge_speed": 0.0}


def _value(v) -> str:
    kind = "Boolean" if isinstance(v, bool) else "Integer" if isinstance(v, int) else "Real"
    text = ("true" if v else "false") if kind == "Boolean" else repr(v)
    return f'<ssv:{kind} value="{text}"/>'


def _component(name, fmu, inputs, outputs, values) -> str:
    conns = "".join(f'\n        <ssd:Connector name="{n}" kind="{k}"><ssc:Real/></ssd:Connector>'
                    for k, names in (("input", inputs), ("output", outputs)) for n in names)
    params = "".join(f'\n              <ssv:Parameter name={quoteattr(n)}>{_value(v)}</ssv:Parameter>'
                     for n, v in values.items())
    return f'''
    <ssd:Component name="{name}" type="application/x-fmu-sharedlibrary" source="resources/{fmu}.fmu">
      <ssd:Connectors>{conns}
      </ssd:Connectors>
      <ssd:ParameterBindings>
        <ssd:ParameterBinding>
          <ssd:ParameterValues>
            <ssv:ParameterSet version="1.0" name="{name}">
              <ssv:Parameters>{params}
              </ssv:Parameters>
            </ssv:ParameterSet>
          </ssd:ParameterValues>
        </ssd:ParameterBinding>
      </ssd:ParameterBindings>
    </ssd:Component>'''


def system_xml(joint="contact", powertrain: dict | None = None, joint_values: dict | None = None,
               stop=STOP) -> str:
    """SystemStructure.ssd of the launch: the powertrain and the joint connected both ways,
    each component's start values in its parameter bindings (SSP 1.0)."""
    p = pt.defaults() | {k: v for k, v in (powertrain or {}).items()}
    for name, v in p.items():
        check_param(pt.BY_NAME[name], v)
    pvals = {q.name: p[q.name] for q in pt.PARAMS}
    jvals = joint_start(p) | JOINT_VALUES[joint] | (joint_values or {})
    conns = "".join(f'\n    <ssd:Connection startElement="powertrain" startConnector="{n}" '
                    f'endElement="joint" endConnector="{n}"/>' for n in TO_JOINT)
    conns += "".join(f'\n    <ssd:Connection startElement="joint" startConnector="{n}" '
                     f'endElement="powertrain" endConnector="{n}"/>' for n in TO_POWERTRAIN)
    comps = _component("powertrain", "Powertrain", TO_POWERTRAIN,
                       TO_JOINT + RECORD["powertrain"], pvals)
    comps += _component("joint", JOINTS[joint], TO_JOINT, TO_POWERTRAIN + RECORD["joint"], jvals)
    return f'''<?xml version="1.0" encoding="UTF-8"?>
<ssd:SystemStructureDescription version="1.0" name="launch"
    xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon"
    xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription"
    xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues">
  <ssd:System name="launch" description="a vehicle launch: a powertrain on its mounts and the {joint} tripod joint of its left half-shaft">
  <ssd:Elements>{comps}
  </ssd:Elements>
  <ssd:Connections>{conns}
  </ssd:Connections>
  </ssd:System>
  <ssd:DefaultExperiment startTime="0" stopTime="{stop!r}"/>
</ssd:SystemStructureDescription>
'''


def write_ssp(dest, joint="contact", powertrain: dict | None = None,
              joint_values: dict | None = None, stop=STOP) -> Path:
    """The launch as an SSP archive at ``dest``: SystemStructure.ssd and both FMUs (built
    first when missing or stale) under resources/."""
    from .fmus import ensure_fmu
    dest = Path(dest)
    dest.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(dest, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("SystemStructure.ssd", system_xml(joint, powertrain, joint_values, stop))
        for name in ("Powertrain", JOINTS[joint]):
            z.write(ensure_fmu(name), f"resources/{name}.fmu")
    return dest


# Each tool runs in a fresh process (an FMU run in the building process would use the source
# tree).  Both record every connector after each step; the results' time is the step's end.
_FMPY = r'''
import json, sys
import numpy as np
from fmpy.ssp.simulation import simulate_ssp
from fmpy.ssp.ssd import Parameter, ParameterSet, find_components, read_ssd
req = json.loads(sys.stdin.read())
# simulate_ssp applies the parameter set it is given, not the SSD's bindings: hand it those
ps = ParameterSet(name="bindings")
for c in find_components(read_ssd(req["ssp"]).system):
    for b in c.parameterBindings:
        for s in b.parameterValues:
            for p in s.parameters:
                # (FMPy sets a Boolean from the literal, and "false" != 0.0: convert it here)
                v = p.value.strip().lower() == "true" if p.type == "Boolean" else p.value
                ps.parameters.append(Parameter(name=c.name + "." + p.name, type=p.type, value=v))
r = simulate_ssp(req["ssp"], stop_time=req["stop"], step_size=req["step"], parameter_set=ps)
out = {n: np.asarray(r[n], float) for n in r.dtype.names}
out["time"] = out["time"] + req["step"]      # simulate_ssp labels a step's results by its start
np.savez(req["out"], **out)
'''

_LIBCOSIM = r'''
import json, sys
import numpy as np
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
log_output_level(CosimLogLevel.ERROR)
from libcosimpy.CosimEnums import CosimVariableType
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
req = json.loads(sys.stdin.read())
ns = int(round(req["step"] * 1e9))
n = int(round(req["stop"] / req["step"]))
ex = CosimExecution.from_ssp_file(req["ssp"], step_size=ns)
obs = CosimObserver.create_time_series(buffer_size=n + 10)
ex.add_observer(observer=obs)
refs = {}
for info in ex.slave_infos():
    comp = info.name.decode()
    for v in ex.slave_variables(slave_index=info.index):
        if v.type == CosimVariableType.REAL.value and comp + "." + v.name.decode() in req["names"]:
            refs[comp + "." + v.name.decode()] = (info.index, v.reference)
            obs.start_time_series(info.index, value_reference=v.reference,
                                  variable_type=CosimVariableType.REAL)
if not ex.simulate_until(target_time=n * ns):
    sys.exit("libcosim: simulate_until returned false")
out = {}
for name, (i, ref) in refs.items():
    t, steps, vals = obs.time_series_real_samples(slave_index=i, value_reference=ref,
                                                  from_step=1, sample_count=n)
    if len(vals) != n:
        sys.exit(f"libcosim kept {len(vals)} of the {n} samples of {name}")
    out[name] = np.asarray(vals, float)
    out["time"] = np.asarray(t, float) * 1e-9
np.savez(req["out"], **out)
'''


def signal_names() -> list[str]:
    """Every recorded signal, as <component>.<variable>."""
    names = [f"powertrain.{n}" for n in TO_JOINT + RECORD["powertrain"] + TO_POWERTRAIN]
    return names + [f"joint.{n}" for n in TO_POWERTRAIN + RECORD["joint"] + TO_JOINT]


def run_system(ssp, tool="fmpy", stop=STOP, step=STEP, timeout=900.0,
               progress: str | None = None) -> dict:
    """Run the SSP ``ssp`` with ``tool`` ('fmpy' or 'libcosim') in a new process, fixed
    communication step ``step`` [s] up to ``stop`` [s]; returns {"time": step ends [s],
    "<component>.<variable>": values after each step}.  ``progress``: a label shown with the
    wall time on a terminal while a run takes longer than two seconds."""
    from .runs import FmuRunError, Ticker
    if tool not in TOOLS:
        raise ValueError(f"tool = {tool!r}: allowed {', '.join(TOOLS)}")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.npz")
        req = {"ssp": os.path.abspath(str(ssp)), "stop": stop, "step": step, "out": out,
               "names": signal_names()}
        with Ticker(progress):
            p = subprocess.run([sys.executable, "-c", _FMPY if tool == "fmpy" else _LIBCOSIM],
                               input=json.dumps(req), capture_output=True, text=True,
                               timeout=timeout, cwd=tmp)
        if p.returncode != 0 or not os.path.exists(out):
            raise FmuRunError(f"{tool} run of {Path(ssp).name} failed (exit {p.returncode}): "
                              f"{p.stderr.strip()[-1500:]}")
        r = dict(np.load(out))
    n = int(round(stop / step))
    return {k: v[:n] for k, v in r.items()}     # simulate_ssp may take one step more (float t)


def order_map(t, angle, y, orders=range(1, 7), hop=0.125):
    """Orders of y per revolution of the shaft ``angle`` [rad], windows of one revolution every
    ``hop`` revolutions: (mean wheel speed [Hz] per window, amplitudes [unit of y], orders x
    windows).  y is resampled uniformly in angle; a window's speed is its angle over its time."""
    from reduced_model.orders import order_spectrum
    orders = tuple(orders)
    speeds, amps = [], []
    a = 0.0
    while a + 2 * math.pi <= angle[-1]:
        xs = a + 2 * math.pi * np.arange(720) / 720
        amp, _ = order_spectrum(np.interp(xs, angle, y), 1, orders)
        ta, tb = np.interp([a, a + 2 * math.pi], angle, t)
        speeds.append(1.0 / (tb - ta))
        amps.append(amp)
        a += 2 * math.pi * hop
    return np.array(speeds), np.array(amps).T.reshape(len(orders), -1)


def peak(r: dict) -> dict:
    """The peak lateral acceleration of the powertrain [m/s2], when [s] and at which wheel
    speed [Hz]."""
    a = r["powertrain.acc_y"]
    i = int(np.argmax(np.abs(a)))
    return {"peak_acc_y": float(abs(a[i])), "time": float(r["time"][i]),
            "wheel_hz": float(r["powertrain.omega"][i] / (2 * math.pi))}



def powertrain_overrides(items) -> dict:
    """``NAME=VALUE`` strings (SI units) as powertrain parameters, each checked against its
    range in the table (ValueError naming it otherwise)."""
    out = {}
    for item in items:
        name, sep, text = item.partition("=")
        p = pt.BY_NAME.get(name.strip())
        if not sep or p is None or p.causality == "input":
            raise ValueError(f"--set {item}: expected NAME=VALUE with NAME a powertrain "
                             f"parameter: {', '.join(q.name for q in pt.PARAMS)}")
        value = parse_param(p, text)
        check_param(p, value)
        out[p.name] = value
    return out


def launch(out, stop=STOP, step=STEP, joints=tuple(JOINTS), tools=TOOLS, powertrain=None,
           check_step=True, plots=True, joint=None) -> dict:
    """The example: the launch with each joint model through each tool (and the contact joint
    at half the step, the convergence check), its table and, with ``plots``, its figures in
    ``out``; ``joint``: a joint's values (reduced_model.joint.load_joint), else the paper's.
    Returns {"rows": [...], "checks": {...}, "runs": {(joint, tool): result}}."""
    from reduced_model.joint import for_model
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    runs = {}
    n_runs = len(joints) * len(tools) + bool(check_step)

    def label(j, tool, s):
        return (f"example: run {len(runs) + 1} of {n_runs}, the {j} joint in {tool} "
                f"({stop:g} s simulated at a {s:g} s step)")
    for name in joints:
        values = None
        if joint is not None:   # the joint's values, and the creep load at its pitch circle
            p = pt.defaults() | (powertrain or {})
            values = for_model(joint, name) | {
                "F_press": p["torque_creep"] / (3.0 * joint["s"])}
        ssp = write_ssp(out / f"launch_{name}.ssp", name, powertrain, values, stop=stop)
        for tool in tools:
            runs[name, tool] = run_system(ssp, tool, stop, step, progress=label(name, tool, step))
    rows = [{"joint": j, "tool": t, **peak(r)} for (j, t), r in runs.items()]
    checks = {}
    first = tools[0]
    if len(tools) == 2:
        for j in joints:
            a, b = runs[j, tools[0]], runs[j, tools[1]]
            checks[f"{j}: {tools[0]} vs {tools[1]}, peak"] = \
                abs(peak(a)["peak_acc_y"] / peak(b)["peak_acc_y"] - 1)
            late = a["time"] > 0.5
            checks[f"{j}: {tools[0]} vs {tools[1]}, acc_y after 0.5 s (of its peak)"] = float(
                np.max(np.abs(a["powertrain.acc_y"][late] - b["powertrain.acc_y"][late]))
                / np.max(np.abs(a["powertrain.acc_y"])))
    if len(joints) == 2:
        pa, pb = peak(runs["analytic", first]), peak(runs["contact", first])
        checks["analytic vs contact, peak"] = abs(pa["peak_acc_y"] / pb["peak_acc_y"] - 1)
    if check_step:
        j = joints[0]
        half = run_system(out / f"launch_{j}.ssp", first, stop, step / 2,
                          progress=label(j, first, step / 2))
        runs[j, first + " (half step)"] = half
        rows.append({"joint": j, "tool": first + f" (step {step / 2:g} s)", **peak(half)})
        checks[f"{j}: step {step:g} s -> {step / 2:g} s, peak"] = \
            abs(peak(half)["peak_acc_y"] / peak(runs[j, first])["peak_acc_y"] - 1)
    files = [f"launch_{j}.ssp" for j in joints] + ["launch.json", "launch.md"]
    if plots:
        files += [f.name for f in launch_plots(runs, out, first)]
    result = {"stop": stop, "step": step, "rows": rows, "checks": checks, "files": files}
    (out / "launch.json").write_text(json.dumps(result, indent=1) + "\n")
    (out / "launch.md").write_text(markdown_table(result))
    return result | {"runs": runs}


def markdown_table(result: dict) -> str:
    """The example's table in Markdown (docs/driveline-example.md's measured block)."""
    lines = ["| joint | tool | peak lateral acceleration [m/s2] | at wheel speed [Hz] | at t [s] |",
             "|---|---|---|---|---|"]
    for r in result["rows"]:
        lines.append(f"| {r['joint']} | {r['tool']} | {r['peak_acc_y']:.4f} | "
                     f"{r['wheel_hz']:.3f} | {r['time']:.4f} |")
    lines += ["", f"Launch 0-{result['stop']:g} s, communication step {result['step']:g} s. "
              "Relative differences:", ""]
    lines += [f"- {k}: {v:.2e}" for k, v in result["checks"].items()]
    return "\n".join(lines) + "\n"


def format_table(result: dict) -> str:
    """The example's table: the peak lateral acceleration per joint model and tool, and the
    checks (relative differences)."""
    lines = [f"launch {result['stop']:g} s, communication step {result['step']:g} s",
             f"{'joint':9s} {'tool':28s} {'peak acc_y [m/s2]':>18s} {'at wheel [Hz]':>14s} "
             f"{'at t [s]':>9s}"]
    for r in result["rows"]:
        lines.append(f"{r['joint']:9s} {r['tool']:28s} {r['peak_acc_y']:18.4f} "
                     f"{r['wheel_hz']:14.3f} {r['time']:9.4f}")
    lines.append("differences (relative):")
    for k, v in result["checks"].items():
        lines.append(f"  {k}: {v:.2e}")
    return "\n".join(lines)


def launch_plots(runs: dict, out, tool="fmpy") -> list[Path]:
    """launch.png (lateral acceleration and wheel speed against time), order_map.png (orders
    of the lateral acceleration against wheel speed), thrust_orders.png (the joint's thrust
    orders along the launch, contact against analytic)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    out = Path(out)
    joints = [j for j in JOINTS if (j, tool) in runs]
    files = []
    fig, (ax, dx, bx) = plt.subplots(3, 1, figsize=(8, 7), sharex=True,
                                     gridspec_kw={"height_ratios": [3, 1, 1]})
    for j in joints:
        r = runs[j, tool]
        ax.plot(r["time"], r["powertrain.acc_y"], lw=0.6, label=f"{j} joint")
    ax.set_ylabel("powertrain lateral\nacceleration [m/s2]")
    ax.legend()
    ax.grid(alpha=0.3)
    if len(joints) == 2:
        c, a = runs["contact", tool], runs["analytic", tool]
        dx.plot(c["time"], a["powertrain.acc_y"] - c["powertrain.acc_y"], "k", lw=0.6)
        dx.set_ylabel("analytic - contact\n[m/s2]")
    dx.grid(alpha=0.3)
    r = runs[joints[0], tool]
    bx.plot(r["time"], r["powertrain.omega"] / (2 * math.pi), "k", lw=1)
    bx.set_ylabel("wheel speed [Hz]")
    bx.set_xlabel("time [s]")
    bx.grid(alpha=0.3)
    ax.set_title(f"launch ({tool}): the joint's thrust shakes the powertrain on its mounts")
    files.append(_save(fig, out / "launch.png"))

    r = runs[joints[0], tool]
    speeds, amps = order_map(r["time"], r["joint.whirl_angle"], r["powertrain.acc_y"])
    if len(speeds) < 2:      # a run too short for order tracking: the time plot only
        return files
    fig, ax = plt.subplots(figsize=(8, 4))
    mesh = ax.pcolormesh(speeds, np.arange(1, amps.shape[0] + 1), amps, shading="nearest")
    fig.colorbar(mesh, ax=ax, label="amplitude [m/s2]")
    ax.set_xlabel("wheel speed [Hz]")
    ax.set_ylabel("order of the wheel rotation")
    ax.set_title(f"powertrain lateral acceleration, order map ({joints[0]} joint, one "
                 "revolution every 1/8)")
    files.append(_save(fig, out / "order_map.png"))

    fig, (ax, bx) = plt.subplots(2, 1, figsize=(8, 6), sharex=True,
                                 gridspec_kw={"height_ratios": [3, 1]})
    orders = {}
    for j, style in zip(joints, ("-", "--")):
        r = runs[j, tool]
        f, amps = order_map(r["time"], r["joint.whirl_angle"], r["joint.Fz_joint"], (1, 3))
        orders[j] = amps
        for k, c in ((1, "C0"), (0, "C1")):
            ax.plot(f, amps[k], c + style, label=f"order {2 * k + 1}, {j} joint")
    ax.set_ylabel("Fz_joint order amplitude [N]")
    ax.legend()
    ax.grid(alpha=0.3)
    ax.set_title("the joint's thrust along the launch (one revolution every 1/8)")
    if len(joints) == 2:
        bx.plot(f, 100 * (orders["analytic"][1] / orders["contact"][1] - 1), "k-")
        bx.set_ylabel("order 3, analytic\nvs contact [%]")
    bx.set_xlabel("wheel speed [Hz] (a revolution's mean)")
    bx.grid(alpha=0.3)
    files.append(_save(fig, out / "thrust_orders.png"))
    return files


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    import matplotlib.pyplot as plt
    plt.close(fig)
    return path
