"""Before a run on several workers (make test: pytest -n 2), fill the compile caches once
(compile_caches.py): with empty caches each worker compiled the same kernels."""
import subprocess
import sys
from pathlib import Path


def pytest_sessionstart(session):
    config = session.config
    if hasattr(config, "workerinput") or not (config.getoption("numprocesses", None) or 0):
        return   # a worker (the controller filled them), or one process: it compiles as it goes
    subprocess.run([sys.executable, str(Path(__file__).with_name("compile_caches.py"))],
                   check=False)
