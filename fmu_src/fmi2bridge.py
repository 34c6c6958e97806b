"""The Python side of the FMUs' native layer (fmu_src/native/fmi2_python.c).

Bundled into each FMU's resources/.  The C layer imports it to create the slave (a pythonfmu
``Fmi2Slave`` subclass) and learn its variables, to drain the slave's log queue and to word
exceptions.  Run as a script (``python fmi2bridge.py --where``) it tells a C host's FMU where
this interpreter's libpython and sys.path are, so the FMU can start the very same Python.
"""
import importlib
import os
import re
import sys
import traceback


class FmuError(Exception):
    """A reason the FMU cannot go on, worded for the user (logged as it is)."""


_SETTABLE = {("parameter", "fixed"): "p", ("parameter", "tunable"): "t"}


def requirements(resources):
    """The FMU's run-time requirements (resources/requirements.txt), one pip argument each."""
    try:
        with open(os.path.join(resources, "requirements.txt")) as f:
            return [ln.strip() for ln in f if ln.strip() and not ln.startswith("#")]
    except OSError:
        return []


def _check_guid(resources, guid):
    """The host's fmuGUID must be the one of modelDescription.xml beside resources/; returns
    this FMU's GUID (what its serialised states carry)."""
    try:
        with open(os.path.join(os.path.dirname(resources), "modelDescription.xml")) as f:
            m = re.search(r'\sguid="([^"]*)"', f.read(4096))
    except OSError:
        m = None
    if not m:
        if not guid:
            raise FmuError("fmuGUID is empty and no modelDescription.xml is beside resources/")
        return guid
    if guid != m.group(1):
        raise FmuError(f"fmuGUID {guid!r} is not this FMU's ({m.group(1)}): the host's "
                       "modelDescription.xml and this binary come from different builds")
    return m.group(1)


def _adopt(module_name, resources):
    """The FMU's package (PKG of PKG.Slave, named after its sources' hash) loaded earlier from
    another extraction of the same build (FMPy extracts each run to a new folder and deletes it
    after): the same code, so keep its modules, but point their search paths here, so modules
    first imported now load from a folder that exists."""
    pkg = module_name.rpartition(".")[0]
    here = os.path.join(resources, pkg)
    mod = sys.modules.get(pkg)
    if not pkg or mod is None or list(getattr(mod, "__path__", ())) == [here]:
        return
    for name, m in list(sys.modules.items()):
        if (name == pkg or name.startswith(pkg + ".")) and hasattr(m, "__path__"):
            sub = name[len(pkg) + 1:].replace(".", os.sep)
            m.__path__[:] = [os.path.join(here, sub) if sub else here]
    importlib.invalidate_caches()


def _import(module_name, resources, owned):
    _adopt(module_name, resources)
    try:
        return importlib.import_module(module_name)
    except ModuleNotFoundError as e:
        pkg = (e.name or "?").split(".")[0]   # (the FMU's own package is in resources/)
        if os.path.exists(os.path.join(resources, pkg)) or os.path.exists(
                os.path.join(resources, pkg + ".py")):
            raise   # a bundled module failed: a broken FMU, not a missing dependency
        whose = "the Python this FMU started" if owned else "the host's Python"
        reqs = " ".join(f"'{r}'" for r in requirements(resources)) or pkg
        hint = ("; or set TRIPOD_THRUST_PYTHON to a Python that has them" if owned else "")
        raise FmuError(f"{module_name} needs the Python package '{pkg}', missing in {whose} "
                       f"({sys.executable}, Python {sys.version.split()[0]}): "
                       f"{sys.executable} -m pip install {reqs}{hint}") from None


def _slave_class(module):
    """The Fmi2Slave subclass the module defines (pythonfmu's slavemodule.txt convention)."""
    from pythonfmu import Fmi2Slave
    found = [c for c in vars(module).values() if isinstance(c, type) and
             issubclass(c, Fmi2Slave) and c.__module__ == module.__name__]
    if len(found) != 1:
        raise FmuError(f"{module.__name__} defines {len(found)} Fmi2Slave classes, not one")
    return found[0]


def create(module_name, instance_name, resources, guid, visible, owned):
    """Instantiate the FMU's slave.  Returns (slave, its log queue, the variable table, the
    variables' names): the table has two characters a value reference, its type (R, I, B, S)
    and when it may be set (p fixed parameter, t tunable parameter, i input, - never)."""
    fmu_guid = _check_guid(resources, guid)
    module = _import(module_name, resources, owned)
    slave = _slave_class(module)(instance_name=instance_name, resources=resources,
                                 visible=bool(visible))
    slave.fmu_guid = fmu_guid
    table, names = [], []
    for i, (vr, var) in enumerate(slave.vars.items()):
        if vr != i:
            raise FmuError(f"value references must be 0, 1, 2, ...: {var.name} has {vr}")
        kind = type(var).__name__[0]
        if kind not in "RIBS":
            raise FmuError(f"{var.name}: variables of type {type(var).__name__} are not supported")
        caus, var_ = var.causality.name, var.variability.name
        table.append(kind + ("i" if caus == "input" else _SETTABLE.get((caus, var_), "-")))
        names.append(var.name)
    return slave, slave._get_log_queue(), "".join(table), tuple(names)


def drain(queue):
    """Empty the slave's log queue: [(status, category, message), ...]."""
    out = [(int(m.status), m.category or "logAll", str(m.msg)) for m in queue]
    del queue[:]
    return out


def describe(exc_type, exc, tb):
    """An exception as one log message: the message alone for a reason meant for the user (the
    slaves raise ValueError for a bad parameter or input), else one line with the exception and
    where it was raised (a host's log is no place for a traceback)."""
    if isinstance(exc, (FmuError, ValueError)):
        return str(exc)
    return one_line(exc, tb)


def one_line(exc, tb=None):
    """'ZeroDivisionError: float division by zero (kernel.py:123)'."""
    frames = traceback.extract_tb(tb if tb is not None else exc.__traceback__)
    where = f" ({os.path.basename(frames[-1].filename)}:{frames[-1].lineno})" if frames else ""
    msg = " ".join(str(exc).split())[:300]
    return f"{type(exc).__name__}: {msg}{where}" if msg else f"{type(exc).__name__}{where}"


def flush():
    """Flush Python's stdout and stderr (an interpreter the FMU started never exits)."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:
            pass


def where():
    """Print this interpreter's libpython ('-' if it has none), executable and sys.path."""
    import sysconfig
    libdir = sysconfig.get_config_var("LIBDIR") or ""
    names = [sysconfig.get_config_var(k) for k in ("INSTSONAME", "LDLIBRARY")]
    libs = [os.path.join(libdir, n) for n in names if n and ".so" in n]
    print(next((p for p in libs if os.path.isfile(p)), "-"))
    print(sys.executable)
    print("\n".join(p for p in sys.path if p and p != os.path.dirname(os.path.abspath(__file__))))


if __name__ == "__main__" and sys.argv[1:] == ["--where"]:
    where()
