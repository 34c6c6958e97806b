"""Generated blocks of README.md and docs/*.md: one registry of what each block holds, how
`make docs` regenerates it and how the docs test knows it is current.

A block is marked in the Markdown as
    <!-- generated: NAME -->
    ...
    <!-- end generated -->
Exact blocks (tables and outputs that depend on the code only) are regenerated and compared
text for text.  Measured blocks (timings) cannot be reproduced exactly; they are written from
one benchmark run, and the test checks that their rows are the cases today's code measures
(a case added, dropped or renamed without a new run fails).
"""
from __future__ import annotations

import math
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
FILES = [ROOT / "README.md"] + sorted(DOCS.glob("*.md"))
_BLOCK = re.compile(r"<!-- generated: (.+?) -->\n(.*?)<!-- end generated -->", re.S)


def blocks(text: str) -> list[tuple[str, str]]:
    """(name, content) of every generated block in a Markdown text, in order."""
    return [(m.group(1), m.group(2)) for m in _BLOCK.finditer(text)]


def replace(text: str, name: str, content: str) -> str:
    """The text with block ``name``'s content replaced (every occurrence)."""
    content = content.rstrip("\n") + "\n"
    return re.sub(rf"(<!-- generated: {re.escape(name)} -->\n).*?(<!-- end generated -->)",
                  lambda m: m.group(1) + content + m.group(2), text, flags=re.S)


def write_marked(path: Path, name: str, text: str) -> None:
    """Put text between <!-- NAME:begin --> and <!-- NAME:end --> in path: the tables the long
    benchmarks write with their own runs (abuse.py), which
    make docs does not rerun."""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    doc = path.read_text()
    i, j = doc.index(begin) + len(begin), doc.index(end)
    path.write_text(doc[:i] + "\n" + text + "\n" + doc[j:])


# --- exact blocks --------------------------------------------------------------------------

def _params() -> str:
    from reduced_model.docs import variables_markdown
    return variables_markdown()


def _analytic() -> str:
    """`tripod-thrust analytic` on the paper's scene, as a console block."""
    from reduced_model.analysis import format_analytic
    from reduced_model.analysis import analytic_report
    return "```\n$ tripod-thrust analytic\n" + format_analytic(analytic_report({})) + "\n```"


def _light_truck() -> str:
    """docs/getting-started.md's worked example: the light truck's joint, its launch-like
    scene, as `tripod-thrust analytic` and `tripod-thrust joint` print them."""
    from reduced_model.analysis import format_analytic
    from reduced_model.analysis import analytic_report
    from reduced_model.joint import EXAMPLES, for_model, load_joint
    j = for_model(load_joint(EXAMPLES / "light-truck.toml"), "analytic")
    scene = dict(j, theta=math.radians(8), omega=2.0 * math.pi * 15, torque=600.0)
    return ("```\n$ tripod-thrust analytic --joint joints/light-truck.toml --theta-deg 8 "
            "--whirl-hz 15 --set torque=600\n" + format_analytic(analytic_report(scene))
            + "\n```")


def _traverse_grid() -> str:
    from harness.validation import grid_rows, markdown
    return markdown(grid_rows())


def _demo() -> str:
    """What `make demo` prints: `tripod-thrust compare --out out`, run in a scratch folder."""
    import subprocess
    import tempfile
    exe = Path(sys.executable).with_name("tripod-thrust")
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run([str(exe), "compare", "--out", "out"], cwd=tmp, capture_output=True,
                           text=True, timeout=900)
    if p.returncode != 0:
        raise RuntimeError(p.stderr[-2000:])
    return "```\n" + p.stdout.rstrip("\n") + "\n```"


def _mask_wall(text: str) -> str:
    """Timings are measured, not reproducible: the wall-time line loses its numbers."""
    return re.sub(r"^(wall time:).*$", r"\1 ...", text, flags=re.M)


def _cells(content: str, first: str) -> list[str]:
    """The cells of the table row whose first cell starts with ``first``."""
    for r in content.splitlines():
        cells = [c.strip() for c in r.split("|")[1:-1]]
        if cells and cells[0].startswith(first):
            return cells
    raise KeyError(first)


