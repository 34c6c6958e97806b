"""Build the prebuilt kernel (tripod_model/native.py): kernel.step compiled once, ahead of time,
into a shared library that goes into the contact FMU, so a scene without resolved needles runs
without numba at run time.

numba compiles the step in a fresh process (an empty cache, so the LLVM module is at hand; a
generic x86-64 CPU, so the library runs on any machine the FMU goes to), llvmlite emits it as
position-independent object code, and the C compiler links it with native/aot_stubs.c (the
symbols of numba's error path) and libm.  About 20 s.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

FMU_SRC = Path(__file__).resolve().parent
STUBS = FMU_SRC / "native" / "aot_stubs.c"

_EMIT = r"""
import json, sys
import llvmlite.binding as llvm
import numba
from tripod_model import kernel, native
llvm.initialize_native_target()
llvm.initialize_native_asmprinter()
mod = llvm.parse_assembly(kernel.c_step()._library.get_llvm_str())
mod.verify()
tm = llvm.Target.from_default_triple().create_target_machine(cpu="generic", features="",
                                                             opt=3, reloc="pic")
open(sys.argv[1], "wb").write(tm.emit_object(mod))
json.dump({"symbol": kernel.c_step().native_name, "hash": native.source_hash(),
           "numba": numba.__version__, "cpu": "generic"}, open(sys.argv[2], "w"))
"""


def build_step_library(dest: Path) -> tuple[Path, Path]:
    """dest/_step.so and dest/_step.json (native.LIB, native.META) from today's sources."""
    if sys.platform != "linux":
        raise RuntimeError(f"the prebuilt kernel builds on Linux only, not {sys.platform}")
    dest.mkdir(parents=True, exist_ok=True)
    lib, meta = dest / "_step.so", dest / "_step.json"
    with tempfile.TemporaryDirectory() as tmp:
        obj = Path(tmp) / "step.o"
        env = dict(os.environ, TRIPOD_NUMBA_CACHE=tmp, NUMBA_CPU_NAME="generic",
                   NUMBA_CPU_FEATURES="", TRIPOD_NUMBA="1", PYTHONPATH=str(FMU_SRC))
        p = subprocess.run([sys.executable, "-c", _EMIT, str(obj), str(meta)], env=env,
                           capture_output=True, text=True, timeout=900)
        if p.returncode != 0:
            raise RuntimeError(f"compiling the prebuilt kernel failed:\n{p.stderr[-3000:]}")
        cc = os.environ.get("CC") or "cc"
        cmd = cc.split()[:1] + ["-shared", "-fPIC", "-O2", str(obj), str(STUBS), "-o", str(lib),
                                "-lm"]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            raise RuntimeError(f"linking the prebuilt kernel failed:\n{p.stderr}")
    json.loads(meta.read_text())   # written whole
    return lib, meta
