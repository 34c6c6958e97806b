"""Speed of this tree against an earlier commit, measured in one run (a refactor that must not
cost speed: issue 14 asks for within 5 %).

The earlier commit is checked out into a temporary git worktree and its contact FMU built there;
both FMUs are timed in alternation (each in its own fresh worker process, after warm-up):
two whirl cycles of the paper's scene (contact FMU with the ideal and lumped bearing, the
analytic FMU; 1e-4 s communication step, doStep + getReal); plus the needle-resolved bearing
in-process (46 x 7 needles, 0.1 whirl cycle).  With --c-host, also the step cost in a plain C
host (tests/c_host/fmu_run.c, no Python in its process) of the lumped bearing and the analytic
FMU, each at their defaults, at fixed inputs and under a master moving theta, omega and F_press
every step.  Prints a table of medians and the ratio now / before.
Usage: python benchmarks/ab_speed.py --before REV [--runs N] [--c-host]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

_NEEDLES = r'''
import sys, time
sys.path.insert(0, sys.argv[1] + "/fmu_src"); sys.path.insert(0, sys.argv[1])
from tripod_model.simulate import simulate
simulate({"bearing": 2}, cycles=0.002)            # compile / load the cache
t0 = time.perf_counter(); simulate({"bearing": 2}, cycles=0.1); print(time.perf_counter() - t0)
'''

_FMU = r'''
import json, sys
sys.path.insert(0, sys.argv[1])
from harness.fmus import ensure_fmu
from harness.bench import time_runs
fmu = ensure_fmu("TripodRoller")
cases = [{"sv": {}, "dt": 1e-4, "stop": 0.2}, {"sv": {"bearing": 1}, "dt": 1e-4, "stop": 0.2}]
walls = [r["wall"] for r in time_runs(fmu, cases, runs=int(sys.argv[2]))]
walls += [r["wall"] for r in time_runs(ensure_fmu("TripodRollerAnalytic"), cases[:1],
                                       runs=int(sys.argv[2]))]
print(json.dumps(walls))
'''


_PATHS = r'''
import json, sys
sys.path.insert(0, sys.argv[1])
from harness.fmus import ensure_fmu
print(json.dumps({n: str(ensure_fmu(n)) for n in ("TripodRoller", "TripodRollerAnalytic")}))
'''

# the C host's cases: (FMU, Integer parameters, the share of their start values by which theta,
# omega and F_press move every step: 0 fixed inputs, 1e-3 a driveline master)
C_CASES = {"c:lumped": ("TripodRoller", {"bearing": 1}, 0.0),
           "c:lumped-master": ("TripodRoller", {"bearing": 1}, 1e-3),
           "c:analytic": ("TripodRollerAnalytic", {}, 0.0),
           "c:analytic-master": ("TripodRollerAnalytic", {}, 1e-3)}
C_STEPS, C_DT = 2000, 1e-4      # two whirl cycles of the paper's scene; timed: the first half


def c_host(tmp):
    """tests/c_host/fmu_run.c compiled into tmp (the host the tests run the FMUs in)."""
    sys.path.insert(0, str(ROOT))
    from harness.fmus import builder
    out = Path(tmp) / "fmu_run"
    subprocess.run([os.environ.get("CC") or "cc", "-std=c99", "-O2",
                    f"-I{builder()._fmi_headers()}", str(ROOT / "tests" / "c_host" / "fmu_run.c"),
                    "-o", str(out), "-lm", "-ldl"], check=True, capture_output=True)
    return out


def c_step_us(host, fmu, ints, share, tmp):
    """Microseconds a step of the FMU at fmu in the C host, C_CASES' way."""
    import zipfile
    from fmpy import read_model_description
    md = read_model_description(str(fmu))
    d = Path(tmp) / f"{Path(fmu).parent.parent.name}-{md.coSimulation.modelIdentifier}"
    if not d.exists():
        zipfile.ZipFile(fmu).extractall(d)
    vr = {v.name: v for v in md.modelVariables}
    ins = ",".join(f"{vr[n].valueReference}:{float(vr[n].start)!r}:"
                   f"{share * float(vr[n].start)!r}:3141.6" for n in ("theta", "omega", "F_press"))
    outs = ",".join(str(v.valueReference) for v in md.modelVariables
                    if v.causality == "output" and v.type == "Real")
    sets = [",".join(f"{vr[k].valueReference}={v}" for k, v in ints.items())] if ints else []
    p = subprocess.run([str(host), str(d / "binaries" / "linux64" /
                                       f"{md.coSimulation.modelIdentifier}.so"), md.guid,
                        str(C_STEPS), repr(C_DT), str(Path(tmp) / "rows.bin"), ins, outs, *sets],
                       capture_output=True, text=True, timeout=600)
    if p.returncode != 0 or "FAILED" in p.stdout:
        raise RuntimeError(p.stdout[-2000:] + p.stderr[-2000:])
    return float(p.stdout.split("time per-step-us")[1].split()[0])


