"""Build the FMUs into build/: pythonfmu, then units, ranges and display units added to
modelDescription.xml from the parameter table (pythonfmu has no unit attributes)."""
from __future__ import annotations

import shutil
import sys
import tempfile
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

ROOT = Path(__file__).resolve().parents[1]
FMU_SRC = ROOT / "fmu_src"
BUILD = ROOT / "build"
# what goes into resources/: the model packages (numpy/scipy/numba come from the host)
PACKAGES = (FMU_SRC / "tripod_model", ROOT / "reduced_model")
SLAVES = {"TripodRoller": FMU_SRC / "TripodRoller.py",
          "TripodRollerAnalytic": FMU_SRC / "TripodRollerAnalytic.py"}
# the analytic FMU needs the reduced model only
KIT = FMU_SRC / "slavekit.py"      # what both slaves share
BUNDLE = {"TripodRoller": PACKAGES + (KIT,),
          "TripodRollerAnalytic": (ROOT / "reduced_model", KIT)}


def _sources(name):
    files = [SLAVES[name], Path(__file__)]
    for pkg in BUNDLE[name]:
        files += list(pkg.rglob("*.py")) if pkg.is_dir() else [pkg]
    return files


def fmu_path(name="TripodRoller") -> Path:
    return BUILD / f"{name}.fmu"


def is_stale(name="TripodRoller") -> bool:
    """True when the FMU is missing or older than any of its sources."""
    f = fmu_path(name)
    if not f.exists():
        return True
    t = f.stat().st_mtime
    return any(s.stat().st_mtime > t for s in _sources(name))


def _units_and_ranges(xml: bytes) -> bytes:
    from reduced_model.scene import BY_NAME
    from reduced_model.scene import OUTPUTS
    out_units = {n: u for n, u, _ in OUTPUTS}
    root = ET.fromstring(xml)
    units = sorted({p.unit for p in BY_NAME.values() if p.kind == "real"} | set(out_units.values()))
    ud = ET.Element("UnitDefinitions")
    for u in units:
        ue = ET.SubElement(ud, "Unit", name=u)
        if u == "rad":
            ET.SubElement(ue, "DisplayUnit", name="deg", factor=str(180.0 / 3.141592653589793))
    # UnitDefinitions goes before ModelVariables (after LogCategories/DefaultExperiment order)
    children = list(root)
    idx = next(i for i, c in enumerate(children) if c.tag in ("LogCategories", "DefaultExperiment",
                                                               "ModelVariables"))
    root.insert(idx, ud)
    for sv in root.iter("ScalarVariable"):
        name = sv.get("name")
        typ = sv[0]
        if name in BY_NAME:
            p = BY_NAME[name]
            if typ.tag == "Real":
                typ.set("unit", p.unit)
                if p.display_unit:
                    typ.set("displayUnit", p.display_unit)
            if typ.tag in ("Real", "Integer"):
                if p.lo is not None:
                    typ.set("min", repr(float(p.lo)) if typ.tag == "Real" else str(int(p.lo)))
                if p.hi is not None:
                    typ.set("max", repr(float(p.hi)) if typ.tag == "Real" else str(int(p.hi)))
        elif name in out_units and typ.tag == "Real":
            typ.set("unit", out_units[name])
    ET.indent(root)
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="utf-8")


def build(name="TripodRoller", force=False) -> Path:
    """Build build/<name>.fmu if missing or stale (or forced); returns its path."""
    dest = fmu_path(name)
    if not force and not is_stale(name):
        return dest
    from pythonfmu import FmuBuilder
    BUILD.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        raw = FmuBuilder.build_FMU(SLAVES[name], dest=tmp, project_files=list(BUNDLE[name]),
                                   needsExecutionTool=False, canGetAndSetFMUstate=True,
                                   canSerializeFMUstate=True)
        tmp_fmu = Path(tmp) / "patched.fmu"
        with zipfile.ZipFile(raw) as zin, zipfile.ZipFile(tmp_fmu, "w", zipfile.ZIP_DEFLATED) as zout:
            for item in zin.infolist():
                if "__pycache__" in item.filename:
                    continue
                data = zin.read(item.filename)
                if item.filename == "modelDescription.xml":
                    data = _units_and_ranges(data)
                zout.writestr(item, data)
        shutil.move(str(tmp_fmu), dest)
    return dest


if __name__ == "__main__":
    for n in SLAVES:
        print(build(n, force="--force" in sys.argv))
