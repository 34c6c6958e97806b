"""The environment switches that pick an execution path, read once, here (docs/architecture.md
names the paths).  Every one defaults to on; "0" turns it off, for debugging and comparison.

- TRIPOD_NUMBA=0: plain Python, no compiled kernel at all (the same source, slower).
- TRIPOD_NUMBA_CACHE: where numba's on-disk cache of the model goes (default: numba's own
  NUMBA_CACHE_DIR where that is set, else under ~/.cache).
"""
import os


def _on(name):
    return os.environ.get(name, "1") != "0"


NUMBA = _on("TRIPOD_NUMBA")
NUMBA_CACHE = os.environ.get("TRIPOD_NUMBA_CACHE") or os.environ.get("NUMBA_CACHE_DIR") or None
