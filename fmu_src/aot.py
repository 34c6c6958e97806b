"""Compile a model's functions ahead of time into object code for the FMUs' binaries
(native_fmu.py links them with the native FMI layer).

numba compiles the functions in a fresh process (a generic x86-64 CPU, so the binary runs on
any machine the FMU goes to; only their LLVM IR, nothing for the host: _EMIT_FUNCTIONS) and
llvmlite emits them as position-independent object code; the binary links them with
native/aot_stubs.c (the symbols of numba's error path) and libm.  For win64 the same IR is
retargeted to x86_64-w64-windows-gnu and linked by mingw-w64 (TARGETS).  The compiled objects
are kept by the content of their sources (AOT_CACHE, cache_key).
"""
from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

FMU_SRC = Path(__file__).resolve().parent
STUBS = FMU_SRC / "native" / "aot_stubs.c"
# compiled objects kept by the content of what compiles them (cache_key): a fresh clone of the
# same sources on this machine reuses them, as numba's own cache (tripod_model/jit.py) does;
# TRIPOD_AOT_CACHE names another folder, or "off"
AOT_CACHE = os.environ.get("TRIPOD_AOT_CACHE") or str(
    Path.home() / ".cache" / "tripod-thrust" / "aot")
# the packages a compiled model imports (the emitting process's path: the project and fmu_src)
SOURCES = (FMU_SRC, FMU_SRC.parent / "reduced_model", FMU_SRC.parent / "driveline")

# per target: the LLVM triple numba's IR is retargeted to (None: the host's), the C compiler
# that links it, the library's name and the libraries it may import
TARGETS = {
    "linux64": {"triple": None, "cc": None},
    # mingw-w64: the -gnu triple, whose stack probe (___chkstk_ms) libgcc provides; linked with
    # -static-libgcc so the DLL imports only what every Windows has
    "win64": {"triple": "x86_64-w64-windows-gnu", "cc": "x86_64-w64-mingw32-gcc",
              "imports": ("KERNEL32.dll", "msvcrt.dll")},
}

# a module's C functions (its factory returns {name: numba cfunc}), compiled once, each emitted
# as an object per target (out/TARGET/NAME.o)
_EMIT_FUNCTIONS = r"""
import importlib, json, os, sys
import llvmlite.binding as llvm
from numba.core import caching, codegen as cg
out, spec, targets = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
module, factory = spec.split(":")
# Only the entry points' IR is wanted.  numba would optimise every function's module with all
# its callees linked in and generate its machine code for this CPU, again for each caller: half
# the compile.  Here a library keeps its function passes only; the entry points' linked
# modules take the module passes once (below), and nothing is generated or cached for the host.
module_passes = cg.CPUCodeLibrary._optimize_final_module
cg.CPUCodeLibrary._optimize_final_module = lambda self: None
cg.JITCodeLibrary._finalize_specific = lambda self: None
cg.JITCodeLibrary.get_pointer_to_function = lambda self, name: self._ensure_finalized() or 0
cg.JITCPUCodegen._add_module = lambda self, module: None
cg.JITCPUCodegen.set_env = lambda self, name, env: None
caching.Cache.save_overload = lambda self, sig, data: None
functions = getattr(importlib.import_module(module), factory)()
for fn in functions.values():
    module_passes(fn._library)
llvm.initialize_all_targets()
llvm.initialize_all_asmprinters()
symbols = {name: fn.native_name for name, fn in functions.items()}
for target, triple in targets.items():
    tm = (llvm.Target.from_triple(triple) if triple else llvm.Target.from_default_triple()
          ).create_target_machine(cpu="generic", features="", opt=3, reloc="pic")
    os.makedirs(f"{out}/{target}", exist_ok=True)
    for name, fn in functions.items():
        mod = llvm.parse_assembly(fn._library.get_llvm_str())
        if triple:   # numba stamps the host's triple and data layout on its IR: the target's
            mod.triple = triple
            mod.data_layout = str(tm.target_data)
        mod.verify()
        open(f"{out}/{target}/{name}.o", "wb").write(tm.emit_object(mod))
json.dump(symbols, open(f"{out}/symbols.json", "w"))
"""