def _run(code, tree, *args):
    # the tree's packages first, for this process and the builds it starts (the environment's
    # own path names this checkout's fmu_src: the two trees' modules must not mix)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join((str(tree), str(Path(tree) / "fmu_src"))))
    # run in the tree: `python -c` puts its working folder first on the path, ahead of
    # PYTHONPATH, so run from another checkout it would import that checkout's packages
    p = subprocess.run([sys.executable, "-c", code, str(tree), *map(str, args)],
                       capture_output=True, text=True, timeout=3600, env=env, cwd=tree)
    if p.returncode != 0:
        raise RuntimeError(p.stderr[-2000:])
    return p.stdout.strip().splitlines()[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", required=True, help="the earlier commit (any git revision)")
    ap.add_argument("--runs", type=int, default=5, help="alternating rounds (default 5)")
    ap.add_argument("--c-host", action="store_true",
                    help="also the lumped bearing's and the analytic FMU's step in a C host")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        old = Path(tmp) / "before"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(old),
                        args.before], check=True, capture_output=True)
        try:
            trees = {"before": old, "now": ROOT}
            t = {k: {"ideal": [], "lumped": [], "analytic": [], "needles": []} for k in trees}
            host = c_host(tmp) if args.c_host else None
            fmus = {k: json.loads(_run(_PATHS, trees[k])) for k in trees} if host else {}
            for k in fmus:
                t[k].update({c: [] for c in C_CASES})
            for r in range(args.runs):
                # alternate which tree goes first: a drift of the machine's load hits both
                for k in (("before", "now") if r % 2 == 0 else ("now", "before")):
                    ideal, lumped, analytic = json.loads(_run(_FMU, trees[k], 1))
                    t[k]["ideal"].append(ideal)
                    t[k]["lumped"].append(lumped)
                    t[k]["analytic"].append(analytic)
                    t[k]["needles"].append(float(_run(_NEEDLES, trees[k])))
                    for c, (name, ints, share) in (C_CASES.items() if host else ()):
                        t[k][c].append(c_step_us(host, fmus[k][name], ints, share, tmp))
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(old)],
                           capture_output=True)
    rev = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", args.before],
                         capture_output=True, text=True).stdout.strip()
    print(f"Now against {rev}, {args.runs} alternating rounds, medians [min-max]\n")
    print("| case | before | now | now / before |")
    print("|---|---|---|---|")
    names = {"ideal": "contact FMU, ideal bearing, two cycles (2000 doStep + getReal)",
             "lumped": "contact FMU, lumped bearing, two cycles",
             "analytic": "analytic FMU, two cycles (2000 doStep + getReal)",
             "needles": "needle-resolved bearing (46 x 7), 0.1 cycle in-process"}
    if args.c_host:
        names.update({"c:lumped": "C host: contact FMU, lumped bearing, a step [us]",
                      "c:lumped-master": "C host: the same under a master moving theta, omega, "
                                         "F_press [us]",
                      "c:analytic": "C host: analytic FMU (its default), a step [us]",
                      "c:analytic-master": "C host: the same under that master [us]"})
    for key, name in names.items():
        c = key.startswith("c:")
        b, n = t["before"][key], t["now"][key]
        mb, mn = statistics.median(b), statistics.median(n)
        u, f = ("", ".2f") if c else (" s", ".4f")
        print(f"| {name} | {mb:{f}}{u} [{min(b):{f}}-{max(b):{f}}] | {mn:{f}}{u} "
              f"[{min(n):{f}}-{max(n):{f}}] | {mn / mb:.3f} |")


if __name__ == "__main__":
    main()
