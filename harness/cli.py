"""Command line of tripod-thrust: argument parsing only; the work is in library functions."""
from __future__ import annotations

import argparse
import json
import math
import sys

from harness.runs import FmuRunError
from reduced_model import scene as scene_mod


class CliError(Exception):
    """A user error: printed as one line, exit code 2."""


def version() -> str:
    """The installed package's version (pyproject.toml's when run from a source tree)."""
    from importlib import metadata
    try:
        return metadata.version("tripod-thrust")
    except metadata.PackageNotFoundError:
        import re
        from pathlib import Path
        text = (Path(__file__).resolve().parents[1] / "pyproject.toml").read_text()
        return re.search(r'^version = "([^"]+)"', text, re.M).group(1)


class _Help(argparse.RawDescriptionHelpFormatter):
    """Every option's help ends with its default (unless it says it, or has none)."""

    def _get_help_string(self, action):
        h = action.help or ""
        d = action.default
        if ("default" in h or d in (None, False, [], argparse.SUPPRESS)
                or not action.option_strings):
            return h
        return f"{h} (default {d})"


def _param_epilog(model: str, params=None) -> str:
    """The parameters --set takes, from the parameter table (``params``, else the ``model``'s
    of the joint's table): name, unit, default, range."""
    rows = [f"parameters for --set NAME=VALUE (SI units; {model} model):"]
    for q in params if params is not None else scene_mod.params_for(model):
        unit = "" if q.unit == "1" else f" [{q.unit}]"
        default = (str(q.default).lower() if q.kind == "bool" else
                   q.default if q.kind == "int" else f"{q.default:g}")
        rows.append(f"  {q.name}{unit} = {default}, {q.range_text()}: {q.description}")
    return "\n".join(rows)


JOINT_HELP = ("a joint file (TOML or JSON; joints/ holds the paper's, a small car's and a light "
              "truck's): the joint's geometry, masses, materials, friction and needle row; "
              "{over} (docs/getting-started.md)")


def _scene_args(p: argparse.ArgumentParser, model: str) -> None:
    p.epilog = _param_epilog(model)
    p.add_argument("--joint", metavar="FILE",
                   help=JOINT_HELP.format(over="--scene and --set override it"))
    p.add_argument("--scene", metavar="FILE.toml", help="scene parameters (SI) as NAME = VALUE; "
                                                        "over the joint file's, under --set")
    p.add_argument("--set", metavar="NAME=VALUE", action="append", default=[],
                   help="set a parameter in SI units (repeatable; names, units, defaults and "
                        "ranges below)")
    p.add_argument("--theta-deg", type=float, metavar="DEG", help="joint angle in degrees")
    p.add_argument("--whirl-hz", type=float, metavar="HZ", help="whirl frequency in Hz (omega = 2 pi f)")


def overrides_from(args, model: str = "contact") -> dict:
    """Scene overrides (SI values) for ``model``: the joint file's (--joint), then the scene
    file's (--scene), then --set and the unit-named convenience options."""
    out: dict = {}
    if getattr(args, "joint", None):
        from reduced_model.joint import for_model, load_joint
        out.update(for_model(load_joint(args.joint), model))
    if getattr(args, "scene", None):
        out.update(_load_scene_file(args.scene))
    for item in args.set:
        if "=" not in item:
            raise ValueError(f"--set expects NAME=VALUE, got '{item}'")
        name, text = item.split("=", 1)
        name = name.strip()
        out[name] = scene_mod.parse_value(name, text)
    if args.theta_deg is not None:
        if not math.isfinite(args.theta_deg):
            raise ValueError("theta-deg: not a finite number; allowed range [0, 45) deg")
        out["theta"] = math.radians(args.theta_deg)
    if args.whirl_hz is not None:
        if not math.isfinite(args.whirl_hz):
            raise ValueError("whirl-hz: not a finite number; allowed range [0, 1591.5] Hz")
        out["omega"] = 2.0 * math.pi * args.whirl_hz
    if getattr(args, "bearing", None) is not None:
        out["bearing"] = args.bearing
    return out


DT_HELP = ("communication step [s] (default 1e-4, or a 1000th of the whirl cycle when that "
           "is shorter)")


def _dt(args):
    """--dt [s], checked (None: the default of harness.runs.default_dt)."""
    if args.dt is not None and not (math.isfinite(args.dt) and args.dt > 0):
        raise ValueError(f"dt = {args.dt!r}: allowed range (0, inf) s")
    return args.dt


