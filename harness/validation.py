"""The reduced traverse model against the contact model over a grid of scenes (docs/validation.md).

Contact model in process (ideal bearing, traverse on), run whole whirl cycles until Fz_mod is
periodic (reduced_model.steady); the reduced traverse model's periodic solution; Eqs. (18)-(27)
in closed form.  Order 3 of Fz_mod, one roller.
"""
from __future__ import annotations

import math

import numpy as np

from reduced_model import scene as scene_mod
from reduced_model.orders import last_cycle_orders
from reduced_model.steady import MAX_CYCLES, MIN_CYCLES, REL_TOL, cycle_change, settled
from reduced_model.thrust import closed_form
from reduced_model.traverse import INERTIA_LIMIT, Traverse, inertia_ratio

from .fmus import ROOT

DEG = math.pi / 180
# the micro-slip scene and the paper's scene, then a low-discrepancy grid over the
# ranges of GRID_RANGES: theta 2-25 deg, whirl 0.5-50 Hz, F_press 300-50000 N,
# mu_groove 0.03-0.12, clearance 0.05-0.8 mm
NAMED = {
    "paper (section 3.1)": {},
    "small angle, wide groove": {"theta": 3 * DEG, "omega": 50 * math.pi, "F_press": 1500.0,
                                 "mu_groove": 0.09, "r_groove": 0.0196},
    "2 deg, 0.7 mm clearance": {"theta": 2 * DEG, "omega": 20 * math.pi, "F_press": 2000.0,
                                "mu_groove": 0.10, "r_groove": 0.0197},
}
GRID_N = 40
PLUNGE_N = 12     # more scenes over the same ranges with a plunge speed in PLUNGE_RANGE
# the paper's joint: the ranges the grid is drawn over, (quantity, unit, lowest, highest)
GRID_RANGES = (("theta", "deg", 2.0, 25.0), ("whirl", "Hz", 0.5, 50.0),
               ("pressing load", "N", 300.0, 50000.0), ("mu_groove", "", 0.03, 0.12),
               ("groove clearance", "mm", 0.05, 0.8))
PLUNGE_RANGE = (-0.1, 0.1)   # [m/s] the plunge speeds of the grid's plunging scenes


def grid() -> dict:
    """{label: overrides} of the validation grid (Halton sequence, not scrambled: the same
    scenes on every machine)."""
    from scipy.stats import qmc
    (th0, th1), (f0, f1), (p0, p1), (mu0, mu1), (c0, c1) = ((lo, hi) for _, _, lo, hi in
                                                            GRID_RANGES)
    r = scene_mod.BY_NAME["r_roller"].default
    out = dict(NAMED)
    for i, u in enumerate(qmc.Halton(5, scramble=False).random(GRID_N + 1)[1:]):
        # linear in theta and mu_groove, logarithmic in whirl, load and clearance
        ov = {"theta": (th0 + (th1 - th0) * u[0]) * DEG,
              "omega": 2 * math.pi * f0 * (f1 / f0) ** u[1],
              "F_press": p0 * (p1 / p0) ** u[2], "mu_groove": mu0 + (mu1 - mu0) * u[3],
              "r_groove": r + 1e-3 * c0 * (c1 / c0) ** u[4]}
        out[f"grid {i + 1}"] = ov
    # the same ranges with the spider plunging (a 6-dimensional sequence of its own)
    v0, v1 = PLUNGE_RANGE
    for i, u in enumerate(qmc.Halton(6, scramble=False).random(PLUNGE_N + 1)[1:]):
        ov = {"theta": (th0 + (th1 - th0) * u[0]) * DEG,
              "omega": 2 * math.pi * f0 * (f1 / f0) ** u[1],
              "F_press": p0 * (p1 / p0) ** u[2], "mu_groove": mu0 + (mu1 - mu0) * u[3],
              "r_groove": r + 1e-3 * c0 * (c1 / c0) ** u[4],
              "plunge_speed": v0 + (v1 - v0) * u[5]}
        out[f"plunge {i + 1}"] = ov
    return out


