"""The contact kernel cross-compiled for Windows (fmu_src/aot.py, target win64: numba's IR
retargeted to x86_64-w64-windows-gnu, linked by mingw-w64) runs under wine64 as the Linux
library does: the same saved state stepped by the same driver source (tests/c_host/
step_driver.c), built for each platform, from a folder whose name is not ASCII and has a space.

Wine is a smoke test, not Windows.  The two C runtimes' libms may differ in the last bit (sin,
cos, tanh, pow), so the outputs are held to 1e-9 of each output's scale over the run, or to
twice what a 4-ulp change of the whirl angles grows into over the same steps (the cause of a
larger difference: last bits of the trigonometry, carried on by the rollers' rocking), rather
than to the bit."""
import math
import os
import shutil
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "fmu_src"))
import aot  # noqa: E402
import build  # noqa: E402
from tripod_model import layout as K  # noqa: E402
from tripod_model.model import JointModel  # noqa: E402

DRIVER = ROOT / "tests" / "c_host" / "step_driver.c"
WINE = "/usr/lib/wine/wine64"      # Debian's loader when only wine64 is installed
STEPS = 300
SCENES = {   # name: parameters, theta [deg], torque [N m]
    "ideal-three": ({"n_rollers": 3}, 8.0, 300.0),
    "lumped-one": ({"bearing": 1}, 25.0, 3000.0),
}


def _tools():
    missing = [t for t in ("x86_64-w64-mingw32-gcc", "x86_64-w64-mingw32-objdump")
               if shutil.which(t) is None] + ([] if os.path.exists(WINE) else [WINE])
    assert not missing, (f"{missing} missing: `make test` installs them as root (apt-get "
                         "install gcc-mingw-w64-x86-64 wine64)")


@pytest.fixture(scope="module")
def libraries(tmp_path_factory):
    """Both kernels and both drivers, the Windows pair under a folder named 'jürgen x'."""
    _tools()
    lin_lib, lin_meta = build.prebuilt_kernel()
    win_lib, win_meta = build.prebuilt_kernel(target="win64")
    where = tmp_path_factory.mktemp("w64") / "jürgen x"
    where.mkdir()
    shutil.copy(win_lib, where / win_lib.name)
    cc = os.environ.get("CC") or "cc"
    subprocess.run([cc, "-O2", "-o", str(where / "step_driver"), str(DRIVER), "-ldl"],
                   check=True)
    subprocess.run(["x86_64-w64-mingw32-gcc", "-O2", "-static-libgcc", "-o",
                    str(where / "step_driver.exe"), str(DRIVER), "-lshell32"], check=True)
    import json
    return {"linux": (lin_lib, json.loads(lin_meta.read_text())["symbol"]),
            "win64": (where / win_lib.name, json.loads(win_meta.read_text())["symbol"]),
            "dir": where}


def _arrays_file(path, params, theta_deg, torque, ulps=0):
    """A scene's kernel arrays after 20 steps through the model, at layout's FA_ places (the
    output array fresh), written for step_driver; ulps: the rollers' whirl angles (the
    argument of every sine and cosine of the driven motion) moved by that many ulps."""
    m = JointModel(dict(params))
    theta = theta_deg * math.pi / 180
    for _ in range(20):
        m.step(1e-4, theta, 2 * math.pi * 10, 0.0, torque)
    arrays = [a.copy() for a in m.fast_arrays()]
    arrays.insert(K.FA_OUT, np.zeros(K.N_OUT))
    arrays[K.FA_Y].reshape(-1, K.Y_LEN)[:, K.Y_X] *= 1 + ulps * 2.0 ** -52
    with open(path, "wb") as f:
        f.write(b"TTARR1\0\0" + struct.pack("<ii", len(arrays), K.FA_OUT))
        for a in arrays:
            a = np.ascontiguousarray(a, dtype="<f8").ravel()
            f.write(struct.pack("<q", a.size) + a.tobytes())


def _run(cmd, out, env=None):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == 0, p.stderr[-2000:]
    raw = Path(out).read_bytes()
    rec = 4 + 8 * K.N_OUT
    assert len(raw) == STEPS * rec
    codes = [struct.unpack_from("<i", raw, k * rec)[0] for k in range(STEPS)]
    outs = np.array([np.frombuffer(raw, "<f8", K.N_OUT, k * rec + 4) for k in range(STEPS)])
    return codes, outs


def test_the_dll_imports_only_what_every_windows_has(libraries):
    assert sorted(aot.dll_imports(libraries["win64"][0])) == ["KERNEL32.dll", "msvcrt.dll"]


@pytest.mark.parametrize("scene", sorted(SCENES))
def test_the_win64_kernel_under_wine_steps_as_the_linux_one(libraries, scene, tmp_path):
    d = libraries["dir"]
    arrays = tmp_path / f"{scene}.bin"
    _arrays_file(arrays, *SCENES[scene])
    lin_lib, lin_sym = libraries["linux"]
    codes_l, out_l = _run([str(d / "step_driver"), str(lin_lib), lin_sym, str(arrays),
                           str(STEPS), str(tmp_path / "lin.out")], tmp_path / "lin.out")
    win_lib, win_sym = libraries["win64"]
    env = dict(os.environ, WINEPREFIX=str(build.BUILD / "wine-prefix"), WINEDEBUG="-all")
    # the paths as a Windows host hands them: drive Z: is the Linux root under wine
    win = lambda p: "Z:" + str(p).replace("/", "\\")  # noqa: E731
    codes_w, out_w = _run([WINE, str(d / "step_driver.exe"), win(win_lib), win_sym,
                           win(arrays), str(STEPS), win(tmp_path / "win.out")],
                          tmp_path / "win.out", env)
    assert set(codes_l) == {1} and codes_w == codes_l
    # what a few ulps grow into in this scene: the same Linux run with the whirl angles 4 ulps
    # off.  The libms' last bits differ at a few steps (the first at step 45 of the
    # three-roller scene here: 8.8e-10 of Fz_3's scale by step 300, against 1.8e-9 from the
    # 4 ulps) and the rollers' rocking carries such a difference on as it carries this one
    _arrays_file(arrays, *SCENES[scene], ulps=4)
    _, out_p = _run([str(d / "step_driver"), str(lin_lib), lin_sym, str(arrays), str(STEPS),
                     str(tmp_path / "lin4.out")], tmp_path / "lin4.out")
    scale = np.abs(out_l).max(axis=0)
    spread = np.abs(out_p - out_l).max(axis=0)
    dev = np.abs(out_w - out_l).max(axis=0)
    tol = np.maximum(1e-9 * scale, 2 * spread)
    assert (dev <= tol).all(), {n: (d, t) for n, d, t in zip(K.OUTPUT_NAMES, dev, tol) if d > t}
    # (a run that moved: the thrust is there)
    assert np.abs(out_l[:, K.OUTPUT_NAMES.index("Fz")]).max() > 1.0