def cmd_analytic(args) -> int:
    from reduced_model.analysis import analytic_report, format_analytic
    r = analytic_report(overrides_from(args, "analytic"))
    print(json.dumps(r, indent=2) if args.json else format_analytic(r))
    return 0


def cmd_params(args) -> int:
    from reduced_model.docs import outputs_markdown, params_markdown
    print(params_markdown())
    print()
    print(outputs_markdown())
    return 0


def _load_scene_file(path) -> dict:
    import tomllib
    try:
        with open(path, "rb") as f:
            data = tomllib.load(f)
    except OSError as e:
        raise ValueError(f"--scene {path}: {e.strerror}") from None
    except tomllib.TOMLDecodeError as e:
        raise ValueError(f"--scene {path}: not valid TOML ({e})") from None
    return data.get("scene", data)


def cmd_compare(args) -> int:
    from harness.compare import compare, format_table
    r = compare(overrides_from(args), max_cycles=args.max_cycles, dt=_dt(args))
    if args.out:
        from harness.plots import compare_plots
        compare_plots(r, args.out)
    if args.json:
        print(json.dumps({k: v for k, v in r.items() if not k.startswith("_")}, indent=2))
    else:
        print(format_table(r))
        if args.out:
            print(f"plots: {args.out}/")
    return 0 if r["pass"] else 1


def cmd_paper(args) -> int:
    from harness.paper import reproduce
    r = reproduce(args.out, share_bearing=args.share_bearing)
    for c in r["claims"]:
        print(f"[{'PASS' if c['pass'] else 'FAIL'}] {c['claim']}: {c['measured']}")
    print(f"report: {args.out}/report.md")
    return 0 if r["pass"] else 1


def cmd_sweep(args) -> int:
    from pathlib import Path
    from harness import sweep as sw
    if not args.grid:
        raise ValueError("--grid NAME=START:STOP:N is required (repeat it for more parameters)")
    grid = dict(sw.parse_grid(g) for g in args.grid)
    base = overrides_from(args, args.model)
    rows = sw.sweep(grid, base, model=args.model, max_cycles=args.max_cycles, dt=_dt(args),
                    scheduler=args.scheduler, workers=args.workers, progress=True)
    out = Path(args.out)
    csv_path = sw.write_csv(rows, out / "sweep.csv")
    png = sw.plot(rows, grid, out / "sweep_order3.png")
    bad = [r for r in rows if r["error"]]
    unsettled = [r for r in rows if not r["error"] and not r["settled"]]
    print(f"{len(rows)} points, {len(bad)} failed, {len(unsettled)} not settled within the cap "
          f"(column 'settled' in the CSV); {csv_path}, {png}")
    for r in bad[:5]:
        print(f"  failed: {r}")
    for r in unsettled[:5]:
        print(f"  NOT SETTLED after {r['cycles']} cycles (last change "
              f"{100 * r['cycle_change']:.3g} %): {r}")
    return 1 if bad else 0


def cmd_bench(args) -> int:
    from pathlib import Path
    from harness import bench
    if not 1 <= args.runs <= 1000:
        raise ValueError(f"--runs = {args.runs}: allowed range [1, 1000]")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.peer:
        rows = bench.peers(runs=args.runs, quick=args.quick, log=lambda m: print(m, flush=True))
        table = bench.peers_markdown(rows)
        (out / "peers.md").write_text(table + "\n")
        print(table)
        print(f"written: {out}/peers.md")
        return 0
    text, off = bench.report(out, runs=args.runs, quick=args.quick,
                             step_cost_only=args.step_cost, log=lambda m: print(m, flush=True))
    print(text)
    print(f"written: {out}/bench.md" + (" (the step-cost table only)" if args.step_cost else
                                         ", work_precision.csv, work_precision.png"))
    for r in off:
        print(f"default setting off the Pareto front: {r['model']} {r['setting']}")
    return 1 if off else 0


def cmd_stress(args) -> int:
    from harness.stress import stress, write_report
    rows = stress(quick=args.quick, log=lambda m: print(m, flush=True))
    path = write_report(rows, args.out)
    bad = sum(not r["pass"] for r in rows)
    print(f"{len(rows) - bad} passed, {bad} failed; report {path}")
    return 1 if bad else 0


