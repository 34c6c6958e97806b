"""A free spider against the prescribed one (spider = 1 against 0, docs/model.md "The floating
spider"): the joint's thrust Fz_joint in orders 1 and 3, the spread of the three trunnions'
loads, the spider's orbit against Eq. (5)'s, and whether superposition (the paper's three
prescribed rollers summed) holds within SUPERPOSITION_TOL."""
from __future__ import annotations

import math

import numpy as np

from reduced_model import scene as scene_mod
from reduced_model.orders import last_cycle_orders

SUPERPOSITION_TOL = 0.05   # order 3 of Fz_joint, free against prescribed (issue's 5 %)


def _last_cycle(run):
    """Indices of the run's last whole whirl cycle (by roller 1's whirl angle)."""
    x = np.abs(run["whirl_angle"])
    return x >= x[-1] - 2 * math.pi


def orbit_of(run, scene) -> dict:
    """The spider's centre over the last whole cycle against Eq. (5)'s orbit e (cos 2x, sin 2x)
    [m] in the housing frame: the amplitude and phase [deg] of its component at 2x, and its
    largest distance from Eq. (5)'s circle [m]."""
    sel = _last_cycle(run)
    x = run["whirl_angle"][sel]
    z = run["spider_x"][sel] + 1j * run["spider_y"][sel]
    c2 = np.mean(z * np.exp(-2j * x))
    e = scene["s"] * (1 - math.cos(scene["theta"])) / (2 * math.cos(scene["theta"]))
    return {"e": e, "amplitude": float(abs(c2)), "phase_deg": float(np.degrees(np.angle(c2))),
            "off_circle": float(np.max(np.abs(z - e * np.exp(2j * x))))}


def loads_of(run, scene) -> dict:
    """The three trunnions' loads over the last whole cycle against torque / (3 s): the lowest
    and highest, relative."""
    sel = _last_cycle(run)
    F = scene_mod.pressing_load(scene["F_press"], scene.get("torque", 0.0), scene["s"])
    rel = np.concatenate([run[f"F_roller_{i}"][sel] / F - 1 for i in (1, 2, 3)])
    return {"nominal": F, "low_rel": float(rel.min()), "high_rel": float(rel.max())}


def spider_comparison(scene, free, prescribed) -> dict:
    """Free against prescribed on one scene (both runs: arrays by output name, settled):
    Fz_joint's orders 1 and 3 of each [N, deg], order 3's relative difference, whether
    superposition holds (within SUPERPOSITION_TOL), roller 1's mean pressing force Fx against
    torque / (3 s) in each (fx_rel: the prescribed joint holds its pressing offset, not its
    load), the loads (loads_of), the orbit (orbit_of)."""
    w = abs(scene["omega"])
    o = {}
    for name, run in (("free", free), ("prescribed", prescribed)):
        res = last_cycle_orders(run["time"], run["Fz_joint"], np.abs(run["whirl_angle"]), (1, 3))
        o[name] = {f"order{k}": {"amplitude": float(res[k][0]), "phase_deg": float(res[k][1])}
                   for k in (1, 3)}
    a3, p3 = o["free"]["order3"]["amplitude"], o["prescribed"]["order3"]["amplitude"]
    rel = a3 / p3 - 1 if p3 > 0 else math.inf
    F = scene_mod.pressing_load(scene["F_press"], scene.get("torque", 0.0), scene["s"])
    fx = {name: float(np.mean(run["Fx"][_last_cycle(run)]) / F - 1)
          for name, run in (("free", free), ("prescribed", prescribed))}
    return {"Fz_joint": o, "order3_rel": float(rel), "fx_rel": fx,
            "superposition_holds": bool(abs(rel) <= SUPERPOSITION_TOL),
            "tolerance": SUPERPOSITION_TOL, "loads": loads_of(free, scene),
            "orbit": orbit_of(free, scene), "omega": w}


def format_spider(b: dict) -> str:
    """compare's lines for a free spider (spider_comparison's result)."""
    f, p = b["Fz_joint"]["free"], b["Fz_joint"]["prescribed"]
    ld, ob = b["loads"], b["orbit"]
    return "\n".join([
        "free spider against the prescribed one (Fz_joint, the housing's thrust; last whole "
        "cycle):",
        f"{'':8s}{'free':>22s}{'prescribed':>22s}",
        *(f"{'order ' + str(k):8s}{f[f'order{k}']['amplitude']:11.3f} N "
          f"{f[f'order{k}']['phase_deg']:7.2f}°{p[f'order{k}']['amplitude']:11.3f} N "
          f"{p[f'order{k}']['phase_deg']:7.2f}°" for k in (1, 3)),
        f"order 3 free / prescribed - 1: {100 * b['order3_rel']:+.2f} % "
        f"(superposition {'holds' if b['superposition_holds'] else 'does NOT hold'} within "
        f"{100 * b['tolerance']:g} %)",
        f"trunnion loads: {100 * ld['low_rel']:+.2f} % to {100 * ld['high_rel']:+.2f} % of "
        f"torque / (3 s) = {ld['nominal']:.1f} N; roller 1's mean Fx against it: prescribed "
        f"{100 * b['fx_rel']['prescribed']:+.2f} %, free {100 * b['fx_rel']['free']:+.2f} %",
        f"spider orbit at 2x in the housing: {1e3 * ob['amplitude']:.4f} mm at "
        f"{ob['phase_deg']:+.2f}° (Eq. 5: e = {1e3 * ob['e']:.4f} mm at 0°), at most "
        f"{1e6 * ob['off_circle']:.2f} um off Eq. (5)'s circle"])
