"""The code's shape: small functions in the FMU sources, and layers that only point down
(benchmarks -> harness -> fmu_src -> reduced_model)."""
import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MAX_LINES = 80


def _functions(folder):
    for p in sorted((ROOT / folder).rglob("*.py")):
        for n in ast.walk(ast.parse(p.read_text())):
            if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)):
                yield p.relative_to(ROOT), n


def _imports(folder):
    for p in sorted((ROOT / folder).rglob("*.py")):
        for n in ast.walk(ast.parse(p.read_text())):
            if isinstance(n, ast.Import):
                yield p.relative_to(ROOT), [a.name.split(".")[0] for a in n.names]
            elif isinstance(n, ast.ImportFrom) and n.level == 0 and n.module:
                yield p.relative_to(ROOT), [n.module.split(".")[0]]


def test_no_function_in_fmu_src_longer_than_80_lines():
    long = [f"{p}:{n.lineno} {n.name} ({n.end_lineno - n.lineno + 1} lines)"
            for p, n in _functions("fmu_src") if n.end_lineno - n.lineno + 1 > MAX_LINES]
    assert not long, long


def test_layers_point_down():
    above = {"reduced_model": {"harness", "benchmarks", "tripod_model"},
             "fmu_src": {"harness", "benchmarks"},
             "harness": {"benchmarks"}}
    bad = [f"{p} imports {m}" for folder, banned in above.items()
           for p, mods in _imports(folder) for m in mods if m in banned]
    assert not bad, bad
