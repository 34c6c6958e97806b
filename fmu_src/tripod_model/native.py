"""The content hash of the contact model's sources, without importing numba: what numba's
on-disk cache is keyed on (jit.py), so every copy of the same sources shares one cache.
"""
import hashlib
import re
import os

_DIR = os.path.dirname(os.path.abspath(__file__))
_HASH = None


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
    """Content hash of every .py file of this package and of _ELSEWHERE (the leading dots of
    imports left out, so a copy whose imports are made relative hashes alike)."""
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
