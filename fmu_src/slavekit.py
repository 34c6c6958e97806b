"""What the pythonfmu slaves share: their description and variables (description.py), the error
contract, and the serialised FMU state (data only).  Bundled into each FMU's resources/."""
import json
import math
import struct
import weakref
import zlib
from typing import NamedTuple

import numpy as np

from pythonfmu import (Boolean, DefaultExperiment, Fmi2Causality, Fmi2Initial, Fmi2Variability,
                       Integer, Real)
from pythonfmu.enums import Fmi2Status

from description import AUTHOR, MODELS, variables
from reduced_model.scene import StepRefused

_TYPES = {"real": Real, "int": Integer, "bool": Boolean}


def omega_by_angle(shaft_angle, whirl_angle, h):
    """Whirl rate [rad/s] over a step of h [s] that brings the whirl angle [rad] to the
    master's shaft angle [rad] at its end (drive_by_angle); fmi2_python.c's
    fast_angle_to_omega is its C mirror (tests/test_fast.py holds them equal bit for bit)."""
    return (shaft_angle - whirl_angle) / h


class FastStep(NamedTuple):
    """A compiled step a slave offers the native layer (its attribute ``_fast``), which reads
    these fields by name (fmi2_python.c: fast_take) and runs it for the next steps, of any
    size, without entering Python.  Addresses are the slave's own arrays, kept alive by it."""
    step: int            # int32_t step(double **args): 1 written, else failed
    args: int            # address of its argument: the addresses of its arrays (uintp array)
    outputs: int         # address of the outputs it writes (doubles, out_vrs' order)
    dt: float            # the step size it was offered for [s]
    out_vrs: list        # value references of its outputs
    in_vrs: list         # value references of the inputs it takes (at most 8)
    in_values: list      # their values now
    in_slots: tuple      # per input: (address the step reads it at, lowest, highest value,
    #                       lowest excluded, highest excluded); address 0: the slave takes it
    dt_slot: int         # address the step reads its step size [s] at (a master's new one is
    #                       written there)
    by_angle: tuple = ()  # whirl driven by angle: (shaft angle's vr, omega's vr, the whirl
    #                       angle's place in out_vrs), both inputs among in_vrs: the layer
    #                       sets omega by omega_by_angle before each step


def describe(cls):
    """Class decorator: the slave ``cls`` (named as its FMU) described as description.py says."""
    m = MODELS[cls.__name__]
    cls.author, cls.description = AUTHOR, m.description
    cls.default_experiment = DefaultExperiment(start_time=0.0, stop_time=m.stop_time,
                                               step_size=m.step_size)
    return cls


def register(slave):
    """Register the slave's FMU's variables (description.variables, with their defaults and
    FMI attributes, Variable.fmi) on ``slave``."""
    for v in variables(type(slave).__name__):
        setattr(slave, v.name, 0.0 if v.start is None else v.start)
        a = v.fmi
        kw = dict(causality=Fmi2Causality[a["causality"]],
                  variability=Fmi2Variability[a["variability"]])
        if "initial" in a:
            kw["initial"] = Fmi2Initial[a["initial"]]
        if v.kind == "int" and v.start is None:
            setattr(slave, v.name, 0)
        slave.register_variable(_TYPES[v.kind](v.name, description=v.description, **kw))


class Guarded:
    """The project's error contract for a slave; subclasses supply ``_initialise()`` (raise
    ValueError on a bad parameter) and ``_advance(t, h)`` (raise ValueError on a bad input).

    A bad parameter fails initialisation: the ValueError reaches the native layer, which logs
    its message and returns fmi2Error.  A bad input or any other exception in a step is logged
    here and the step returns Discard.  No output is changed by a failed step.
    """
    _ready = False

    def exit_initialization_mode(self):
        self._ready = False
        try:
            self._initialise()
        except ValueError as e:
            raise ValueError(f"invalid parameter: {e}") from None
        except ArithmeticError as e:   # a value inside its range the model cannot compute with
            from fmi2bridge import one_line
            raise ValueError(f"invalid parameter: the scene cannot be computed ({one_line(e)}): "
                             "a parameter or start input at the edge of its range (a denormal "
                             "or near-zero value?)") from None
        self._ready = True

    def do_step(self, current_time, step_size):
        if not self._ready:
            self.log("doStep before a successful initialisation", Fmi2Status.error)
            return False
        try:
            return self._advance(current_time, step_size)
        except StepRefused as e:
            self.log(f"step refused at t = {current_time:g} s: {e}", Fmi2Status.error)
            return False
        except ValueError as e:
            self.log(f"invalid input at t = {current_time:g} s: {e}", Fmi2Status.error)
            return False
        except Exception as e:   # no exception may escape into the host
            from fmi2bridge import one_line
            self.log(f"step failed at t = {current_time:g} s: {one_line(e)}", Fmi2Status.error)
            return False


