"""Speed of this tree against an earlier commit, measured in one run (a refactor that must not
cost speed: issue 14 asks for within 5 %).

The earlier commit is checked out into a temporary git worktree and its contact FMU built there;
both FMUs are timed in alternation (each in its own fresh worker process, after warm-up):
two whirl cycles of the paper's scene (contact FMU with the ideal and lumped bearing, the
analytic FMU; 1e-4 s communication step, doStep + getReal); plus the needle-resolved bearing
in-process (46 x 7 needles, 0.1 whirl cycle).  Prints a table of medians and the ratio now / before.
Usage: python benchmarks/ab_speed.py --before REV [--runs N]
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


def _run(code, tree, *args):
    # the tree's packages first, for this process and the builds it starts (the environment's
    # own path names this checkout's fmu_src: the two trees' modules must not mix)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join((str(tree), str(Path(tree) / "fmu_src"))))
    p = subprocess.run([sys.executable, "-c", code, str(tree), *map(str, args)],
                       capture_output=True, text=True, timeout=3600, env=env)
    if p.returncode != 0:
        raise RuntimeError(p.stderr[-2000:])
    return p.stdout.strip().splitlines()[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", required=True, help="the earlier commit (any git revision)")
    ap.add_argument("--runs", type=int, default=5, help="alternating rounds (default 5)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        old = Path(tmp) / "before"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(old),
                        args.before], check=True, capture_output=True)
        try:
            trees = {"before": old, "now": ROOT}
            t = {k: {"ideal": [], "lumped": [], "analytic": [], "needles": []} for k in trees}
            for r in range(args.runs):
                # alternate which tree goes first: a drift of the machine's load hits both
                for k in (("before", "now") if r % 2 == 0 else ("now", "before")):
                    ideal, lumped, analytic = json.loads(_run(_FMU, trees[k], 1))
                    t[k]["ideal"].append(ideal)
                    t[k]["lumped"].append(lumped)
                    t[k]["analytic"].append(analytic)
                    t[k]["needles"].append(float(_run(_NEEDLES, trees[k])))
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
    for key, name in names.items():
        b, n = t["before"][key], t["now"][key]
        mb, mn = statistics.median(b), statistics.median(n)
        print(f"| {name} | {mb:.4f} s [{min(b):.4f}-{max(b):.4f}] | {mn:.4f} s "
              f"[{min(n):.4f}-{max(n):.4f}] | {mn / mb:.3f} |")


if __name__ == "__main__":
    main()