def _readme_speed() -> str:
    """README's speed summary, taken from docs/benchmarks.md's measured blocks (one run)."""
    bm = dict(blocks((DOCS / "benchmarks.md").read_text()))
    spd, cost, wp = bm["make bench"], bm["bench: step cost"], bm["bench: work-precision"]
    two = _cells(spd, "ideal bearing, traverse (default)")[1].split(" [")[0]
    fresh = _cells(spd, "fresh `fmpy simulate` process")[1].split(" [")[0]
    ana = _cells(cost, "analytic FMU (traverse model, default)")[2]
    con = _cells(cost, "contact FMU, ideal bearing, traverse (default)")[2]
    joint = "the whole joint (n_rollers = 3) under that master: "
    master = [f"| {label}: analytic / contact FMU | {_cells(cost, ana_row)[2]}x / "
              f"{_cells(cost, con_row)[2]}x | same |" for label, ana_row, con_row in (
                  ("a driveline master setting new inputs every step (against the bare "
                   "boundary under the same master)",
                   "analytic FMU, ", "the same, "),
                  ("the whole joint (three rollers) under that master", joint + "analytic",
                   joint + "contact"))]
    res = next(r for r in wp.splitlines() if r.startswith("| contact bearing 2")
               and "| yes |" in r)
    # "median [min-max]" of the runs (a table written before the range: the median alone)
    med, *rng = [c.strip() for c in res.split("|")[1:-1]][4].rstrip("]").split(" [")
    span = ""
    if rng:
        lo, hi = (float(x) for x in rng[0].split("-"))
        span = f" [{lo:.1f}-{hi:.1f}]"
    # the cheapest Exudyn row: its order-3 error and its time against the FMU's at that error
    ex = _cells(bm["bench: peers"], "Exudyn")
    link = "[benchmarks](docs/benchmarks.md"
    return "\n".join([
        "| run (paper's scene, this 2-core machine) | time | full table |", "|---|---|---|",
        f"| contact FMU, two whirl cycles through FMPy, in process | {two} | "
        f"{link}#two-cycles-through-fmpy-make-bench) |",
        f"| a fresh `fmpy simulate` process of the contact FMU | {fresh} | same |",
        f"| cost of a step against the bare FMI boundary: analytic / contact FMU | {ana}x / "
        f"{con}x | {link}#cost-per-step-tripod-thrust-bench) |", *master,
        f"| needle-resolved bearing (46 needles x 7 spheres), two cycles, in process, median "
        f"[min-max] of the runs | "
        f"{float(med):.1f} s{span} | {link}#run-time-against-error-tripod-thrust-bench) |",
        f"| the same roller in Exudyn (a multibody engine), at equal order-3 error ({ex[3]}) | "
        f"{ex[4]}x the FMU's time | {link}#beside-peers-on-the-same-roller-tripod-thrust-bench---peer) |"])


def _powertrain_variables() -> str:
    from harness.fmus import ensure_fmu
    from harness.reference import variables_markdown
    return variables_markdown(ensure_fmu("Powertrain"))


EXACT = {"tripod-thrust params": _params, "tripod-thrust analytic": _analytic,
         "getting started: light truck": _light_truck,
         "readme: speed": _readme_speed, "powertrain: variables": _powertrain_variables}
# reproducible except for their timings (compared with the wall-time line masked)
RUN = {"make demo": _demo}
def _quadrant_grid() -> str:
    from harness.validation import quadrant_markdown, quadrant_rows
    return quadrant_markdown(quadrant_rows())


def _contact_damping() -> str:
    from harness.validation import damping_markdown, damping_rows
    return damping_markdown(damping_rows())


# slow: checked by the tests that rerun them (tests/test_traverse.py, tests/test_coast.py,
# tests/test_contact_model.py, tests/test_spider.py)
def _size_grid() -> str:
    from harness.validation import size_markdown, size_rows
    return size_markdown(size_rows())


def _spider_grid() -> str:
    from harness.validation import spider_markdown, spider_rows
    return spider_markdown(spider_rows())


SLOW_EXACT = {"traverse grid": _traverse_grid, "size grid": _size_grid,
              "quadrant grid": _quadrant_grid, "contact damping": _contact_damping,
              "spider grid": _spider_grid}


# --- measured blocks: the rows today's code would measure ----------------------------------

def _first_column(content: str) -> list[str]:
    rows = [r for r in content.splitlines() if r.startswith("|")][2:]
    return [r.split("|")[1].strip() for r in rows]


def _step_cost_rows():
    from harness.bench import STEP_COST_CASES
    return list(STEP_COST_CASES)


def _breakdown_rows():
    from harness.bench import BREAKDOWN_PARTS
    return list(BREAKDOWN_PARTS)


def _work_precision_rows():
    from harness.bench import ladder
    return [r[0] for r in ladder()]


