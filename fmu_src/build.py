"""Build the FMUs into build/.

Each FMU is its model compiled under the native FMI layer (native_fmu.py) and a
modelDescription.xml written from the parameter table (description.py, then the units,
ranges and identity here).  Neither pythonfmu nor Python is in an FMU or on the way to it; the
tests hold each FMU to its model's functions run as Python in process (harness/inprocess.py).
"""
from __future__ import annotations

import contextlib
import fcntl
import hashlib
import re
import sys
import uuid
from pathlib import Path
from xml.etree import ElementTree as ET

ROOT = Path(__file__).resolve().parents[1]
FMU_SRC = ROOT / "fmu_src"
BUILD = ROOT / "build"
DESCRIPTION = FMU_SRC / "description.py"    # what each FMU is: its model description
# the Python each model is made of (compiled into its FMU)
MODEL_PACKAGES = {"TripodRoller": (FMU_SRC / "tripod_model", ROOT / "reduced_model"),
                  "TripodRollerAnalytic": (ROOT / "reduced_model",),
                  "Powertrain": (ROOT / "driveline", ROOT / "reduced_model")}

# FMUs whose binary runs the model compiled, without Python (native_fmu.py): the C functions
# (module:factory) and where the variables live (a function of the model's package)
COMPILED = {"Powertrain": ("driveline.mounts:c_functions", "driveline.powertrain:native_layout"),
            "TripodRollerAnalytic": ("reduced_model.analytic_kernel:c_functions",
                                     "reduced_model.analytic_kernel:native_layout"),
            "TripodRoller": ("tripod_model.lifecycle:c_functions",
                             "tripod_model.lifecycle:native_layout")}
# the native layer: every file of native/ (a file added there is a source without a list to
# keep), and what compiles ahead of time
NATIVE_FMU = (FMU_SRC / "native_fmu.py",
              *sorted(f for f in (FMU_SRC / "native").iterdir() if f.suffix in (".c", ".h", ".map")))
AOT = (FMU_SRC / "aot.py",)


def _py_files(paths):
    return [f for p in paths for f in (sorted(p.rglob("*.py")) if p.is_dir() else [p])]


def _sources(name):
    """What the FMU ``name`` is built from."""
    return [Path(__file__), DESCRIPTION, *AOT, *NATIVE_FMU, *_py_files(MODEL_PACKAGES[name])]


def _fmi_headers() -> Path:
    """The FMI 2.0 standard's C headers, as FMPy ships them."""
    import fmpy
    return Path(fmpy.__file__).parent / "c-code"


_HELD = {}   # this process's depth inside _exclusive, per lock


@contextlib.contextmanager
def _exclusive(what="shared"):
    """One build of ``what`` at a time in build/ across processes (parallel test workers each
    build what they find stale): an FMU's name (two FMUs build side by side), or "shared";
    re-entrant within a process."""
    if _HELD.get(what):
        _HELD[what] += 1
        try:
            yield
        finally:
            _HELD[what] -= 1
        return
    BUILD.mkdir(parents=True, exist_ok=True)
    with open(BUILD / f".lock-{what}", "w") as f:
        try:
            fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            _tell(f"waiting for another process's build ({what}) ...")
            fcntl.flock(f, fcntl.LOCK_EX)
        _HELD[what] = 1
        try:
            yield
        finally:
            _HELD[what] = 0


def _tell(line):
    """One line to a user at a terminal (a first build takes minutes and would look hung);
    nothing when stderr is captured, so a run's captured output is the same built or not."""
    if sys.stderr.isatty():
        print(line, file=sys.stderr, flush=True)


def build_module(name: str):
    """fmu_src/<name>.py, one of the build's own modules (aot, native_fmu), loaded by path as
    this file is (harness.fmus): fmu_src is what goes into the FMUs, not a package."""
    import importlib.util
    if name not in sys.modules:
        if name == "native_fmu":
            build_module("aot")          # (it imports aot by name)
        spec = importlib.util.spec_from_file_location(name, FMU_SRC / f"{name}.py")
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod
        spec.loader.exec_module(mod)
    return sys.modules[name]


def fmu_path(name="TripodRoller") -> Path:
    return BUILD / f"{name}.fmu"


def sources_hash(name="TripodRoller") -> str:
    """Content hash of the FMU's sources (their paths and bytes)."""
    h = hashlib.sha256()
    for s in sorted(_sources(name)):
        h.update(str(s).encode() + b"\0" + s.read_bytes())
    return h.hexdigest()


def _stamp(name) -> Path:
    """build/<name>.fmu.sources: the sources' hash the FMU was built from."""
    fmu = fmu_path(name)
    return fmu.with_name(fmu.name + ".sources")


