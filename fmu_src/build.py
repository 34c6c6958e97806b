"""Build the FMUs into build/.

Each FMU is its model compiled under the native FMI layer (native_fmu.py) and a
modelDescription.xml written from the parameter table (description.py, then the units,
ranges and identity here).  Neither pythonfmu nor Python is on the way.

The tests' reference FMUs (build/reference/, ``reference``) are the pythonfmu slaves of the
same models over the Python layer (fmu_src/native/fmi2_python.c, compiled here with the system
C compiler, in place of pythonfmu's, whose teardown corrupts the host's heap:
docs/native-layer.md), with the same model description.
"""
from __future__ import annotations

import contextlib
import fcntl
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import uuid
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

ROOT = Path(__file__).resolve().parents[1]
FMU_SRC = ROOT / "fmu_src"
BUILD = ROOT / "build"
# the contact model's packages (its reference FMU bundles them; numpy/numba come from the host)
PACKAGES = (FMU_SRC / "tripod_model", ROOT / "reduced_model")
SLAVES = {"TripodRoller": FMU_SRC / "TripodRoller.py",
          "TripodRollerAnalytic": FMU_SRC / "TripodRollerAnalytic.py",
          "Powertrain": FMU_SRC / "Powertrain.py"}     # the driveline example's (driveline/)
DESCRIPTION = FMU_SRC / "description.py"    # what each FMU is: its model description
KIT = (FMU_SRC / "slavekit.py", DESCRIPTION)   # what the slaves share
# the Python each model is made of (compiled into its FMU; bundled into its reference)
MODEL_PACKAGES = {"TripodRoller": PACKAGES,
                  "TripodRollerAnalytic": (ROOT / "reduced_model",),
                  "Powertrain": (ROOT / "driveline", ROOT / "reduced_model")}
# what each FMU needs in the Python it runs in (versions from pyproject.toml): the FMU's log
# names them when they are missing
RUNTIME_DEPS = {"TripodRoller": ("numpy", "numba"), "TripodRollerAnalytic": ("numpy",),
                "Powertrain": ("numpy",)}

# FMUs whose binary runs the model compiled, without Python (native_fmu.py): the C functions
# (module:factory) and where the variables live (a function of the model's package)
COMPILED = {"Powertrain": ("driveline.mounts:c_functions", "driveline.powertrain:native_layout"),
            "TripodRollerAnalytic": ("reduced_model.analytic_kernel:c_functions",
                                     "reduced_model.analytic_kernel:native_layout"),
            "TripodRoller": ("tripod_model.lifecycle:c_functions",
                             "tripod_model.lifecycle:native_layout")}
NATIVE_FMU = (FMU_SRC / "native_fmu.py", FMU_SRC / "native" / "exports.map",
              *(FMU_SRC / "native" / f for f in ("fmi2_native.c", "native_values.c",
                                                 "native_state.c", "native_model.h",
                                                 "native_values.h", "native_state.h")))
NATIVE_SRC = FMU_SRC / "native" / "fmi2_python.c"
AOT = (FMU_SRC / "aot.py", FMU_SRC / "native" / "aot_stubs.c")   # the prebuilt kernel
AOT_DIR = BUILD / "aot"
BRIDGE = FMU_SRC / "fmi2bridge.py"     # the native layer's Python side, in every FMU
NATIVE_LIB = BUILD / "native" / "fmi2_python.so"
PLATFORM = "linux64"


def _py_files(paths):
    return [f for p in paths for f in (sorted(p.rglob("*.py")) if p.is_dir() else [p])]


def _sources(name):
    """What the FMU ``name`` is built from."""
    return [Path(__file__), DESCRIPTION, *AOT, *NATIVE_FMU, *_py_files(MODEL_PACKAGES[name])]


def _reference_sources(name):
    """What its reference FMU is built from besides: the slave, the kit, the Python layer."""
    return _sources(name) + [SLAVES[name], NATIVE_SRC, BRIDGE, *KIT]


def _fmi_headers() -> Path:
    """The FMI 2.0 standard's C headers, as FMPy ships them."""
    import fmpy
    return Path(fmpy.__file__).parent / "c-code"


def _compile(src: Path, lib: Path, flags) -> Path:
    """Compile the C file ``src`` into the shared library ``lib`` with $CC (else cc)."""
    if sys.platform != "linux":
        raise RuntimeError(f"the FMUs' native code builds on Linux only, not {sys.platform}")
    lib.parent.mkdir(parents=True, exist_ok=True)
    cc = os.environ.get("CC") or "cc"
    cmd = cc.split()[:1] + ["-std=c11", "-O2", "-g", "-fPIC", "-shared", "-fvisibility=hidden",
                           "-Wall", "-Wextra"] + list(flags) + [str(src), "-o", str(lib), "-lm"]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True)
    except FileNotFoundError:
        raise RuntimeError(f"no C compiler '{cmd[0]}': install one (Debian: apt-get install "
                           "gcc) or set CC") from None
    if p.returncode != 0:
        raise RuntimeError(f"compiling {src.name} failed:\n{p.stderr}")
    return lib


