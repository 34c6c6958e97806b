"""Where the FMUs are and how to (re)build them: a thin wrapper over fmu_src/build.py."""
from __future__ import annotations

import importlib.util
from functools import lru_cache
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FMU_NAMES = ("TripodRoller", "TripodRollerAnalytic")


@lru_cache(maxsize=1)
def builder():
    """fmu_src/build.py as a module (fmu_src is not a package: it is what goes into the FMUs)."""
    spec = importlib.util.spec_from_file_location("tripod_fmu_build", ROOT / "fmu_src" / "build.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def ensure_fmu(name: str = "TripodRoller", force: bool = False) -> Path:
    """Path of build/<name>.fmu, built first when missing, stale or forced."""
    return builder().build(name, force=force)


def check_fmu(fmu: str | Path) -> tuple[bool, str]:
    """Whether ``fmu`` came from this checkout: this checkout's FMU of its model (built when
    missing or stale) holds the same files with the same bytes (the build is reproducible:
    fmu_src/build.py content_guid).  Returns (same, one line saying so)."""
    import zipfile
    from xml.etree import ElementTree as ET
    try:
        with zipfile.ZipFile(fmu) as z:
            theirs = {i.filename: z.read(i.filename) for i in z.infolist()}
    except (OSError, zipfile.BadZipFile) as e:
        raise ValueError(f"{fmu}: not an FMU ({e})") from None
    if "modelDescription.xml" not in theirs:
        raise ValueError(f"{fmu}: not an FMU (no modelDescription.xml)")
    root = ET.fromstring(theirs["modelDescription.xml"])
    name = root.get("modelName")
    if name not in FMU_NAMES + ("Powertrain",):
        return False, f"{fmu}: model {name!r} is none of this project's FMUs"
    ours_path = ensure_fmu(name)
    with zipfile.ZipFile(ours_path) as z:
        ours = {i.filename: z.read(i.filename) for i in z.infolist()}
    differ = sorted(k for k in set(ours) | set(theirs) if ours.get(k) != theirs.get(k))
    guid = root.get("guid")
    if not differ:
        return True, f"{fmu}: built from this checkout (GUID {guid}, byte for byte {ours_path})"
    ours_guid = ET.fromstring(ours["modelDescription.xml"]).get("guid")
    return False, (f"{fmu}: not from this checkout: {', '.join(differ)} differ (GUID {guid}, "
                   f"this checkout's {ours_guid})")
