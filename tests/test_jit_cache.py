"""The compiled kernel's on-disk cache (tripod_model/jit.py): one folder per source version and
import name, shared by every copy of that version under that name (FMPy extracts an FMU to a
new folder each run; an FMU's package has a name of its own), so two versions on one machine
never overwrite each other's cache; and each of its functions compiled once for every caller."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _cache_path(pkg_parent: Path, env=None) -> str:
    code = ("import sys; sys.path.insert(0, sys.argv[1]); from tripod_model import kernel; "
            "print(kernel.run_substeps._cache._cache_path)")
    p = subprocess.run([sys.executable, "-c", code, str(pkg_parent)], capture_output=True,
                       text=True, timeout=120, check=True, env=env)
    return p.stdout.strip().splitlines()[-1]


def test_the_cache_goes_where_numba_cache_dir_or_tripod_numba_cache_says(tmp_path):
    """numba's own NUMBA_CACHE_DIR takes the model's cache too (a user who empties or moves
    numba's cache moves the model's); TRIPOD_NUMBA_CACHE, where set, goes first."""
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR",
                                                            "TRIPOD_NUMBA_CACHE")}
    numba_dir, ours = tmp_path / "numba", tmp_path / "ours"
    at = Path(_cache_path(ROOT / "fmu_src", dict(env, NUMBA_CACHE_DIR=str(numba_dir))))
    assert at.parent == numba_dir and at.name.startswith("tripod_model-")
    at = Path(_cache_path(ROOT / "fmu_src", dict(env, NUMBA_CACHE_DIR=str(numba_dir),
                                                 TRIPOD_NUMBA_CACHE=str(ours))))
    assert at.parent == ours
    # neither set: under the home folder's cache, one folder per Python version
    at = Path(_cache_path(ROOT / "fmu_src", env))
    assert at.parent.parent == Path.home() / ".cache" / "tripod-thrust"
    assert at.parent.name == "numba-py%d%d" % sys.version_info[:2]


def test_cache_folder_per_source_version(tmp_path):
    tree = _cache_path(ROOT / "fmu_src")
    same, changed = tmp_path / "same", tmp_path / "changed"
    for d in (same, changed):
        shutil.copytree(ROOT / "fmu_src" / "tripod_model", d / "tripod_model",
                        ignore=shutil.ignore_patterns("__pycache__"))
    k = changed / "tripod_model" / "kernel.py"
    k.write_text(k.read_text() + "\n# another version\n")
    assert _cache_path(same) == tree          # an extracted copy finds the tree's cache
    assert _cache_path(changed) != tree       # another version keeps its own
    assert Path(tree).name.startswith("tripod_model-")


@pytest.mark.slow   # (the kernel compiled from nothing: about 2 minutes)
def test_each_kernel_function_compiles_once_for_every_step(tmp_path):
    """A literal argument compiles a function once more for its value, with everything it
    calls: the needle loop for the split step's False and the one-system step's True, the
    kernel's advance for the floating spider's one substep.  In a fresh process with an empty
    cache, so every function this run needs is compiled and its signatures listed (a cached
    caller carries its callees' code, and they are then never loaded)."""
    code = ("import math\n"
            "from tripod_model.model import JointModel\n"
            "from tripod_model import kernel, needles\n"
            "for p in ({'bearing': 2}, {'bearing': 2, 'integrator': 1},\n"
            "          {'bearing': 1, 'n_rollers': 3, 'spider': 1}):\n"
            "    JointModel(p).step(1e-4, math.radians(8), 20 * math.pi, 4500.0)\n"
            "print(len(needles._contacts.signatures), len(needles.needle_forces.signatures),\n"
            "      len(kernel.advance.signatures),\n"
            "      sum('Literal' in str(s) for s in kernel.advance.signatures))\n")
    env = dict(os.environ, TRIPOD_NUMBA_CACHE=str(tmp_path))
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=1200, cwd=ROOT, env=env)
    assert p.returncode == 0, p.stderr[-3000:]
    # advance: once with the needle row's work, once without it (the other bearings)
    assert p.stdout.split() == ["1", "1", "2", "0"], p.stdout