def run_periodic(sc: dict, signal: str, per_cycle: int, max_cycles: int):
    """The contact model (JointModel) on a validated scene, whole whirl cycles of per_cycle
    steps until ``signal`` is periodic (reduced_model.steady), at most max_cycles: (its outputs
    by name as arrays with "time" [s], cycles used, settled)."""
    from tripod_model.model import JointModel
    th, w, F, vp = sc["theta"], sc["omega"], sc["F_press"], sc["plunge_speed"]
    m = JointModel(sc)
    dt = 2 * math.pi / w / per_cycle
    rows = []
    ok = False
    for c in range(1, max_cycles + 1):
        rows += [m.step(dt, th, w, F, 0.0, vp) for _ in range(per_cycle)]
        if c >= MIN_CYCLES:
            t = dt * np.arange(1, len(rows) + 1)
            ok = settled(cycle_change(t, np.array([r[signal] for r in rows]), w * t), REL_TOL)
            if ok:
                break
    out = {k: np.array([r[k] for r in rows]) for k in rows[0]}
    out["time"] = dt * np.arange(1, len(rows) + 1)
    return out, c, ok


def contact_orders(overrides: dict, per_cycle: int = 2000, max_cycles: int = 3 * MAX_CYCLES):
    """Orders 1 and 3 of the contact model's Fz_mod over its last whole cycle once periodic:
    ({k: (amplitude N, phase deg)}, cycles used, settled)."""
    sc = scene_mod.validate(dict(overrides, bearing=0, traverse=True), "contact")
    r, c, ok = run_periodic(sc, "Fz_mod", per_cycle, max_cycles)
    return last_cycle_orders(r["time"], r["Fz_mod"], sc["omega"] * r["time"], (1, 3)), c, ok


def grid_rows(scenes: dict | None = None) -> list[dict]:
    """One row a scene: the contact model, Eqs. (18)-(27) and the traverse model, order 3."""
    rows = []
    for label, ov in (scenes or grid()).items():
        sc = scene_mod.validate(scene_mod.analytic_counterpart(ov), "analytic")
        oc, cycles, ok = contact_orders(ov)
        tr = Traverse(sc)
        o3 = tr.orders()[3]
        e27 = closed_form(sc)["total"][3]
        rows.append({"scene": label, "theta_deg": sc["theta"] / DEG,
                     "whirl_hz": sc["omega"] / (2 * math.pi), "F_press": sc["F_press"],
                     "mu_groove": sc["mu_groove"],
                     "clearance_mm": 1e3 * (sc["r_groove"] - sc["r_roller"]),
                     "plunge_speed": sc["plunge_speed"],
                     "regime": tr.regime(), "cycles": cycles, "settled": ok,
                     "contact": oc[3], "eq27": e27, "traverse": o3,
                     "eq27_rel": e27[0] / oc[3][0] - 1, "traverse_rel": o3[0] / oc[3][0] - 1,
                     "traverse_dphase": _dphase(o3[1], oc[3][1]),
                     "inertia": inertia_ratio(sc),
                     "eq27_dphase": _dphase(e27[1], oc[3][1])})
    return rows


def _dphase(a, b):
    return float((a - b + 180.0) % 360.0 - 180.0)


def summary(rows) -> dict:
    """Errors of the traverse model over the scenes inside the checked range (the roller's
    inertia ratio at most traverse.INERTIA_LIMIT), and the worst of those beyond it."""
    inside = [r for r in rows if r["inertia"] <= INERTIA_LIMIT and r["plunge_speed"] == 0]
    plunging = [r for r in rows if r["inertia"] <= INERTIA_LIMIT and r["plunge_speed"] != 0]
    beyond = [r for r in rows if r["inertia"] > INERTIA_LIMIT]
    a = np.abs([r["traverse_rel"] for r in inside])
    b = np.abs([r["eq27_rel"] for r in inside])
    p = np.abs([r["traverse_dphase"] for r in inside])
    return {"median_rel": float(np.median(a)), "worst_rel": float(a.max()),
            "worst_dphase": float(p.max()), "eq27_median_rel": float(np.median(b)),
            "eq27_worst_rel": float(b.max()), "n": len(inside), "n_beyond": len(beyond),
            "beyond_worst_rel": max((abs(r["traverse_rel"]) for r in beyond), default=0.0),
            "beyond_worst_dphase": max((abs(r["traverse_dphase"]) for r in beyond),
                                       default=0.0),
            "n_plunging": len(plunging),
            "plunging_median_rel": float(np.median([abs(r["traverse_rel"]) for r in plunging]))
            if plunging else 0.0,
            "plunging_worst_rel": max((abs(r["traverse_rel"]) for r in plunging), default=0.0),
            "plunging_worst_dphase": max((abs(r["traverse_dphase"]) for r in plunging),
                                         default=0.0)}


