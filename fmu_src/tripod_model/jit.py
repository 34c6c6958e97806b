"""numba when a scene needs it and it is installed; plain Python otherwise (same source).

Set TRIPOD_NUMBA=0 to force plain Python (debugging, or a host without numba).
"""
import os

_ENABLED = os.environ.get("TRIPOD_NUMBA", "1") != "0"
try:
    if not _ENABLED:
        raise ImportError
    import numba as _nb
    HAVE_NUMBA = True
except ImportError:   # numba is optional: the kernel runs as Python, slower
    _nb = None
    HAVE_NUMBA = False


def njit(fn):
    """numba.njit(cache=True) if available, else the function unchanged."""
    if HAVE_NUMBA:
        return _nb.njit(cache=True, nogil=True)(fn)
    return fn
