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


def test_no_integrator_imports_another():
    """The integrators as scipy keeps its ODE methods: genalpha.py and bdf2.py import the shared
    step library (steplib.py) and what derives a jump (oppoint.py), never each other; the
    library imports neither."""
    integrators = {"genalpha", "bdf2"}
    bad = []
    for name in integrators | {"steplib"}:
        p = ROOT / "fmu_src" / "tripod_model" / f"{name}.py"
        for n in ast.walk(ast.parse(p.read_text())):
            if isinstance(n, ast.ImportFrom) and n.level == 1:
                if (n.module or "") in integrators - {name}:
                    bad.append(f"{name}.py imports {n.module}")
    assert not bad, bad


MAX_MODULE_LINES = 500   # a module a newcomer reads in one sitting (the C binary aside)
MAX_PARAMS = 12          # more: the arguments belong in a record (layout.Work, Drive, ...)


def test_no_module_in_fmu_src_over_500_lines():
    big = [f"{p.relative_to(ROOT)} ({n} lines)" for p in sorted((ROOT / "fmu_src").rglob("*.py"))
           if (n := len(p.read_text().splitlines())) > MAX_MODULE_LINES]
    assert not big, big


def test_no_function_takes_more_than_12_parameters():
    many = []
    for folder in ("fmu_src", "reduced_model", "harness", "driveline", "benchmarks"):
        for p, n in _functions(folder):
            a = n.args
            k = (len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + (a.vararg is not None)
                 + (a.kwarg is not None))
            if k > MAX_PARAMS:
                many.append(f"{p}:{n.lineno} {n.name} ({k})")
    assert not many, many


def test_bearings_and_integrators_compared_by_name_only():
    # the values of `bearing` and `integrator` are named in reduced_model/scene.py (and as
    # P's floats in tripod_model/layout.py); a comparison with a bare number elsewhere hides
    # which bearing or integrator it means
    def names_switch(node):
        if isinstance(node, ast.Subscript):
            s = node.slice
            return (isinstance(s, ast.Constant) and s.value in ("bearing", "integrator")) or \
                (isinstance(s, ast.Name) and s.id in ("P_BEARING", "P_INTEGRATOR"))
        if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "get":
            return bool(node.args) and isinstance(node.args[0], ast.Constant) and \
                node.args[0].value in ("bearing", "integrator")
        return False
    bad = []
    for folder in ("fmu_src", "reduced_model", "harness", "driveline"):
        for p in sorted((ROOT / folder).rglob("*.py")):
            for n in ast.walk(ast.parse(p.read_text())):
                if isinstance(n, ast.Compare):
                    sides = [n.left, *n.comparators]
                    if any(names_switch(s) for s in sides) and any(
                            isinstance(s, ast.Constant) and isinstance(s.value, (int, float))
                            and not isinstance(s.value, bool) for s in sides):
                        bad.append(f"{p.relative_to(ROOT)}:{n.lineno}")
    assert not bad, bad


def test_every_contact_parameter_is_copied_derived_or_placed():
    """One name per parameter from the table to the kernel: each contact parameter is copied
    into P's slot named after it (roller_setup.COPIED, FLAGS), read where its slot is derived
    (kernel_params, needle_params: its T_ slot named in their source), or said to go elsewhere
    (ELSEWHERE); none twice, none left out."""
    import inspect
    from tripod_model import layout as K, roller_setup as RS
    copied = [RS.PARAM_NAMES[t] for _, t in RS.COPIED + RS.FLAGS]
    for slot, t in RS.COPIED + RS.FLAGS:   # the slot named after its parameter
        name = next(n for n in dir(K) if n.startswith("P_") and getattr(K, n) == slot)
        assert name == "P_" + RS.PARAM_NAMES[t].upper(), (name, RS.PARAM_NAMES[t])
    slots = {getattr(RS, n): n for n in dir(RS) if n.startswith("T_") and n != "T_LEN"}
    assert all(n == "T_" + RS.PARAM_NAMES[t].upper() for t, n in slots.items()), slots
    for names, fns in ((RS.DERIVED_FROM, (RS.kernel_params,)),
                       (RS.NEEDLE_ROW, (RS.needle_params, RS.row_bore_radius,
                                        RS.neighbour_distance))):
        src = "".join(inspect.getsource(f) for f in fns)
        for n in names:
            assert slots[RS.PARAM_NAMES.index(n)] in src, n
    every = copied + list(RS.DERIVED_FROM) + list(RS.NEEDLE_ROW) + list(RS.ELSEWHERE)
    assert len(every) == len(set(every)) and set(every) == set(RS.PARAM_NAMES), \
        sorted(set(RS.PARAM_NAMES) ^ set(every))


def test_no_two_modules_share_a_name():
    """One name, one module, across the project's folders (a reader, a traceback and an import
    by name each find one file)."""
    seen = {}
    for folder in ("fmu_src", "reduced_model", "driveline", "harness", "benchmarks", "tests"):
        for p in sorted((ROOT / folder).rglob("*.py")):
            if p.name != "__init__.py" and "__pycache__" not in p.parts:
                seen.setdefault(p.name, []).append(str(p.relative_to(ROOT)))
    twice = {name: paths for name, paths in seen.items() if len(paths) > 1}
    assert not twice, twice