def markdown(rows) -> str:
    s = summary(rows)
    out = ["| scene | theta [deg] | whirl [Hz] | F_press [N] | mu_groove | clearance [mm] "
           "| plunge [m/s] | inertia ratio | regime | cycles | contact order 3 [N, deg] "
           "| Eqs. 18-27 | traverse model |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        beyond = " (beyond)" if r["inertia"] > INERTIA_LIMIT else ""
        out.append(
            f"| {r['scene']} | {r['theta_deg']:.1f} | {r['whirl_hz']:.1f} | {r['F_press']:.0f} "
            f"| {r['mu_groove']:.3f} | {r['clearance_mm']:.3f} | {r['plunge_speed']:+.3f} "
            f"| {r['inertia']:.3g}{beyond} "
            f"| {r['regime']} "
            f"| {r['cycles']}{'' if r['settled'] else ' (cap)'} "
            f"| {r['contact'][0]:.3f} at {r['contact'][1]:.1f} "
            f"| {100 * r['eq27_rel']:+.1f} %, {r['eq27_dphase']:+.1f} deg "
            f"| {100 * r['traverse_rel']:+.1f} %, {r['traverse_dphase']:+.1f} deg |")
    out += ["", f"Traverse model, order 3 amplitude over the {s['n']} scenes without plunge "
            f"inside the checked range (inertia ratio m r (2 omega)^2 / load up to "
            f"{INERTIA_LIMIT:g}): median error "
            f"{100 * s['median_rel']:.1f} %, worst {100 * s['worst_rel']:.1f} %; phase within "
            f"{s['worst_dphase']:.1f} deg. Eqs. (18)-(27): median {100 * s['eq27_median_rel']:.1f} %, "
            f"worst {100 * s['eq27_worst_rel']:.0f} %. The {s['n_plunging']} plunging scenes "
            f"inside it: median {100 * s['plunging_median_rel']:.1f} %, worst "
            f"{100 * s['plunging_worst_rel']:.1f} %, phase within "
            f"{s['plunging_worst_dphase']:.1f} deg. The {s['n_beyond']} scenes beyond that "
            f"ratio: worst {100 * s['beyond_worst_rel']:.1f} %, phase within "
            f"{s['beyond_worst_dphase']:.1f} deg."]
    return "\n".join(out)


# joints of every size: a low-discrepancy grid over the pitch circle, the proportions about it,
# and today's scene ranges (the load per roller with the square of the size: a joint's torque
# capacity grows with its cube).  Published proportions (EP1707834): the outer roller's
# diameter 0.80-0.90 of the pitch circle's; the roller's wall about 0.11 of it (the paper's
# joint as the project assumes it: 0.15); the groove clearance 0.05-0.8 mm at the paper's roller.
SIZE_N = 48
SIZE_RANGES = (("pitch circle diameter", "mm", 30.0, 75.0),
               ("r_roller / s", "", 0.80, 0.90),
               ("r_bore / r_roller", "", 0.60, 0.78),
               ("clearance / r_roller", "", 0.05 / 19.0, 0.8 / 19.0),
               ("theta", "deg", 2.0, 25.0),
               ("whirl", "Hz", 0.5, 50.0),
               ("load / size^2", "N", 300.0, 50000.0),
               ("mu_groove", "", 0.03, 0.12))


def size_scene(u) -> dict:
    """The scene (overrides) at the unit point u of SIZE_RANGES: linear in the proportions,
    the angle and friction, logarithmic in size, clearance, whirl and load."""
    lin = lambda k: SIZE_RANGES[k][2] + (SIZE_RANGES[k][3] - SIZE_RANGES[k][2]) * u[k]
    log = lambda k: SIZE_RANGES[k][2] * (SIZE_RANGES[k][3] / SIZE_RANGES[k][2]) ** u[k]
    d = scene_mod.defaults("contact")
    f = log(0) / (2e3 * d["s"])                   # the size against the paper's joint
    s = d["s"] * f
    r = lin(1) * s
    rb = lin(2) * r
    return {"s": s, "r_roller": r, "r_bore": rb, "r_groove": r * (1.0 + log(3)),
            "m_roller": d["m_roller"] * f ** 3, "roller_width": d["roller_width"] * f,
            "d_needle": d["d_needle"] * f, "l_needle": d["l_needle"] * f,
            "r_trunnion": rb - d["d_needle"] * f, "theta": lin(4) * DEG,
            "omega": 2 * math.pi * log(5), "F_press": log(6) * f * f, "mu_groove": lin(7)}


def size_grid() -> dict:
    """{label: overrides}: the scaled joints of the example files and SIZE_N scenes of a Halton
    sequence over SIZE_RANGES (not scrambled: the same scenes on every machine)."""
    from scipy.stats import qmc
    from reduced_model.joint import for_model, load_joint, EXAMPLES
    out = {f"{n} joint, paper's scene": for_model(load_joint(EXAMPLES / f"{n}.toml"), "contact")
           for n in ("small-car", "light-truck")}
    for i, u in enumerate(qmc.Halton(len(SIZE_RANGES), scramble=False).random(SIZE_N + 1)[1:]):
        out[f"size {i + 1}"] = size_scene(u)
    return out


def size_rows(scenes: dict | None = None) -> list[dict]:
    """One row a scene of the size grid: its groups (kernel.CHECKED_RANGES), the contact model
    and the traverse model, order 3 of Fz_mod."""
    from reduced_model import analytic_kernel as kernel
    from reduced_model.traverse import operating_point, params_array
    rows = []
    for label, ov in (scenes or size_grid()).items():
        sc = scene_mod.validate(scene_mod.analytic_counterpart(ov), "analytic")
        oc, cycles, ok = contact_orders(ov)
        tr = Traverse(sc)
        o3 = tr.orders()[3]
        P, O = params_array(sc), operating_point(sc)
        groups = {name: kernel.checked_value(P, O, k)
                  for k, (name, *_) in enumerate(kernel.CHECKED_RANGES)}
        rows.append({"scene": label, "pitch_mm": 2e3 * sc["s"],
                     "theta_deg": sc["theta"] / DEG, "whirl_hz": sc["omega"] / (2 * math.pi),
                     "F_press": sc["F_press"], "groups": groups, "regime": tr.regime(),
                     "cycles": cycles, "settled": ok, "contact": oc[3], "traverse": o3,
                     "traverse_rel": o3[0] / oc[3][0] - 1,
                     "traverse_dphase": _dphase(o3[1], oc[3][1]),
                     "outside": kernel_outside(P, O)})
    return rows


def kernel_outside(P, O) -> list:
    """The checked groups (kernel.CHECKED_RANGES) the scene at (P, O) leaves."""
    from reduced_model import analytic_kernel as kernel
    return [name for k, (name, *_) in enumerate(kernel.CHECKED_RANGES)
            if not kernel.inside(k, kernel.checked_value(P, O, k),
                                 kernel.checked_value(P, O, k))]


def size_markdown(rows) -> str:
    from reduced_model import analytic_kernel as kernel
    names = [c[0] for c in kernel.CHECKED_RANGES if c[0] not in ("theta", "mu_groove",
                                                                  "plunge speed")]
    out = ["| scene | pitch circle [mm] | theta [deg] | whirl [Hz] | F_press [N] | "
           + " | ".join(names) + " | contact order 3 [N, deg] | traverse model |",
           "|---" * (6 + len(names)) + "|"]
    for r in rows:
        g = " | ".join(f"{r['groups'][n]:.3g}" for n in names)
        out.append(f"| {r['scene']}{' (outside)' if r['outside'] else ''} | {r['pitch_mm']:.1f} "
                   f"| {r['theta_deg']:.1f} | {r['whirl_hz']:.1f} | {r['F_press']:.0f} | {g} "
                   f"| {r['contact'][0]:.3f} at {r['contact'][1]:.1f} "
                   f"| {100 * r['traverse_rel']:+.1f} %, {r['traverse_dphase']:+.1f} deg |")
    inside = [r for r in rows if not r["outside"]]
    a = np.abs([r["traverse_rel"] for r in inside])
    p = np.abs([r["traverse_dphase"] for r in inside])
    worst = max(inside, key=lambda r: abs(r["traverse_rel"]))
    beyond = [r for r in rows if r["outside"]]
    left = sorted({g for r in beyond for g in r["outside"]})
    out += ["", f"Traverse model against the contact model, order 3 of Fz_mod, over the "
            f"{len(inside)} scenes inside the checked range: median "
            f"{100 * float(np.median(a)):.1f} %, worst {100 * float(a.max()):.1f} % "
            f"({worst['scene']}), phase within {float(p.max()):.1f} deg."
            + (f" The {len(beyond)} scenes outside it (leaving: {'; '.join(left)}): worst "
               f"{100 * max(abs(r['traverse_rel']) for r in beyond):.1f} %."
               if beyond else "")]
    return "\n".join(out)


# coast and reverse whirl: the paper's scene and the first grid scenes inside the checked range
# (whirl from 2 Hz: the FMUs run whole cycles until periodic), through both built FMUs
QUADRANT_N = 6
QUADRANTS = {"coast": (1, -1), "reverse": (-1, 1), "coast in reverse": (-1, -1)}


def quadrant_scenes() -> dict:
    """{label: overrides}: the paper's scene and QUADRANT_N grid scenes without plunge inside
    the checked range with a whirl of 2 Hz or more."""
    out = {"paper (section 3.1)": {}}
    for label, ov in grid().items():
        sc = scene_mod.validate(ov, "analytic")
        if (label.startswith("grid") and len(out) <= QUADRANT_N and
                inertia_ratio(sc) <= INERTIA_LIMIT and sc["omega"] >= 4 * math.pi):
            out[label] = ov
    return out


def fmu_order3(name: str, overrides: dict):
    """Order 3 of Fz_mod (amplitude N, phase deg) over the last whole cycle of the built FMU
    ``name`` (FMPy, a fresh process) run until periodic, the phase against the whirl angle's
    magnitude (reverse whirl turns the other way)."""
    from .fmus import ensure_fmu
    from .runs import run_settled
    if name == "TripodRollerAnalytic":
        overrides = scene_mod.analytic_counterpart(overrides)
    sc = scene_mod.validate(overrides, "analytic")
    w = abs(sc["omega"])
    r = run_settled(ensure_fmu(name), overrides, w, ["Fz_mod"], dt=2 * math.pi / w / 2000)
    return last_cycle_orders(r["time"], r["Fz_mod"], np.abs(r["whirl_angle"]), (3,))[3]


def quadrant_rows(scenes: dict | None = None) -> list[dict]:
    """Each scene in coast, reverse and coast in reverse: order 3 of Fz_mod, the analytic FMU
    against the contact FMU."""
    rows = []
    for label, ov in (scenes or quadrant_scenes()).items():
        sc = scene_mod.validate(ov, "analytic")
        for q, (sw, sf) in QUADRANTS.items():
            o = dict(ov, omega=sw * sc["omega"], F_press=sf * sc["F_press"])
            c, a = fmu_order3("TripodRoller", o), fmu_order3("TripodRollerAnalytic", o)
            rows.append({"scene": label, "quadrant": q, "theta_deg": sc["theta"] / DEG,
                         "whirl_hz": o["omega"] / (2 * math.pi), "F_press": o["F_press"],
                         "contact": c, "analytic": a, "rel": a[0] / c[0] - 1,
                         "dphase": _dphase(a[1], c[1])})
    return rows


def quadrant_markdown(rows) -> str:
    out = ["| scene | quadrant | theta [deg] | whirl [Hz] | F_press [N] | contact FMU order 3 "
           "[N, deg] | analytic FMU |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['scene']} | {r['quadrant']} | {r['theta_deg']:.1f} | "
                   f"{r['whirl_hz']:+.1f} | {r['F_press']:+.0f} | {r['contact'][0]:.3f} at "
                   f"{r['contact'][1]:.1f} | {100 * r['rel']:+.1f} %, {r['dphase']:+.1f} deg |")
    a = np.abs([r["rel"] for r in rows])
    p = np.abs([r["dphase"] for r in rows])
    out += ["", f"Analytic against contact FMU over the {len(rows)} coast and reverse runs: "
            f"order 3 amplitude median {100 * np.median(a):.1f} %, worst {100 * a.max():.1f} %; "
            f"phase within {p.max():.1f} deg."]
    return "\n".join(out)


# contact damping: the Hunt-Crossley term against the roller's slide ring (three rollers,
# 40 Hz, 300 N m, 8 deg: the 3 kHz line of Fz_joint), ideal and lumped bearing
DAMPING_SCENE = {"n_rollers": 3, "omega": 80 * math.pi, "torque": 300.0, "theta": 8 * DEG}
DAMPING_CASES = ({"contact_damping": 0.0}, {"contact_damping": 0.3}, {"contact_damping": 3.0},
                 {"contact_damping": 10.0}, {"bearing": 1, "contact_damping": 0.0},
                 {"bearing": 1, "contact_damping": 3.0})


def ring_and_orders(overrides: dict, stop=0.3, dt=2e-5):
    """The contact FMU (FMPy, a fresh process) at DAMPING_SCENE with ``overrides``: the largest
    line of Fz_joint between 1 and 10 kHz over the second half of the run (frequency Hz,
    amplitude N, Hann window) and orders 1 and 3 of Fz_joint over its last whole cycle."""
    from .fmus import ensure_fmu
    from .runs import run_fmu
    r = run_fmu(ensure_fmu("TripodRoller"), dict(DAMPING_SCENE, **overrides), stop_time=stop,
                output_interval=dt, outputs=["Fz_joint", "whirl_angle"])
    t, y = r["time"], r["Fz_joint"]
    late = y[t > stop / 2] - y[t > stop / 2].mean()
    spec = np.abs(np.fft.rfft(late * np.hanning(len(late)))) * 4 / len(late)
    f = np.fft.rfftfreq(len(late), dt)
    band = (f > 1e3) & (f < 1e4)
    i = int(np.argmax(spec[band]))
    o = last_cycle_orders(t, y, r["whirl_angle"], (1, 3))
    return {"ring_hz": float(f[band][i]), "ring": float(spec[band][i]), "order1": o[1],
            "order3": o[3]}


def damping_rows() -> list[dict]:
    return [dict(case, bearing=case.get("bearing", 0), **ring_and_orders(case))
            for case in DAMPING_CASES]


def damping_markdown(rows) -> str:
    out = ["| bearing | contact_damping [s/m] | slide ring in Fz_joint [Hz, N] | order 1 [N] "
           "| order 3 [N, deg] |", "|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['bearing']} | {r['contact_damping']:g} | {r['ring_hz']:.0f}, "
                   f"{r['ring']:.3f} | {r['order1'][0]:.2e} | {r['order3'][0]:.3f} at "
                   f"{r['order3'][1]:.2f} |")
    return "\n".join(out)


# the free spider against the prescribed one (spider = 1 against 0; harness.spider_superposition): the paper's
# scene and the first SPIDER_N scenes of the grid without plunge, each bearing the free spider
# takes, three rollers pressed by F_press each
SPIDER_N = 10
SPIDER_BEARINGS = (0, 1)


def spider_scenes() -> dict:
    """{label: overrides}: the paper's scene and SPIDER_N grid scenes without plunge."""
    out = {"paper (section 3.1)": {}}
    for label, ov in grid().items():
        if label.startswith("grid") and len(out) <= SPIDER_N:
            out[label] = ov
    return out


def joint_run(overrides: dict, per_cycle: int = 1000, max_cycles: int = 3 * MAX_CYCLES) -> dict:
    """A three-roller joint in process until Fz_joint is periodic (run_periodic): its outputs
    by name (arrays) with "time" [s], and "settled"."""
    sc = scene_mod.validate(dict(overrides, n_rollers=3), "contact")
    out, _, ok = run_periodic(sc, "Fz_joint", per_cycle, max_cycles)
    out["settled"] = ok
    return out


def spider_rows(scenes: dict | None = None) -> list[dict]:
    """One row a scene and bearing: the free spider against the prescribed one
    (harness.spider_superposition.spider_comparison)."""
    from .spider_superposition import spider_comparison
    rows = []
    for label, ov in (scenes or spider_scenes()).items():
        for bearing in SPIDER_BEARINGS:
            o = dict(ov, bearing=bearing)
            sc = scene_mod.validate(dict(o, n_rollers=3, spider=1), "contact")
            free, pres = joint_run(dict(o, spider=1)), joint_run(dict(o, spider=0))
            rows.append({"scene": label, "bearing": bearing, "theta_deg": sc["theta"] / DEG,
                         "whirl_hz": sc["omega"] / (2 * math.pi), "F_press": sc["F_press"],
                         "clearance_mm": 1e3 * (sc["r_groove"] - sc["r_roller"]),
                         "regime": Traverse(scene_mod.validate(ov, "analytic")).regime(),
                         "settled": bool(free["settled"] and pres["settled"]),
                         **spider_comparison(sc, free, pres)})
    return rows


def spider_markdown(rows) -> str:
    out = ["| scene | bearing | theta [deg] | whirl [Hz] | F_press [N] | clearance [mm] | "
           "regime | Fz_joint order 3: prescribed, free [N] | free / prescribed - 1 | order 1: "
           "prescribed, free [N] | mean Fx - F: prescribed, free [%] | loads [% of F] | orbit at "
           "2x / e, off the circle [um] |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        f, p = r["Fz_joint"]["free"], r["Fz_joint"]["prescribed"]
        ld, ob = r["loads"], r["orbit"]
        out.append(
            f"| {r['scene']} | {r['bearing']} | {r['theta_deg']:.1f} | {r['whirl_hz']:.1f} | "
            f"{r['F_press']:.0f} | {r['clearance_mm']:.2f} | {r['regime']} | "
            f"{p['order3']['amplitude']:.3f}, "
            f"{f['order3']['amplitude']:.3f} | {100 * r['order3_rel']:+.1f} %"
            f"{'' if r['superposition_holds'] else ' (beyond 5 %)'}"
            f"{'' if r['settled'] else ', not settled'} | "
            f"{p['order1']['amplitude']:.3f}, {f['order1']['amplitude']:.3f} | "
            f"{100 * r['fx_rel']['prescribed']:+.1f}, {100 * r['fx_rel']['free']:+.1f} | "
            f"{100 * ld['low_rel']:+.1f} to {100 * ld['high_rel']:+.1f} | "
            f"{ob['amplitude'] / ob['e']:.4f}, {1e6 * ob['off_circle']:.1f} |")
    for b in SPIDER_BEARINGS:
        rb = [r for r in rows if r["bearing"] == b]
        if not rb:
            continue
        a = np.abs([r["order3_rel"] for r in rb])
        out.append("")
        out.append(f"Bearing {b}: superposition (the prescribed joint's order 3 of Fz_joint) "
                   f"within 5 % of the free spider's in {sum(r['superposition_holds'] for r in rb)}"
                   f" of {len(rb)} scenes; |free / prescribed - 1| median {100 * np.median(a):.1f}"
                   f" %, worst {100 * a.max():.1f} %.")
    return "\n".join(out)


END = "<!-- end generated -->"
# docs/validation.md's generated blocks: (name, the table's generator)
BLOCKS = (("traverse grid", lambda: markdown(grid_rows())),
          ("quadrant grid", lambda: quadrant_markdown(quadrant_rows())),
          ("contact damping", lambda: damping_markdown(damping_rows())),
          ("spider grid", lambda: spider_markdown(spider_rows())))


def write_docs(path=ROOT / "docs" / "validation.md", names=None) -> str:
    """Regenerate the tables between their markers in docs/validation.md (those of BLOCKS named
    in ``names``; all by default)."""
    text = path.read_text()
    tables = []
    for name, table in BLOCKS:
        if names and name not in names:
            continue
        start = f"<!-- generated: {name} -->"
        i = text.index(start) + len(start)
        j = text.index(END, i)
        tables.append(table())
        text = text[:i] + "\n" + tables[-1] + "\n" + text[j:]
    path.write_text(text)
    return "\n\n".join(tables)


if __name__ == "__main__":
    import sys
    # python -m harness.validation ["block name" ...]: those blocks only (all by default)
    print(write_docs(names=sys.argv[1:] or None))