def cmd_runup(args) -> int:
    from harness import input_transients as T
    sv = dict(T.RUNUP_START, **overrides_from(args))
    _dt(args)
    if args.input:
        inputs = T.read_input_csv(args.input)
        stop = inputs["time"][-1]
    else:
        for name in ("from_hz", "to_hz"):
            if not 0 <= getattr(args, name) <= 500:
                raise ValueError(f"--{name.replace('_', '-')} = {getattr(args, name)} Hz: "
                                 "allowed [0, 500]")
        if not args.duration > 0:
            raise ValueError(f"--duration = {args.duration} s: allowed (0, 600]")
        inputs, stop = T.ramp_inputs(args.from_hz, args.to_hz, args.duration), args.duration
    if args.plunge_amplitude:
        if not (0 < args.plunge_amplitude <= 0.05 and 0 < args.plunge_hz <= 500):
            raise ValueError(f"--plunge-amplitude = {args.plunge_amplitude} m, --plunge-hz = "
                             f"{args.plunge_hz} Hz: allowed (0, 0.05] m and (0, 500] Hz")
        if "plunge_speed" in inputs:
            raise ValueError("--plunge-amplitude and an input history with plunge_speed: "
                             "give one")
        inputs = T.with_plunge(inputs, stop, args.plunge_amplitude, args.plunge_hz, args.dt)
    rows = T.runup_fmus(sv, inputs, stop, dt=args.dt)
    if not rows:
        raise ValueError("the history holds no whole revolution of the whirl angle")
    out = T.write_runup(rows, args.out)
    print(f"orders of {rows[0]['signal']} per revolution")
    print(f"{'rev':>4} {'speed [Hz]':>10} {'order 3 contact [N]':>20} {'analytic [N]':>13} "
          f"{'diff [%]':>9} {'order 1 contact [N]':>20}")
    for r in rows:
        print(f"{r['revolution']:4d} {r['speed_hz']:10.2f} {r['contact_order3']:20.3f} "
              f"{r['analytic_order3']:13.3f} {r['order3_diff_pct']:+9.2f} "
              f"{r['contact_order1']:20.3f}")
    print(f"written: {out}/runup.csv, runup.json, runup.png")
    return 0


def cmd_example(args) -> int:
    from harness import example as E
    if not (0 < args.stop <= 60 and 1e-6 <= args.step <= 1e-2 and args.step < args.stop):
        raise ValueError(f"--stop = {args.stop} s, --step = {args.step} s: allowed (0, 60] s "
                         "and [1e-6, 1e-2] s, the step below the stop time")
    powertrain = E.powertrain_overrides(args.set)
    joints = tuple(E.JOINTS) if args.model == "both" else (args.model,)
    tools = E.TOOLS if args.tool == "both" else (args.tool,)
    joint = None
    if args.joint:
        from reduced_model.joint import load_joint
        joint = load_joint(args.joint)
    r = E.launch(args.out, args.stop, args.step, joints, tools, powertrain=powertrain,
                 check_step=not args.no_step_check, joint=joint)
    print(E.format_table(r))
    print(f"written into {args.out}: {', '.join(r['files'])}")
    return 0


def cmd_joint(args) -> int:
    from reduced_model import scene as sc
    from reduced_model.joint import for_model, load_joint
    from reduced_model.traverse import outside_checked
    j = load_joint(args.file)
    start = {"TripodRoller": for_model(j, "contact"),
             "TripodRollerAnalytic": for_model(j, "analytic")}
    outside = outside_checked(sc.validate(for_model(j, "analytic"), "analytic"))
    if args.json:
        print(json.dumps({"joint": j, "start_values": start, "outside_checked": outside},
                         indent=2))
        return 0
    print(f"{args.file}: a joint of pitch circle diameter {2e3 * j['s']:.1f} mm")
    for k, v in j.items():
        unit = sc.BY_NAME[k].unit
        print(f"  {k} = {v:g}{'' if unit == '1' else ' ' + unit}")
    print("start values: all of them for TripodRoller.fmu; "
          f"{', '.join(start['TripodRollerAnalytic'])} for TripodRollerAnalytic.fmu")
    print("at the default scene (10 deg, 10 Hz, 1000 N): " +
          ("inside the range the traverse model was checked in" if not outside else
           "outside the range the traverse model was checked in: " + "; ".join(outside)))
    return 0


def cmd_build(args) -> int:
    from harness.fmus import FMU_NAMES, check_fmu, ensure_fmu
    if args.check:
        same, line = check_fmu(args.check)
        print(line)
        return 0 if same else 1
    for name in FMU_NAMES + ("Powertrain",):
        print(ensure_fmu(name, force=args.force))
    return 0