def is_stale(name="TripodRoller") -> bool:
    """True when the FMU is missing or was built from other sources than today's (by content:
    a source edited while a build ran, after it was read, leaves the FMU stale, which the
    files' times could not tell)."""
    f = fmu_path(name)
    stamp = _stamp(name)
    if not f.exists() or not stamp.exists():
        return True
    return stamp.read_text().strip() != sources_hash(name)


def _table(name):
    """The parameter table (name -> Param) and the outputs ((name, unit, description)) the
    FMU ``name``'s variables come from."""
    if name == "Powertrain":
        from driveline.powertrain import BY_NAME, OUTPUTS
    else:
        from reduced_model.scene import BY_NAME, OUTPUTS
    return BY_NAME, OUTPUTS


def _project_version() -> str:
    import tomllib
    with open(ROOT / "pyproject.toml", "rb") as f:
        return tomllib.load(f)["project"]["version"]


def content_guid(name, xml: bytes) -> str:
    """The FMU's GUID from what it is made of: its model description (the guid and the
    generation attributes left out), its sources by their paths in the checkout, and the
    compilers' versions: the same commit gives the same GUID on any machine and in any folder,
    a change to the model another."""
    import llvmlite
    import numba
    h = hashlib.sha256(re.sub(rb'\s(guid|generationTool|generationDateAndTime)="[^"]*"', b"", xml))
    for s in sorted(_sources(name), key=lambda f: str(f.relative_to(ROOT))):
        h.update(str(s.relative_to(ROOT)).encode() + b"\0" + s.read_bytes())
    h.update(f"numba {numba.__version__} llvmlite {llvmlite.__version__}".encode())
    b = bytearray(h.digest()[:16])
    b[6], b[8] = (b[6] & 0x0F) | 0x50, (b[8] & 0x3F) | 0x80     # an RFC 4122 name-based GUID
    return "{%s}" % uuid.UUID(bytes=bytes(b))


def _identity(xml: bytes, name) -> bytes:
    """The model description named by its content (content_guid) and its true generation tool,
    with no generation time: the same sources give the same bytes."""
    xml = re.sub(rb'\sgenerationDateAndTime="[^"]*"', b"", xml, count=1)
    xml = re.sub(rb'\sgenerationTool="[^"]*"',
                 f' generationTool="tripod-thrust {_project_version()}"'.encode(), xml, count=1)
    return re.sub(rb'\sguid="[^"]*"', f' guid="{content_guid(name, xml)}"'.encode(), xml,
                  count=1)


def _units_and_ranges(xml: bytes, BY_NAME, OUTPUTS) -> bytes:
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
    _initial_unknowns(root)
    ET.indent(root)
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="utf-8")


def _initial_unknowns(root):
    """ModelStructure/InitialUnknowns: the outputs the FMU calculates at initialisation
    (initial = calculated; FMI 2.0 requires the list)."""
    idx = [str(i) for i, sv in enumerate(root.iter("ScalarVariable"), start=1)
           if sv.get("causality") == "output" and sv.get("initial", "calculated") != "exact"]
    if idx:
        iu = ET.SubElement(root.find("ModelStructure"), "InitialUnknowns")
        for i in idx:
            ET.SubElement(iu, "Unknown", index=i)


def model_description(name) -> bytes:
    """The FMU's modelDescription.xml: description.py's variables with the table's units and
    ranges, named by its content."""
    return _identity(_units_and_ranges(build_module("description").raw_xml(name),
                                       *_table(name)), name)


def build(name="TripodRoller", force=False) -> Path:
    """Build build/<name>.fmu if missing or stale (or forced); returns its path."""
    with _exclusive(name):
        return _build(name, force)


def _build(name, force):
    dest = fmu_path(name)
    if not force and not is_stale(name):
        return dest
    built_from = sources_hash(name)    # before anything is read
    _tell(f"building {dest.relative_to(ROOT)} from its sources (a few minutes) ...")
    import importlib
    native_fmu = build_module("native_fmu")
    spec, layout = COMPILED[name]
    module, fn = layout.split(":")
    out = native_fmu.package(model_description(name), dest, spec,
                             getattr(importlib.import_module(module), fn)(), _fmi_headers(),
                             generated=generated_path(name))
    _stamp(name).write_text(built_from + "\n")
    return out


def generated_path(name) -> Path:
    """build/generated/<name>/: what the build generated for the FMU's binaries, kept for a
    reader (<target>/model_data.c: its variables table, sizes, notes and functions)."""
    return BUILD / "generated" / name


if __name__ == "__main__":
    for n in COMPILED:
        print(build(n, force="--force" in sys.argv))
