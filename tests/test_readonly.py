"""An FMU extracted to a read-only folder, run by a user whose home and cache folders cannot be
written, with the needle-resolved bearing: it runs, and says nothing about caches.  The FMU (compiled,
no Python) writes nothing anywhere.

Root writes through file permissions, so the folder is made read-only by a bind mount in a
private mount namespace (unshare -m); where that is not allowed the test says so and skips."""
import json
import shutil
import subprocess
import sys
import zipfile

import pytest

from harness.fmus import ensure_fmu

_RUN = r'''
import json, math, sys
from fmpy import simulate_fmu
logs = []
r = simulate_fmu(sys.argv[1], stop_time=0.002, output_interval=1e-4,
                 start_values={"bearing": 2}, debug_logging=True,
                 logger=lambda c, n, s, cat, msg: logs.append((s, msg.decode())))
print(json.dumps({"finite": all(math.isfinite(v) for v in r["Fz"]), "n": len(r),
                  "problems": [m for s, m in logs if s >= 1]}))
'''


def test_read_only_fmu_folder_and_unwritable_home(tmp_path):
    if not shutil.which("unshare"):
        pytest.skip("needs unshare (util-linux) to make a read-only folder as root")
    d = tmp_path / "fmu"
    with zipfile.ZipFile(ensure_fmu("TripodRoller")) as z:
        z.extractall(d)
    blocker = tmp_path / "a-file"           # a folder under a regular file cannot be created
    blocker.write_text("")
    probe = subprocess.run(["unshare", "-m", "sh", "-c",
                            f"mount --bind {d} {d} && mount -o remount,bind,ro {d} && "
                            f"! touch {d}/x 2>/dev/null"], capture_output=True, text=True)
    if probe.returncode != 0:
        pytest.skip(f"no private read-only bind mount here: {probe.stderr.strip()[:200]}")
    script = tmp_path / "run.py"
    script.write_text(_RUN)
    env = {"HOME": str(blocker / "home"), "XDG_CACHE_HOME": str(blocker / "cache"),
           "TRIPOD_NUMBA_CACHE": str(blocker / "numba"), "PATH": "/usr/bin:/bin"}
    p = subprocess.run(["unshare", "-m", "sh", "-c",
                        f"mount --bind {d} {d} && mount -o remount,bind,ro {d} && "
                        f'exec "$0" "$1" "$2"', sys.executable, str(script), str(d)],
                       capture_output=True, text=True, timeout=600, env=env)
    assert p.returncode == 0, p.stderr[-3000:]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    assert r["finite"] and r["n"] == 21
    assert not r["problems"], r["problems"]
    assert "Traceback" not in p.stderr and "locator" not in p.stderr, p.stderr[-2000:]
    assert "resources" not in [q.name for q in d.iterdir()]   # (nothing but the binaries)
