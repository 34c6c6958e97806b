"""The prebuilt kernel: kernel.step compiled ahead of time into a shared library when the FMU is
built (fmu_src/aot.py), loaded here with ctypes.  A scene without resolved needles then steps
through it and never imports numba: a fresh process saves numba's import and start-up (about
0.6 s of a 1.3 s `fmpy simulate`).  The library is used only when it was built from exactly
these sources (their content hash); otherwise, or with TRIPOD_AOT=0, numba compiles the
kernel (TRIPOD_NUMBA=0: plain Python, neither).
"""
import ctypes
import hashlib
import re
import json
import os

from reduced_model import switches

_DIR = os.path.dirname(os.path.abspath(__file__))
LIB, META = "_step.so", "_step.json"     # next to this file, in the FMU only
_HASH = None
_STEP = False   # not looked up yet


# modules of the reduced model the compiled kernel takes in (kernel.py: the housing frame and
# Fz_mod; oppoint.py, compiled into the step: v_st, the pressing load, the slip amplitudes)
_ELSEWHERE = ("reduced_model.housing", "reduced_model.thrust", "reduced_model.friction",
              "reduced_model.scene", "reduced_model.sliding")


def _compiled_elsewhere():
    """Source files of _ELSEWHERE under this package's import name (reduced_model in the
    source tree, PKG.reduced_model in an FMU), without importing them."""
    import importlib.util
    base = __name__.rpartition(".")[0].rpartition(".")[0]
    paths = []
    for mod in _ELSEWHERE:
        spec = importlib.util.find_spec((base + "." if base else "") + mod)
        if spec is not None and spec.origin:
            paths.append(spec.origin)
    return paths


def source_hash() -> str:
    """Content hash of every .py file of this package and of _ELSEWHERE (the same in every
    extracted copy, and in the source tree: the FMU's build makes its imports of the other
    bundled packages relative, so the leading dots of imports are left out)."""
    global _HASH
    if _HASH is None:
        h = hashlib.sha256()
        files = [os.path.join(_DIR, n) for n in sorted(os.listdir(_DIR)) if n.endswith(".py")]
        files += _compiled_elsewhere()
        for path in files:
            with open(path, "rb") as f:
                text = re.sub(rb"^(\s*from )\.+", rb"\1", f.read(), flags=re.M)
            h.update(os.path.basename(path).encode() + b"\0" + text)
        _HASH = h.hexdigest()
    return _HASH


def step_function():
    """The prebuilt step as a ctypes function (kernel.step's C signature: int32_t f(double **)),
    or None."""
    global _STEP
    if _STEP is False:
        _STEP = _load()
    return _STEP


def _load():
    if not switches.AOT:
        return None   # (TRIPOD_NUMBA=0 asks for plain Python: no compiled kernel at all)
    try:
        with open(os.path.join(_DIR, META)) as f:
            meta = json.load(f)
        if meta["hash"] != source_hash():
            return None
        fn = ctypes.CDLL(os.path.join(_DIR, LIB))[meta["symbol"]]
    except (OSError, KeyError, ValueError, AttributeError):
        return None
    fn.restype = ctypes.c_int32
    fn.argtypes = [ctypes.c_void_p]   # kernel.step's one argument: its arrays' addresses
    return fn


def address(fn) -> int:
    """The C address of a ctypes function (what the native layer calls)."""
    return ctypes.cast(fn, ctypes.c_void_p).value