# --- the serialised FMU state: data only -------------------------------------------------------
# MAGIC, a little-endian u32 header length, the header (UTF-8 JSON), the arrays' bytes, and a
# CRC-32 of all that (a file damaged in storage or transfer is refused, not half-used).  The
# header holds the format version, the FMU's GUID, the structural parameters the state was taken
# with and the state's tree: JSON values, and {"@array": [dtype, shape, offset]} for an array.
# Decoding parses JSON and copies bytes into arrays of allowed dtypes whose sizes are checked
# against the buffer first: nothing in a state can run code or size an allocation unchecked.
STATE_MAGIC, STATE_VERSION = b"TTSTATE\0", 1
_DTYPES = {"<f8": np.float64, "<i8": np.int64, "|b1": np.bool_}
MAX_STATE_BYTES = 1 << 28     # 256 MiB: far above any state (a needle row's is about 50 kB)


class StateError(ValueError):
    """A serialised or restored FMU state refused, with the reason."""


def encode_state(tree, guid, structural) -> bytes:
    """``tree`` (dicts with str keys, lists, str, bool, int, float, None, numpy arrays) as bytes."""
    blobs, size = [], 0

    def enc(v):
        nonlocal size
        if isinstance(v, np.ndarray):
            a = np.ascontiguousarray(v, dtype=v.dtype.newbyteorder("<"))
            if a.dtype.str not in _DTYPES:
                raise StateError(f"array of dtype {a.dtype} in the state")
            blobs.append(a.tobytes())
            size += a.nbytes
            return {"@array": [a.dtype.str, list(a.shape), size - a.nbytes]}
        if isinstance(v, dict):
            return {str(k): enc(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return [enc(x) for x in v]
        if isinstance(v, float):                         # JSON has no inf or nan
            return v if math.isfinite(v) else {"@float": repr(v)}
        if isinstance(v, (np.floating, np.integer, np.bool_)):
            return enc(v.item())
        if v is None or isinstance(v, (bool, int, str)):
            return v
        raise StateError(f"{type(v).__name__} in the state")
    head = json.dumps({"version": STATE_VERSION, "guid": guid, "structural": structural,
                       "state": enc(tree)}, separators=(",", ":")).encode()
    data = STATE_MAGIC + struct.pack("<I", len(head)) + head + b"".join(blobs)
    return data + struct.pack("<I", zlib.crc32(data))


def decode_state(data, guid, structural):
    """The tree ``encode_state`` wrote, after checking every length, dtype and shape against
    the buffer, and the GUID and structural parameters against this instance's."""
    data = bytes(data)
    if len(data) > MAX_STATE_BYTES or len(data) < len(STATE_MAGIC) + 8 or \
            not data.startswith(STATE_MAGIC):
        raise StateError("not a serialised state of this FMU (bad magic or size)")
    if zlib.crc32(data[:-4]) != struct.unpack("<I", data[-4:])[0]:
        raise StateError("the state is damaged (checksum mismatch)")
    data = data[:-4]
    n = struct.unpack_from("<I", data, len(STATE_MAGIC))[0]
    start = len(STATE_MAGIC) + 4
    if n > len(data) - start:
        raise StateError(f"header length {n} exceeds the {len(data) - start} bytes given")
    try:
        head = json.loads(data[start:start + n].decode("utf-8"))
    except (UnicodeDecodeError, ValueError) as e:
        raise StateError(f"corrupt state: its header is not JSON ({e.__class__.__name__})") \
            from None
    except RecursionError:   # (the decoder's own limit: arrays nested about 1000 deep)
        raise StateError("corrupt state: its header is nested too deep") from None
    version = head.get("version") if isinstance(head, dict) else "?"
    if version != STATE_VERSION:
        raise StateError(f"state format version {version} is not {STATE_VERSION}")
    if head.get("guid") != guid:
        raise StateError(f"state of another FMU or build (GUID {head.get('guid')!r}, this "
                         f"FMU's {guid!r})")
    theirs = head.get("structural")
    if theirs != structural:
        if not isinstance(theirs, dict):
            raise StateError("corrupt state: its header has no structural parameters")
        diff = [f"{k} = {str(theirs.get(k, '(none)'))[:20]} (this instance: {v})"
                for k, v in structural.items() if theirs.get(k, "(none)") != v][:4]
        raise StateError("state taken with other structural parameters: " +
                         ("; ".join(diff) or "other names"))
    body = memoryview(data)[start + n:]

    def dec(v, depth=0):
        if depth > 32:
            raise StateError("corrupt state: nested too deep")
        if isinstance(v, list):
            return [dec(x, depth + 1) for x in v]
        if isinstance(v, dict):
            if set(v) == {"@float"}:
                if v["@float"] not in ("inf", "-inf", "nan"):
                    raise StateError("corrupt state: a non-finite float misspelt")
                return float(v["@float"])
            if set(v) == {"@array"}:
                return _array(v["@array"], body)
            return {k: dec(x, depth + 1) for k, x in v.items()}
        return v
    return dec(head.get("state"))


def _array(spec, body):
    ok = isinstance(spec, list) and len(spec) == 3 and spec[0] in _DTYPES and \
        isinstance(spec[1], list) and len(spec[1]) <= 4 and \
        all(type(d) is int and 0 <= d <= MAX_STATE_BYTES for d in spec[1]) and \
        type(spec[2]) is int and spec[2] >= 0
    if not ok:
        raise StateError(f"corrupt state: array description {str(spec)[:80]}")
    dt = np.dtype(_DTYPES[spec[0]])
    count = math.prod(spec[1])
    end = spec[2] + count * dt.itemsize
    if end > len(body):
        raise StateError(f"array of {count} {dt} runs past the state's end")
    return np.frombuffer(body[spec[2]:end], dtype=dt).reshape(spec[1]).copy()


def same_layout(got, want, where="state"):
    """Raise StateError unless ``got`` has ``want``'s layout: the same keys, list lengths,
    scalar types and array dtypes and shapes (None matches anything of that kind in ``want``
    only where ``want`` is None too), and no non-finite float where ``want`` has a finite one."""
    if isinstance(want, np.ndarray):
        if not isinstance(got, np.ndarray) or got.dtype != want.dtype or got.shape != want.shape:
            raise StateError(f"{where}: expected a {want.dtype} array of shape {want.shape}")
        if got.dtype.kind == "f" and not np.isfinite(got[np.isfinite(want)]).all():
            raise StateError(f"{where}: non-finite value")
        return
    if isinstance(want, dict):
        if not isinstance(got, dict) or set(got) != set(want):
            raise StateError(f"{where}: expected the keys {sorted(want)}")
        for k in want:
            same_layout(got[k], want[k], f"{where}.{k}")
        return
    if isinstance(want, (list, tuple)):
        if not isinstance(got, (list, tuple)) or len(got) != len(want):
            raise StateError(f"{where}: expected a list of {len(want)}")
        for i, (g, w) in enumerate(zip(got, want)):
            same_layout(g, w, f"{where}[{i}]")
        return
    if want is None:
        if got is not None:
            raise StateError(f"{where}: expected nothing")
        return
    kinds = (bool,) if isinstance(want, bool) else (int,) if isinstance(want, int) else \
        (int, float) if isinstance(want, float) else (str,)
    if not isinstance(got, kinds) or (isinstance(got, bool) and kinds != (bool,)):
        raise StateError(f"{where}: expected a {type(want).__name__}")
    if isinstance(want, float) and math.isfinite(want) and not math.isfinite(got):
        raise StateError(f"{where}: non-finite value")


class _Vouched(dict):
    """A state its instance vouches for (DataState._vouch); weakly referenced by it."""
    __slots__ = ("__weakref__",)


class DataState:
    """FMU state to and from bytes without pickle (``encode_state``).  A slave names the
    parameters that fix its state's layout (``STRUCTURAL``) and checks a state before using it
    in ``_check_state`` (raise StateError); the native layer sets ``fmu_guid``.

    A state the slave took itself, or decoded from bytes and checked, is vouched for
    (``_vouch``): setting it again skips the check (``_needs_check``), which cost most of a
    rollback (an iterative master's get, step, set: 315 us a step with three rollers).  A host
    holds only a handle to such a state and cannot change it; a state of another instance (or
    of this one before an fmi2Reset, which makes a new slave) is checked as any other."""
    STRUCTURAL: tuple = ()
    fmu_guid = ""

    def _vouch(self, state):
        """state (a dict) as one this instance vouches for."""
        st = _Vouched(state)
        if "_vouched" not in self.__dict__:
            self._vouched = weakref.WeakValueDictionary()
        self._vouched[id(st)] = st
        return st

    def _needs_check(self, state):
        """Whether state is not one this instance vouched for (_vouch)."""
        return self.__dict__.get("_vouched", {}).get(id(state)) is not state

    def _structural(self):
        return {n: getattr(self, n) for n in self.STRUCTURAL}

    def _check_structural(self, state_vars):
        """Raise StateError unless the state's variables hold this instance's structural
        parameters (a state belongs to the layout they give)."""
        for n in self.STRUCTURAL:
            if state_vars[n] != getattr(self, n):
                raise StateError(f"state taken with {n} = {state_vars[n]}, this instance "
                                 f"has {getattr(self, n)}")

    def _fmu_state_to_bytes(self, state):
        return encode_state(state, self.fmu_guid, self._structural())

    def _fmu_state_from_bytes(self, data):
        state = decode_state(data, self.fmu_guid, self._structural())
        self._check_state(state)
        return self._vouch(state)
