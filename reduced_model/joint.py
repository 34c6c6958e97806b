"""A joint described once: a joint file (TOML or JSON) holds what describes a tripod joint on
its drawing (geometry, masses, materials, friction, the needle row) under the parameter table's
names, in its SI units; `tripod-thrust ... --joint FILE` and the FMUs' start values take it.

A file names every key of JOINT_KEYS and nothing else (besides an optional ``name`` and
``description``), each value inside the table's range, and a geometry that can be built: the
roller inside its groove, the bore inside the roller, the needle row inside the bore, the
needles no longer than the roller is wide.  Anything else is refused with one line naming the
key.  Example joints: joints/ (the paper's, a small car's, a light truck's); how to fill one in
from a drawing: docs/getting-started.md.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

from .scene import BY_NAME, check_param

# what describes the joint (the rest of the table: the scene's inputs and the models' switches)
JOINT_KEYS = ("s", "r_roller", "r_groove", "r_bore", "m_roller", "roller_width",
              "running_clearance", "mu_groove", "E", "nu", "r_trunnion", "d_needle", "l_needle",
              "n_needles", "needle_clearance", "needle_circ_clearance", "needle_axial_clearance",
              "rho_needle", "mu_needle", "mu_rolling")
TEXT_KEYS = ("name", "description")
EXAMPLES = Path(__file__).resolve().parents[1] / "joints"


def _read(path: Path) -> dict:
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise ValueError(f"joint file {path}: {e.strerror}") from None
    if path.suffix.lower() == ".json":
        try:
            data = json.loads(raw)
        except ValueError as e:
            raise ValueError(f"joint file {path}: not valid JSON ({e})") from None
    else:
        import tomllib
        try:
            data = tomllib.loads(raw.decode("utf-8"))
        except (UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
            raise ValueError(f"joint file {path}: not valid TOML ({e})") from None
    if isinstance(data, dict) and isinstance(data.get("joint"), dict) and len(data) == 1:
        data = data["joint"]
    if not isinstance(data, dict):
        raise ValueError(f"joint file {path}: expected a table of NAME = VALUE")
    return data


def check_geometry(j: dict, where: str = "joint") -> None:
    """ValueError naming the key where the joint ``j`` cannot be built."""
    def refuse(key, why):
        raise ValueError(f"{where}: {key} = {j[key]:g} m: {why}")
    if j["r_groove"] <= j["r_roller"]:
        refuse("r_groove", f"the roller (r_roller = {j['r_roller']:g} m) is larger than its "
                           "groove; r_groove must exceed r_roller")
    if j["r_bore"] >= j["r_roller"]:
        refuse("r_bore", f"the bore is larger than the roller (r_roller = {j['r_roller']:g} m); "
                         "r_bore must be below r_roller")
    row = j["r_trunnion"] + j["d_needle"]
    if row > j["r_bore"] * (1.0 + 1e-9):
        refuse("r_trunnion", f"the needle row (r_trunnion + d_needle = {row:g} m) does not fit "
                             f"in the bore (r_bore = {j['r_bore']:g} m)")
    if j["l_needle"] > j["roller_width"]:
        refuse("l_needle", f"the needles are longer than the roller is wide (roller_width = "
                           f"{j['roller_width']:g} m)")
    if j["s"] <= j["r_trunnion"]:
        refuse("s", f"the pitch-circle radius is within the trunnion (r_trunnion = "
                    f"{j['r_trunnion']:g} m)")
    c, c0 = j["running_clearance"], 2.0 * (j["r_groove"] - j["r_roller"])
    if c != 0.0 and c < c0:
        refuse("running_clearance", f"below 2 (r_groove - r_roller) = {c0:g} m, where the "
                                    "roller would touch both flanks; 0 (from the geometry) or "
                                    "at least that")


def load_joint(path) -> dict:
    """The joint file at ``path`` as {parameter name: value} (SI; n_needles an int), every key
    of JOINT_KEYS, checked; ValueError with one line naming the file and the key otherwise."""
    path = Path(path)
    data = _read(path)
    where = f"joint file {path}"
    unknown = sorted(k for k in data if k not in JOINT_KEYS and k not in TEXT_KEYS)
    if unknown:
        raise ValueError(f"{where}: unknown key '{unknown[0]}'; a joint file takes "
                         f"{', '.join(JOINT_KEYS)} (and name, description)")
    missing = [k for k in JOINT_KEYS if k not in data]
    if missing:
        p = BY_NAME[missing[0]]
        raise ValueError(f"{where}: missing key '{p.name}' ({p.description} [{p.unit}]; the "
                         f"paper's joint has {p.default:g})")
    out = {}
    for k in JOINT_KEYS:
        p, v = BY_NAME[k], data[k]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(f"{where}: {k} = {v!r} is not a number; allowed range "
                             f"{p.range_text()}")
        if p.kind == "int" and (not math.isfinite(v) or v != int(v)):
            raise ValueError(f"{where}: {k} = {v!r} is not an integer; allowed range "
                             f"{p.range_text()}")
        try:
            check_param(p, v)
        except ValueError as e:
            raise ValueError(f"{where}: {e}") from None
        out[k] = int(v) if p.kind == "int" else float(v)
    check_geometry(out, where)
    return out


def scaled(factor: float, clearance: float = 2e-4) -> dict:
    """The paper's joint scaled by its pitch circle: every length times ``factor`` (the needle
    row's clearances and the running clearance kept), the roller's groove clearance
    r_groove - r_roller = ``clearance`` [m], the roller's mass with the cube, materials and
    friction as they are: the scaled families of docs/validation.md."""
    j = {k: BY_NAME[k].default for k in JOINT_KEYS}
    for k in ("s", "r_roller", "r_bore", "roller_width", "r_trunnion", "d_needle", "l_needle"):
        j[k] = j[k] * factor
    j["r_groove"] = j["r_roller"] + clearance
    j["m_roller"] = j["m_roller"] * factor ** 3
    return j


def for_model(joint: dict, model: str) -> dict:
    """The joint's values a model ('contact' or 'analytic') takes (the analytic model has no
    needle row)."""
    return {k: v for k, v in joint.items() if model in BY_NAME[k].models}