class _Parser(argparse.ArgumentParser):
    """argparse with its errors in one line, exit status 2 (no usage block above them)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {' '.join(message.split())}\n")


def _unknown_options(ap, args, extra) -> str:
    """One line for options the subcommand does not have, each with its nearest valid one."""
    import difflib
    sub = next(a for a in ap._actions if isinstance(a, argparse._SubParsersAction))
    p = sub.choices[args.command]
    valid = [o for a in p._actions for o in a.option_strings if o.startswith("--")]
    words = []
    for x in extra:
        if not x.startswith("-"):
            words.append(repr(x))
            continue
        name = x.split("=", 1)[0]
        near = ([o for o in valid if o.startswith(name)]   # an abbreviation: what it abbreviates
                or difflib.get_close_matches(name, valid, n=1, cutoff=0.5))
        words.append(f"{x} (did you mean {near[0]}?)" if near else x)
    return (f"{p.prog}: error: unrecognized arguments: {', '.join(words)}; "
            f"`{p.prog} --help` lists its options")


def build_parser() -> argparse.ArgumentParser:
    # allow_abbrev=False: an option is spelled whole or refused (--theta is not --theta-deg)
    ap = _Parser(prog="tripod-thrust", formatter_class=_Help, allow_abbrev=False,
                                 description="Thrust force of tripod constant-velocity joints.",
                                 epilog="`tripod-thrust COMMAND --help` lists a command's "
                                        "options with units and defaults.")
    ap.add_argument("--version", action="version", version=f"%(prog)s {version()}")
    sub = ap.add_subparsers(dest="command", required=True)

    def add(name, help):
        return sub.add_parser(name, help=help, description=help, formatter_class=_Help,
                              allow_abbrev=False)

    p = add("compare", "run the analytic and the contact FMU on a scene and compare orders 1 and 3")
    _scene_args(p, "contact")
    p.add_argument("--bearing", type=int, choices=(0, 1, 2), default=None,
                   help="the contact FMU's needle bearing, the contact model the analytic FMU is "
                        "judged against: 0 ideal, 1 lumped row, 2 every needle resolved (the "
                        "paper's full model; about 4 s a whirl cycle); the same as --set bearing=N")
    p.add_argument("--max-cycles", type=int, default=None,
                   help="cap on whirl cycles, count; the run stops earlier once orders 1 and 3 change by "
                        "less than 0.1 %% from one cycle to the next (default 40)")
    p.add_argument("--dt", type=float, default=None, help=DT_HELP)
    p.add_argument("--out", metavar="DIR", help="write PNG plots into DIR")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_compare)
    p = add("sweep", "run an FMU over a parameter grid in parallel (dask)")
    _scene_args(p, "contact")
    p.add_argument("--grid", metavar="NAME=START:STOP:N", action="append", default=[],
                   help="a swept parameter in SI units (repeat for a grid)")
    p.add_argument("--model", choices=("contact", "analytic"), default="contact",
                   help="which FMU to sweep")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="address of a running dask.distributed scheduler (default: local processes)")
    p.add_argument("--workers", type=int, default=2, help="local worker processes, count (default 2)")
    p.add_argument("--max-cycles", type=int, default=None,
                   help="cap on whirl cycles per point, count; each run stops once periodic "
                        "(default 40)")
    p.add_argument("--dt", type=float, default=None, help=DT_HELP)
    p.add_argument("--out", metavar="DIR", default="out/sweep", help="output folder (CSV, plots)")
    p.set_defaults(func=cmd_sweep)
    p = add("bench", "work-precision benchmark, cost per step, run breakdown")
    p.add_argument("--out", metavar="DIR", default="out/bench",
                   help="output folder (tables, CSV, plot)")
    p.add_argument("--runs", type=int, default=5, help="timed runs per setting, count (median)")
    p.add_argument("--quick", action="store_true",
                   help="skip the whole-process timings; with --peer: fewer rows, one run each")
    p.add_argument("--step-cost", action="store_true",
                   help="only the cost-per-step table (about a minute)")
    p.add_argument("--peer", action="store_true",
                   help="only the peer table: the contact FMU beside scipy solve_ivp (LSODA, "
                        "Radau) on the same equations and Exudyn's multibody model of the same "
                        "roller (extra 'peer'), time against order-3 error")
    p.set_defaults(func=cmd_bench)
    p = add("stress", "run the contact FMU far outside the paper's scene")
    p.add_argument("--out", metavar="DIR", default="out/stress", help="output folder (report)")
    p.add_argument("--quick", action="store_true", help="the small subset CI runs")
    p.set_defaults(func=cmd_stress)
    p = add("paper", "reproduce the paper's figures and claims (PNG + report.md)")
    p.add_argument("--out", metavar="DIR", default="out/paper", help="output folder (default out/paper)")
    p.add_argument("--share-bearing", type=int, choices=(1, 2), default=2,
                   help="bearing of the section 4.2 friction study: 2 needle-resolved (default, "
                        "about 2 min), 1 lumped (seconds)")
    p.set_defaults(func=cmd_paper)
    p = add("runup", "order tracking: both FMUs through a run-up or any input history, orders 1 "
                     "and 3 of Fz_joint (one roller: Fz_mod) per revolution against speed "
                     "(CSV, JSON, plot); the whole joint at 300 N m and 8 deg unless --set says "
                     "otherwise")
    _scene_args(p, "contact")
    p.add_argument("--from-hz", type=float, default=2.0, help="whirl speed at the start [Hz]")
    p.add_argument("--to-hz", type=float, default=40.0, help="whirl speed at the end [Hz]")
    p.add_argument("--duration", type=float, default=0.5, help="length of the ramp [s]")
    p.add_argument("--input", metavar="FILE.csv",
                   help="an input history instead of the ramp: FMPy's input CSV (time, then "
                        "any input columns by name, SI units)")
    p.add_argument("--plunge-amplitude", type=float, default=0.0, metavar="M",
                   help="a harmonic plunge on top [m] (the spider at M sin(2 pi f t); a "
                        "constant plunge speed: --set plunge_speed=V)")
    p.add_argument("--plunge-hz", type=float, default=25.0,
                   help="frequency of that plunge [Hz]")
    p.add_argument("--dt", type=float, default=1e-4, help="communication step [s]")
    p.add_argument("--out", metavar="DIR", default="out/runup", help="output folder")
    p.set_defaults(func=cmd_runup)
    p = add("example", "the driveline example: a vehicle launch, the joint FMU beside a "
                       "powertrain FMU in one SSP system file, run by FMPy and libcosim; peak "
                       "lateral acceleration, order map, the joint's thrust orders "
                       "(docs/driveline-example.md)")
    from driveline.powertrain import PARAMS as POWERTRAIN
    p.epilog = _param_epilog("powertrain", POWERTRAIN)
    p.add_argument("--set", metavar="NAME=VALUE", action="append", default=[],
                   help="set a powertrain parameter in SI units (repeatable; names, units, "
                        "defaults and ranges below)")
    p.add_argument("--model", choices=("contact", "analytic", "both"), default="both",
                   help="which joint FMU is in the system (both: one run each)")
    p.add_argument("--joint", metavar="FILE",
                   help=JOINT_HELP.format(over="the joint FMU's values (--set sets the "
                                               "powertrain's)"))
    p.add_argument("--tool", choices=("fmpy", "libcosim", "both"), default="both",
                   help="which co-simulation tool runs it")
    p.add_argument("--stop", type=float, default=2.5, help="end of the launch [s]")
    p.add_argument("--step", type=float, default=1e-4, help="communication step [s]")
    p.add_argument("--no-step-check", action="store_true",
                   help="skip the convergence run at half the step")
    p.add_argument("--out", metavar="DIR", default="out/example", help="output folder")
    p.set_defaults(func=cmd_example)
    p = add("build", "build build/TripodRoller.fmu, build/TripodRollerAnalytic.fmu and "
                     "build/Powertrain.fmu (when missing or stale)")
    p.add_argument("--force", action="store_true", help="rebuild even when up to date")
    p.add_argument("--check", metavar="FMU", help="instead: whether FMU came from this "
                   "checkout, byte for byte (exit 0) or not (exit 1)")
    p.set_defaults(func=cmd_build)
    p = add("joint", "check a joint file and print the FMUs' start values from it (and whether "
                     "the analytic model was checked for such a joint)")
    p.add_argument("file", metavar="FILE", help="a joint file (TOML or JSON; joints/ has examples)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_joint)
    p = add("params", "print the parameter table (Markdown)")
    p.set_defaults(func=cmd_params)
    p = add("analytic", "reduced (analytic) model: orders 1 and 3, closed form vs FFT")
    _scene_args(p, "analytic")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_analytic)
    return ap


def main(argv=None) -> int:
    ap = build_parser()
    args, extra = ap.parse_known_args(argv)
    if extra:
        print(_unknown_options(ap, args, extra), file=sys.stderr)
        return 2
    try:
        return args.func(args)
    except (ValueError, CliError, FmuRunError) as e:   # bad input, or an FMU run that failed
        print(f"tripod-thrust {args.command}: error: {' '.join(str(e).split())}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
