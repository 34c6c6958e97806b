"""numba when a scene needs it and it is installed; plain Python otherwise (same source).

Set TRIPOD_NUMBA=0 to force plain Python (debugging, or a host without numba).

numba keys its on-disk cache on the source file's folder.  A cache locator keyed on the
package's import name and the content hash of its sources keeps one cache for every copy of the
same version (a fresh clone, a test's copy of the tree):
~/.cache/tripod-thrust/numba-pyXY/<name>-<hash>, or under TRIPOD_NUMBA_CACHE (or numba's
NUMBA_CACHE_DIR) when set.
"""
import os
import sys
import types

from reduced_model import switches
from .native import source_hash   # the sources' content hash (no numba there)

ENABLED = switches.NUMBA    # False: plain Python on purpose
try:
    if not ENABLED:
        raise ImportError
    import numba as _nb
    HAVE_NUMBA = True
except ImportError:   # numba is optional: the kernel runs as Python, slower
    _nb = None
    HAVE_NUMBA = False

CACHE_DIR = switches.NUMBA_CACHE or os.path.join(
    os.path.expanduser("~"), ".cache", "tripod-thrust",
    f"numba-py{sys.version_info[0]}{sys.version_info[1]}")


# this package's import name (tripod_model); its functions, and those of the reduced model it
# compiles, are ours
_PKG = __name__.rpartition(".")[0]
_OURS = tuple(_PKG.rpartition(".")[0] + "." + n if "." in _PKG else n
              for n in ("tripod_model", "reduced_model"))


def _ours(py_func) -> bool:
    return (getattr(py_func, "__module__", "") or "").startswith(_OURS)


def _install_stable_locator():
    """Put a path-independent cache locator first for this package's functions, and, last, a
    per-process temporary cache for any of ours no other locator takes (a read-only FMU folder
    with an unwritable home, or a source file already deleted: FMPy removes an extraction after
    its run, while its modules stay loaded): compiled then, not cached across processes."""
    try:
        from numba.core import caching as c
    except ImportError:
        return
    if any(getattr(k, "_tripod", None) == _PKG for k in c.CacheImpl._locator_classes):
        return

    class _StableLocator(c._SourceFileBackedLocatorMixin, c._CacheLocator):
        _tripod = _PKG

        def __init__(self, py_func, py_file):
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            # a folder per source version: two versions of the FMU on one machine (a release
            # beside its successor) would otherwise overwrite each other's index and recompile
            # (about 11 s) on every alternate run; and per import name (the cache refers to
            # its modules by name: the source tree's and an FMU's package differ)
            self._cache_path = os.path.join(CACHE_DIR, _PKG + "-" + source_hash()[:16])

        def get_cache_path(self):
            return self._cache_path

        def get_source_stamp(self):
            # numba stamps only the function's own file; a kernel calls into other files of
            # the package (needles.py, linalg.py), so stamp the whole package's source
            return source_hash()

        @classmethod
        def from_function(cls, py_func, py_file):
            if (getattr(py_func, "__module__", "") or "").rpartition(".")[0] != _PKG:
                return None
            self = cls(py_func, py_file)   # (the file itself may be gone: the stamp is ours)
            try:
                self.ensure_cache_path()
            except OSError:
                return None
            return self

    class _TempLocator(_StableLocator):
        _tripod = _PKG + " (temporary)"
        _dir = None

        def __init__(self, py_func, py_file):
            super().__init__(py_func, py_file)
            if _TempLocator._dir is None:
                import tempfile
                _TempLocator._dir = tempfile.mkdtemp(prefix="tripod-thrust-numba-")
            self._cache_path = _TempLocator._dir

        @classmethod
        def from_function(cls, py_func, py_file):
            if not _ours(py_func):
                return None
            self = cls(py_func, py_file)
            try:
                self.ensure_cache_path()
            except OSError:
                return None
            return self

    c.CacheImpl._locator_classes.insert(0, _StableLocator)
    c.CacheImpl._locator_classes.append(_TempLocator)


if HAVE_NUMBA:
    try:
        _install_stable_locator()
    except Exception:   # numba internals moved: fall back to its own (per-folder) cache
        pass


def _compiled(fn, **options):
    try:
        return _nb.njit(cache=True, nogil=True, **options)(fn)
    except RuntimeError:   # "cannot cache function ...: no locator available": nowhere to
        return _nb.njit(nogil=True, **options)(fn)   # write (read-only everywhere): no cache


def njit(fn):
    """numba.njit(cache=True) if available, else the function unchanged."""
    if HAVE_NUMBA:
        return _compiled(fn)
    return fn


def inline(fn):
    """njit, inlined into its callers at numba's IR level: for the small named pieces of the
    hot kernels (a real call passing arrays costs reference counting on every argument; the
    needle contacts run 1000 times a substep)."""
    if HAVE_NUMBA:
        return _compiled(fn, inline="always")
    return fn


def compiled_copies(module, names, given=None):
    """numba versions of ``module``'s functions ``names`` (its own and those it imported), the
    module's own calling each other compiled, in a namespace; the module itself is untouched,
    so its plain functions stay plain (oppoint: the model derives an operating point without
    numba, and the kernel compiles the same source into the step).  ``given``: callees
    compiled elsewhere, by name (another module's compiled copies)."""
    if not HAVE_NUMBA:
        return types.SimpleNamespace(**{n: getattr(module, n) for n in names})
    g = dict(vars(module))   # the copies' globals: the module's, with the compiled callees
    g.update(given or {})
    done = {}
    for n in names:
        f = g[n]
        own = getattr(f, "__module__", None) == module.__name__
        # an imported function calls the copies compiled before it, in its own module's globals
        fg = g if own else {**f.__globals__, **done}
        if own or done:
            f = types.FunctionType(f.__code__, fg, f.__name__, f.__defaults__, f.__closure__)
            f.__qualname__ = g[n].__qualname__
        g[n] = done[n] = njit(f)
    return types.SimpleNamespace(**{n: g[n] for n in names})
