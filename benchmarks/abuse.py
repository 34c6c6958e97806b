"""The long abuse run: every value of every variable, and deserialise fuzzing under valgrind, for
each bearing and roller count of the contact FMU and both roller counts of the analytic FMU.

Per scene:
- the value matrix (tests/value_matrix.py): every parameter and input at NaN, +-Inf, 0, -0,
  a denormal, min, max, +-1e300 (integers: min, max, 0, -1, one past each end, the int32
  limits), before initialisation and during the run;
- state fuzzing (tests/state_abuse.py) under valgrind memcheck: every truncation of a good
  state, random bit flips, random tails, bytes changed with the checksum made valid again
  (what reaches the decoder's own checks) and two pickle payloads.

A state case is clean when refused with fmi2Error, or taken and then stepped to finite outputs
or refused at the step with a reason (a changed byte may leave a well-formed state); a defect is
a non-finite output with fmi2OK, code run (a pickle payload would create a file), the good state
no longer restoring after the refusals, or an invalid memory access that a baseline run of the
same interpreter without any FMU does not show.  A value case is clean when it runs to finite
outputs or is refused with a one-line logged reason, within 10 s.

Prints the counts table and writes it into docs/native-layer.md (between the abuse-counts
markers).  Usage: python -m benchmarks.abuse [--flips N] [--resealed N] [--random N]
[--no-valgrind] [--no-docs]   (about 10-20 minutes with valgrind on 2 cores).
"""
import argparse
import collections
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.memcheck import BASELINE, errors, signature, valgrind

ROOT = Path(__file__).resolve().parents[1]

SCENES = [   # (FMU, integer start values, crafted cases beyond the common ones)
    ("TripodRoller", {"bearing": 0, "n_rollers": 1}, "arrays"),
    ("TripodRoller", {"bearing": 0, "n_rollers": 3}, "arrays"),
    ("TripodRoller", {"bearing": 1, "n_rollers": 3}, "arrays"),
    ("TripodRoller", {"bearing": 2, "n_rollers": 1}, "arrays"),
    ("TripodRollerAnalytic", {"n_rollers": 1}, "analytic"),
    ("TripodRollerAnalytic", {"n_rollers": 3}, "analytic"),
]
CASE_SECONDS = 10.0
DOC = ROOT / "docs" / "native-layer.md"


def value_matrix(fmu, ints):
    p = subprocess.run([sys.executable, str(ROOT / "tests" / "value_matrix.py"), str(fmu),
                        json.dumps({"ints": ints})], capture_output=True, text=True,
                       timeout=3600)
    rows = [json.loads(ln) for ln in p.stdout.splitlines() if ln.startswith('{"case')]
    bad = [r for r in rows if r["outcome"] not in ("finite", "refused")
           or r["seconds"] > CASE_SECONDS]
    if p.returncode != 0:
        bad.append({"case": "worker", "outcome": f"exit {p.returncode}: {p.stderr[-300:]}"})
    return rows, bad