_HELD = {}   # this process's depth inside _exclusive, per lock


@contextlib.contextmanager
def _exclusive(what="shared"):
    """One build of ``what`` at a time in build/ across processes (parallel test workers each
    build what they find stale): an FMU's name (two FMUs build side by side), or "shared" for
    what the FMUs share (the Python layer, the prebuilt kernel); re-entrant within a process."""
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


def _fresh(lib: Path, src: Path) -> bool:
    return lib.exists() and lib.stat().st_mtime >= src.stat().st_mtime


def native_library(force=False) -> Path:
    """build/native/fmi2_python.so, compiled from fmu_src/native/ when missing or stale.

    Needs only a C compiler ($CC, else cc): the Python C API is bound at run time, so neither
    the Python headers nor libpython are needed to build it."""
    with _exclusive():
        if not force and _fresh(NATIVE_LIB, NATIVE_SRC):
            return NATIVE_LIB
        return _compile(NATIVE_SRC, NATIVE_LIB, [f"-I{_fmi_headers()}", "-ldl", "-lpthread"])


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


def prebuilt_kernel(force=False, target="linux64") -> tuple[Path, Path]:
    """The prebuilt kernel for target (_prebuilt_kernel), built under the build lock."""
    with _exclusive():
        return _prebuilt_kernel(force, target)


def _prebuilt_kernel(force, target):
    """build/aot/_step.{so,json} (win64: build/aot-win64/_step.{dll,json}, cross-compiled): the
    contact kernel's step compiled ahead of time (aot.py), rebuilt when missing or stale: built
    from other kernel sources than today's (the content hash the FMU checks when it loads the
    library, native.source_hash, which covers the reduced model's modules the kernel compiles
    too), or older than aot.py and its stubs."""
    aot = build_module("aot")
    dest = AOT_DIR if target == "linux64" else BUILD / f"aot-{target}"
    lib, meta = dest / aot.TARGETS[target]["lib"], dest / "_step.json"
    if not force and lib.exists() and meta.exists():
        from tripod_model import native
        try:
            built = json.loads(meta.read_text())["hash"]
        except (ValueError, KeyError):
            built = None
        if (built == native.source_hash()
                and all(lib.stat().st_mtime >= f.stat().st_mtime for f in AOT)):
            return lib, meta
    return aot.build_step_library(dest, target)


def _requirements(names) -> str:
    """requirements.txt lines for ``names``, with the version ranges of pyproject.toml."""
    import tomllib
    with open(ROOT / "pyproject.toml", "rb") as f:
        deps = tomllib.load(f)["project"]["dependencies"]
    pick = [d for d in deps if d.split(">")[0].split("<")[0].split("=")[0].strip() in names]
    return "".join(d + "\n" for d in pick)


def package(script, dest, project_files=(), requirements="", patch_xml=None,
            extra=()) -> Path:
    """Build the FMU of the slave in ``script`` at ``dest`` with our native layer.

    project_files go to resources/; requirements: resources/requirements.txt (what the FMU's
    Python must have); patch_xml: bytes -> bytes applied to modelDescription.xml; extra:
    (file, path in the FMU) pairs added as they are."""
    from pythonfmu import FmuBuilder
    lib = native_library()
    dest = Path(dest)
    with tempfile.TemporaryDirectory() as tmp:
        raw = FmuBuilder.build_FMU(script, dest=tmp,
                                   project_files=list(project_files) + [BRIDGE],
                                   needsExecutionTool=False, canGetAndSetFMUstate=True,
                                   canSerializeFMUstate=True)
        tmp_fmu = Path(tmp) / "patched.fmu"
        with zipfile.ZipFile(raw) as zin, zipfile.ZipFile(tmp_fmu, "w", zipfile.ZIP_DEFLATED) as zout:
            model_id = None
            files = {i.filename: zin.read(i.filename) for i in zin.infolist()
                     if "__pycache__" not in i.filename and not i.filename.endswith("/")
                     and not i.filename.startswith("binaries/")}   # pythonfmu's: ours instead
            files.update((arc, Path(f).read_bytes()) for f, arc in extra)
            for arc, data in own_package(files).items():
                if arc == "modelDescription.xml":
                    model_id = ET.fromstring(data).find("CoSimulation").get("modelIdentifier")
                    if patch_xml:
                        data = patch_xml(data)
                zout.writestr(arc, data)
            zout.write(lib, f"binaries/{PLATFORM}/{model_id}.so")
            # the interpreter that built the FMU: a C host's first guess at a Python to start
            zout.writestr("resources/python.txt", sys.executable + "\n")
            zout.writestr("resources/requirements.txt", requirements)
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.move(str(tmp_fmu), dest)
    return dest