def cache_key(spec: str, targets, sources=SOURCES) -> str:
    """What decides the objects compile_functions emits: the spec and targets, the emitting
    script, Python's, numba's and llvmlite's versions, and every .py file under ``sources``
    (path and content)."""
    from importlib.metadata import version
    h = hashlib.sha256()
    for part in (spec, json.dumps(list(targets)), _EMIT_FUNCTIONS, sys.version,
                 version("numba"), version("llvmlite"),
                 json.dumps({t: TARGETS[t]["triple"] for t in targets})):
        h.update(part.encode() + b"\0")
    for top in sources:
        for f in sorted(Path(top).rglob("*.py")):
            h.update(f"{Path(top).name}/{f.relative_to(top)}".encode() + b"\0" + f.read_bytes())
    return h.hexdigest()[:32]


def _symbols(dest: Path, targets) -> dict:
    symbols = json.loads((dest / "symbols.json").read_text())
    return {t: {name: (dest / t / f"{name}.o", sym) for name, sym in symbols.items()}
            for t in targets}


def compile_functions(spec: str, dest: Path, targets=("linux64",)) -> dict:
    """Objects dest/TARGET/NAME.o of the C functions module:factory returns (numba cfuncs,
    compiled once in a fresh process for a generic x86-64 CPU, emitted for each target);
    returns {TARGET: {NAME: (object path, its symbol)}}.  Taken from AOT_CACHE when the same
    sources compiled them before (cache_key)."""
    dest.mkdir(parents=True, exist_ok=True)
    cached = None if AOT_CACHE == "off" else Path(AOT_CACHE) / cache_key(spec, targets)
    if cached is not None and (cached / "symbols.json").exists():
        shutil.copytree(cached, dest, dirs_exist_ok=True)
        return _symbols(dest, targets)
    with tempfile.TemporaryDirectory() as tmp:
        # empty caches (the LLVM module is then at hand), a generic x86-64 CPU, SVML off (its
        # __svml_* functions exist in no Windows C runtime)
        env = dict(os.environ, NUMBA_CACHE_DIR=tmp, TRIPOD_NUMBA_CACHE=tmp, TRIPOD_NUMBA="1",
                   NUMBA_CPU_NAME="generic", NUMBA_CPU_FEATURES="", NUMBA_DISABLE_INTEL_SVML="1",
                   PYTHONPATH=os.pathsep.join((str(FMU_SRC.parent), str(FMU_SRC))))
        triples = {t: TARGETS[t]["triple"] or "" for t in targets}
        p = subprocess.run([sys.executable, "-c", _EMIT_FUNCTIONS, str(dest), spec,
                            json.dumps(triples)], env=env, capture_output=True, text=True,
                           timeout=1800)
    if p.returncode != 0:
        raise RuntimeError(f"compiling {spec} failed:\n{p.stderr[-3000:]}")
    if cached is not None:
        _keep(dest, cached)
    return _symbols(dest, targets)


def _keep(dest: Path, cached: Path) -> None:
    """dest's objects kept at cached, whole or not at all (a rename within the cache's folder;
    nothing where another build kept them first or the folder is not writable)."""
    try:
        cached.parent.mkdir(parents=True, exist_ok=True)
        part = Path(tempfile.mkdtemp(dir=cached.parent))
    except OSError:
        return
    try:
        shutil.copytree(dest, part, dirs_exist_ok=True)
        os.rename(part, cached)
    except OSError:
        shutil.rmtree(part, ignore_errors=True)


def compiler(target: str) -> str:
    """The C compiler that links for ``target`` (RuntimeError naming the package where the
    cross compiler is missing)."""
    import shutil
    cc = TARGETS[target]["cc"]
    if cc is None:
        return os.environ.get("CC") or "cc"
    if shutil.which(cc) is None:
        raise RuntimeError(f"{cc} is needed to build for {target} (as root: apt-get install "
                           "gcc-mingw-w64-x86-64; make cross-tools)")
    return cc


def check_imports(lib: Path, target: str) -> None:
    """RuntimeError if the Windows library imports more than every Windows has."""
    allowed = TARGETS[target].get("imports")
    if allowed:
        bad = sorted(set(dll_imports(lib)) - set(allowed))
        if bad:
            raise RuntimeError(f"{lib.name} imports {bad}, beyond {list(allowed)}")


def dll_imports(lib: Path) -> list[str]:
    """The DLLs a Windows library imports (its import table, read with mingw's objdump)."""
    p = subprocess.run(["x86_64-w64-mingw32-objdump", "-p", str(lib)], capture_output=True,
                       text=True, check=True)
    return [ln.split("DLL Name:")[1].strip() for ln in p.stdout.splitlines() if "DLL Name:" in ln]