def state_fuzz(fmu, name, ints, kind, args, log, base):
    spec = {"ints": ints, "moving": name.endswith("Analytic"), "every_truncation": True,
            "flips": args.flips, "random": args.random, "resealed": args.resealed,
            "seed": 7,
            "marker": os.path.join(tempfile.mkdtemp(), "code-ran")}
    cmd = [sys.executable, str(ROOT / "tests" / "state_abuse.py"), str(fmu), json.dumps(spec)]
    env = dict(os.environ, PYTHONMALLOC="malloc")
    if args.no_valgrind:
        p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=7200)
        rc, text, new = p.returncode, p.stdout, []
    else:
        rc, text = valgrind(cmd, log, env)
        new = [s for s in map(signature, (f for _, f in errors(Path(log).read_text())))
               if s not in base]
    lines = [ln for ln in text.splitlines() if ln.startswith('{"size"')]
    res = json.loads(lines[-1]) if lines else None
    return rc, res, new


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--flips", type=int, default=2000)
    ap.add_argument("--resealed", type=int, default=2000)
    ap.add_argument("--random", type=int, default=500)
    ap.add_argument("--no-valgrind", action="store_true")
    ap.add_argument("--no-docs", action="store_true")
    ap.add_argument("--scenes", help="comma-separated indexes into SCENES (default: all)")
    ap.add_argument("--out", default=str(ROOT / "out" / "abuse"))
    args = ap.parse_args()
    if not args.no_valgrind and not shutil.which("valgrind"):
        sys.exit("abuse.py needs valgrind (apt-get install valgrind), or --no-valgrind")
    from harness.fmus import ensure_fmu
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    base = set()
    if not args.no_valgrind:
        log = out / "baseline.log"
        valgrind([sys.executable, "-c", BASELINE], log, dict(os.environ, PYTHONMALLOC="malloc"))
        base = {signature(f) for _, f in errors(log.read_text())}
    rows = []
    pick = SCENES if not args.scenes else [SCENES[int(i)] for i in args.scenes.split(",")]
    for name, ints, kind in pick:
        fmu = ensure_fmu(name)
        label = f"{name} " + ", ".join(f"{k} {v}" for k, v in ints.items())
        t0 = time.perf_counter()
        vals, vbad = value_matrix(fmu, ints)
        slowest = max((r["seconds"] for r in vals), default=0.0)
        rows.append((label, "values before and during the run", len(vals),
                     len(vals) - len(vbad), len(vbad),
                     f"slowest case {slowest:.2f} s; " + outcome_text(
                         collections.Counter(r["outcome"] for r in vals))))
        for r in vbad:
            print(f"  defect: {label}: {r}", file=sys.stderr)
        log = out / (re.sub(r"\W+", "_", label) + ".log")
        rc, res, new = state_fuzz(fmu, name, ints, kind, args, log, base)
        if res is None:
            rows.append((label, "serialised states", 0, 0, 1, f"worker exit {rc}, no result"))
            continue
        cases = res["cases"]
        good = cases.pop("good")
        count = collections.Counter(cases.values())
        defects = count["non-finite"] + int(res["code_ran"]) + \
            int(good != "finite" or res["good_after"] != "finite") + len(new) + int(rc != 0)
        clean = sum(count[k] for k in ("refused", "refused-later", "finite"))
        rows.append((label, f"serialised states ({res['size']} bytes good)", len(cases), clean,
                     defects, outcome_text(count) + f"; code run: {res['code_ran']}; "
                     f"invalid accesses not in the baseline: "
                     f"{'n/a (no valgrind)' if args.no_valgrind else len(new)}"))
        print(f"{label}: {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    table = render(rows, args)
    print(table)
    if not args.no_docs:
        from harness.docgen import write_marked
        write_marked(DOC, "abuse-counts", table)


def outcome_text(count):
    return ", ".join(f"{k} {v}" for k, v in sorted(count.items()))


def render(rows, args):
    head = (f"Generated by `python -m benchmarks.abuse` ({'no valgrind' if args.no_valgrind else 'states under valgrind memcheck'}; "
            f"{args.flips} bit flips, {args.random} random tails, {args.resealed} changed bytes "
            "re-sealed with a valid checksum, every truncation, the crafted states and two "
            "pickle payloads per scene).\n\n"
            "| scene | cases | count | clean | defects | outcomes |\n|---|---|---|---|---|---|")
    body = "\n".join(f"| {a} | {b} | {c} | {d} | {e} | {f} |" for a, b, c, d, e, f in rows)
    total = (sum(r[2] for r in rows), sum(r[3] for r in rows), sum(r[4] for r in rows))
    return head + "\n" + body + f"\n| all | | {total[0]} | {total[1]} | {total[2]} | |"


if __name__ == "__main__":
    main()