def own_package(files: dict) -> dict:
    """The FMU's files with its Python moved into a package of its own, resources/PKG/, PKG
    named after the hash of those sources: the slave, the kit, the bridge, the model packages
    and pythonfmu, their imports of each other made relative, slavemodule.txt naming PKG.Slave.
    Two FMUs, or two builds of one, in one process then never run each other's modules, and an
    installed copy of the project is never picked up."""
    keep = {"resources/slavemodule.txt", "resources/python.txt", "resources/requirements.txt"}
    own = [a for a in files if a.startswith("resources/") and a not in keep and
           ("/" in a[len("resources/"):] or a.endswith(".py"))]
    tops = sorted({a[len("resources/"):].split("/")[0].removesuffix(".py") for a in own})
    h = hashlib.sha256()
    for a in sorted(own):
        h.update(a.encode() + b"\0" + files[a])
    pkg = "tripod_fmu_" + h.hexdigest()[:12]
    pattern = re.compile(rb"^(\s*)from (" + "|".join(tops).encode() + rb")\b", re.M)
    out = {a: d for a, d in files.items() if a not in own}
    for a in own:
        rel = a[len("resources/"):]
        data = files[a]
        if a.endswith(".py"):
            dots = b"." * (rel.count("/") + 1)
            data = pattern.sub(lambda m: m.group(1) + b"from " + dots + m.group(2), data)
        out[f"resources/{pkg}/{rel}"] = data
    out[f"resources/{pkg}/__init__.py"] = b'"""The FMU\'s own Python (build.py: own_package)."""\n'
    slave = files["resources/slavemodule.txt"].decode().strip()
    out["resources/slavemodule.txt"] = f"{pkg}.{slave}\n".encode()
    return out


def fmu_path(name="TripodRoller") -> Path:
    return BUILD / f"{name}.fmu"


def sources_hash(name="TripodRoller", reference=False) -> str:
    """Content hash of the FMU's sources (their paths and bytes); reference: its reference
    FMU's."""
    h = hashlib.sha256()
    for s in sorted((_reference_sources if reference else _sources)(name)):
        h.update(str(s).encode() + b"\0" + s.read_bytes())
    return h.hexdigest()


def _stamp(name, reference=False) -> Path:
    """build/<name>.fmu.sources: the sources' hash the FMU was built from."""
    fmu = reference_path(name) if reference else fmu_path(name)
    return fmu.with_name(fmu.name + ".sources")


def is_stale(name="TripodRoller", reference=False) -> bool:
    """True when the FMU (reference: its reference FMU) is missing or was built from other
    sources than today's (by content: a source edited while a build ran, after it was read,
    leaves the FMU stale, which the files' times could not tell)."""
    f = reference_path(name) if reference else fmu_path(name)
    stamp = _stamp(name, reference)
    if not f.exists() or not stamp.exists():
        return True
    return stamp.read_text().strip() != sources_hash(name, reference)


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
    (initial = calculated; pythonfmu writes no such list, and FMI 2.0 requires it)."""
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


def reference_path(name) -> Path:
    """build/reference/<name>.fmu: the pythonfmu slave's FMU of the model (``reference``)."""
    return BUILD / "reference" / f"{name}.fmu"


def _same_variables(theirs: bytes, ours: bytes, name) -> bytes:
    """ours, once the slave's own model description (pythonfmu's) is found to declare the same
    variables (names, value references, causality, variability, type, start)."""
    def rows(xml):
        return [(sv.get("name"), sv.get("valueReference"), sv.get("causality"),
                 sv.get("variability"), sv[0].tag, sv[0].get("start"))
                for sv in ET.fromstring(xml).iter("ScalarVariable")]
    if rows(theirs) != rows(ours):
        from itertools import zip_longest
        bad = next((a, b) for a, b in zip_longest(rows(theirs), rows(ours)) if a != b)
        raise RuntimeError(f"the {name} slave's variables are not description.py's: "
                           f"{bad[0]} against {bad[1]}")
    return ours


def reference(name="TripodRoller", force=False) -> Path:
    """build/reference/<name>.fmu, built when missing or stale (or forced): the model's
    pythonfmu slave over the Python layer, with the FMU's own model description (the same
    GUID), which the tests hold the compiled FMU to.  Needs pythonfmu."""
    with _exclusive(name):
        dest = reference_path(name)
        if not force and not is_stale(name, reference=True):
            return dest
        built_from = sources_hash(name, reference=True)
        native_library(force=force)
        extra = ()
        if name == "TripodRoller":   # next to the bundled kernel's sources (native.py looks there)
            extra = [(f, f"resources/tripod_model/{f.name}") for f in prebuilt_kernel(force)]
        xml = model_description(name)
        out = package(SLAVES[name], dest, MODEL_PACKAGES[name] + KIT,
                      _requirements(RUNTIME_DEPS[name]), lambda theirs: _same_variables(
                          theirs, xml, name), extra)
        _stamp(name, reference=True).write_text(built_from + "\n")
        return out


if __name__ == "__main__":
    for n in SLAVES:
        print(build(n, force="--force" in sys.argv))