def _side_by_side_rows():
    from harness.bench import ladder
    labels = dict.fromkeys(r[0] for r in ladder() if r[0].startswith("contact bearing 0"))
    return [label.split(", ", 1)[1] for label in labels] + ["generalized-alpha stepped in Python"]


def _peer_rows():
    from harness.bench import EXUDYN, PEER_EXUDYN, PEER_FMU, PEER_IVP
    return (["contact FMU through FMI (integrator 4)"] * len(PEER_FMU)
            + [f"scipy solve_ivp {m}" for m, _ in PEER_IVP] + [EXUDYN] * len(PEER_EXUDYN))


def _stress_rows():
    from harness.stress import cases
    return [c[0] for c in cases()]


def _benchmark(name):
    """benchmarks/<name>.py loaded by path, for the rows its table has: the harness does not
    import the benchmarks (they sit above it)."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(f"_docgen_{name}",
                                                  ROOT / "benchmarks" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _fmu_speed_rows():
    fmu_speed = _benchmark("fmu_speed")
    return [name for name, _ in fmu_speed.CASES] + list(fmu_speed.PROCESS_ROWS)


def _work_precision_check(content: str) -> list[str]:
    from harness.bench import GA_PYTHON, GA_PYTHON_STEPS
    want = _work_precision_rows() + [GA_PYTHON] * len(GA_PYTHON_STEPS)
    got = _first_column(content)
    return [] if got == want else [f"work-precision rows {got} != today's ladder {want}"]


def _example_rows():
    from harness.example import JOINTS, TOOLS
    return [j for j in JOINTS for _ in TOOLS] + [next(iter(JOINTS))]


def _needle_chaos_rows():
    needle_chaos = _benchmark("needle_chaos")
    return needle_chaos.row_labels()


def _transients_rows():
    from harness.input_transients import (LAUNCH_ROW, RESOLVED_CYCLE_ROW, RESOLVED_LAUNCH,
                                    RESOLVED_ONE_PASS, RESOLVED_ROWS)
    return (["ideal"] * 6 + ["lumped"] * 6 + [LAUNCH_ROW] * 3 + list(RESOLVED_ROWS)
            + [RESOLVED_CYCLE_ROW]
            + [label for label, _ in RESOLVED_LAUNCH]
            + [label for label, *_ in RESOLVED_ONE_PASS])


def _step_budget_rows():
    from harness.budget_use import SCENES
    return [label for label, *_ in SCENES]


MEASURED = {   # name: (rows today's code measures, the command that writes the block)
    "benchmarks/step_budget.py": (_step_budget_rows,
                                  "python -m benchmarks.step_budget --md FILE"),
    "make example": (_example_rows, "make example"),
    "benchmarks/transients.py": (_transients_rows, "python benchmarks/transients.py --md FILE"),
    "benchmarks/needle_chaos.py": (_needle_chaos_rows,
                                   "python benchmarks/needle_chaos.py --md FILE"),
    "bench: step cost": (_step_cost_rows, "tripod-thrust bench"),
    "bench: breakdown": (_breakdown_rows, "tripod-thrust bench"),
    "bench: work-precision": (None, "tripod-thrust bench"),
    "bench: side by side": (_side_by_side_rows, "tripod-thrust bench"),
    "bench: peers": (_peer_rows, "tripod-thrust bench --peer"),
    "make bench": (_fmu_speed_rows, "make bench"),
    "tripod-thrust stress": (_stress_rows, "tripod-thrust stress"),
}


def problems(path: Path, slow: bool = False) -> list[str]:
    """Why the generated blocks of one file are not current (empty: they are)."""
    out = []
    for name, content in blocks(path.read_text()):
        where = f"{path.relative_to(ROOT)}: block '{name}'"
        if name in EXACT or (slow and name in SLOW_EXACT):
            new = (EXACT.get(name) or SLOW_EXACT[name])().rstrip("\n") + "\n"
            if new != content:
                out.append(f"{where} is stale: run `make docs`")
        elif name in SLOW_EXACT:
            pass
        elif name in RUN:
            if _mask_wall(RUN[name]().rstrip("\n") + "\n") != _mask_wall(content):
                out.append(f"{where}: today's output differs (timings aside): run `make docs`")
        elif name in MEASURED:
            rows, cmd = MEASURED[name]
            if rows is None:
                out += [f"{where}: {p}" for p in _work_precision_check(content)]
            elif _first_column(content) != rows():
                out.append(f"{where}: rows {_first_column(content)} are not the cases today's "
                           f"code measures {rows()}: rerun `{cmd}` (make docs)")
        else:
            out.append(f"{where}: no generator registered in harness/docgen.py")
    return out


def update_exact(files=FILES) -> list[Path]:
    """Rewrite every exact block in the files; returns the files that changed."""
    changed = []
    for path in files:
        text = path.read_text()
        new = text
        for name, _ in blocks(text):
            gen = EXACT.get(name) or SLOW_EXACT.get(name) or RUN.get(name)
            if gen:
                new = replace(new, name, gen())
        if new != text:
            path.write_text(new)
            changed.append(path)
    return changed


def update_measured(bench_md: Path | None = None, stress_md: Path | None = None,
                    speed_md: Path | None = None, peers_md: Path | None = None,
                    example_md: Path | None = None, transients_md: Path | None = None,
                    chaos_md: Path | None = None, budget_md: Path | None = None,
                    files=FILES) -> list[Path]:
    """Write the measured blocks from one run's outputs: bench.md of `tripod-thrust bench`,
    stress.md of `tripod-thrust stress`, the table `make bench` prints, peers.md of
    `tripod-thrust bench --peer`, launch.md of `make example`, the tables of
    benchmarks/transients.py, benchmarks/needle_chaos.py and benchmarks/step_budget.py."""
    new_blocks = {}
    if budget_md:
        new_blocks["benchmarks/step_budget.py"] = Path(budget_md).read_text()
    if transients_md:
        new_blocks["benchmarks/transients.py"] = Path(transients_md).read_text()
    if chaos_md:
        new_blocks["benchmarks/needle_chaos.py"] = Path(chaos_md).read_text()
    if example_md:
        new_blocks["make example"] = Path(example_md).read_text()
    if peers_md:
        new_blocks["bench: peers"] = Path(peers_md).read_text()
    if bench_md:
        sections = re.split(r"^## .*$", Path(bench_md).read_text(), flags=re.M)
        titles = re.findall(r"^## (.*)$", Path(bench_md).read_text(), flags=re.M)
        by = dict(zip(titles, (s.strip("\n") for s in sections[1:])))
        for key, title in (("bench: step cost", "Cost per doStep"),
                           ("bench: breakdown", "Where one run goes"),
                           ("bench: work-precision", "Work-precision"),
                           ("bench: side by side", "Side by side")):
            found = [v for t, v in by.items() if t.startswith(title)]
            if found:      # (a run of only some sections, e.g. bench --step-cost)
                new_blocks[key] = found[0]
    if stress_md:
        new_blocks["tripod-thrust stress"] = Path(stress_md).read_text()
    if speed_md:
        new_blocks["make bench"] = Path(speed_md).read_text()
    changed = []
    for path in files:
        text = path.read_text()
        new = text
        for name, content in new_blocks.items():
            new = replace(new, name, content)
        if new != text:
            path.write_text(new)
            changed.append(path)
    return changed


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser(description="regenerate the generated blocks of the docs")
    ap.add_argument("--bench", metavar="BENCH.md", help="bench.md of one `tripod-thrust bench` run")
    ap.add_argument("--stress", metavar="STRESS.md", help="stress.md of `tripod-thrust stress`")
    ap.add_argument("--speed", metavar="SPEED.md", help="the table `make bench` printed")
    ap.add_argument("--peers", metavar="PEERS.md", help="peers.md of `tripod-thrust bench --peer`")
    ap.add_argument("--example", metavar="LAUNCH.md", help="launch.md of `make example`")
    ap.add_argument("--transients", metavar="FILE.md",
                    help="the table of `python benchmarks/transients.py --md FILE.md`")
    ap.add_argument("--chaos", metavar="FILE.md",
                    help="the tables of `python benchmarks/needle_chaos.py --md FILE.md`")
    ap.add_argument("--budget", metavar="FILE.md",
                    help="the table of `python -m benchmarks.step_budget --md FILE.md`")
    ap.add_argument("--check", action="store_true", help="only report stale blocks (exit 1)")
    a = ap.parse_args()
    if a.check:
        bad = [p for f in FILES for p in problems(f)]
        print("\n".join(bad) or "every generated block is current")
        sys.exit(1 if bad else 0)
    # measured blocks first: the README's speed summary is read from them
    for p in dict.fromkeys(update_measured(a.bench, a.stress, a.speed, a.peers, a.example,
                                             a.transients, a.chaos, a.budget)
                           + update_exact()):
        print("updated", p.relative_to(ROOT))
