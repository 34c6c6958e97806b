"""The fast models against the full one over the driveline envelope (issue 67 point 5): a
quasi-random grid of scenes, each run with a bearing of the contact model or the analytic model,
orders 1 and 3 of one roller's Fz.  benchmarks/row_grid.py prints the table in
docs/validation.md; tests/test_row_mechanism.py holds the lumped row to it.

Scenes: a Halton sequence over the joint angle 2-25 deg, the load per roller 0.3-45 kN
(logarithmic), the whirl 2-30 Hz (logarithmic), the joints of joints/ and drive or coast (the
pressing load's sign).  Each run: three whirl cycles from the start at a 0.1 ms communication
step, in process; orders over the last whole cycle.
"""
import math
import time
from pathlib import Path

import numpy as np

from reduced_model.joint import for_model, load_joint
from reduced_model.orders import last_cycle_orders
from reduced_model.scene import defaults, validate

JOINTS = sorted((Path(__file__).resolve().parents[1] / "joints").glob("*.toml"))
TABLE_DOC = Path(__file__).resolve().parents[1] / "docs" / "validation.md"   # its table
CYCLES = 3
DT = 1e-4


def halton(i, base):
    """The i-th (from 1) element of the van der Corput sequence in base, in [0, 1)."""
    f, r = 1.0, 0.0
    while i > 0:
        f /= base
        r += f * (i % base)
        i //= base
    return r


def scene(i):
    """Scene i (from 1): (joint file, theta [rad], pressing load per roller [N], < 0 coast,
    omega [rad/s])."""
    theta = math.radians(2.0 + 23.0 * halton(i, 2))
    F = 300.0 * (45000.0 / 300.0) ** halton(i, 3)
    f = 2.0 * (30.0 / 2.0) ** halton(i, 5)
    joint = JOINTS[int(halton(i, 7) * len(JOINTS))]
    sign = 1.0 if halton(i, 11) < 0.5 else -1.0
    return joint, theta, sign * F, 2.0 * math.pi * f


def _steps(omega):
    return int(round(CYCLES * 2 * math.pi / abs(omega) / DT))


def contact_orders(path, theta, F, omega, bearing, **over):
    """{1: (amplitude [N], phase [deg]), 3: ...} of Fz of one roller of the contact model with
    ``bearing`` (0 ideal, 1 lumped, 2 needle-resolved) in the scene; over: its parameters other
    than their defaults."""
    from tripod_model.model import ContactModel
    m = ContactModel(dict(for_model(load_joint(path), "contact"), bearing=bearing, theta=theta,
                          omega=omega, F_press=F, **over))
    t, fz, x = [], [], []
    for _ in range(_steps(omega)):
        o = m.step(DT, theta, omega, F)
        t.append(m.time)
        fz.append(o["Fz"])
        x.append(m.whirl_angle)
    return last_cycle_orders(np.array(t), np.array(fz), np.array(x), (1, 3))


def joint_orders(path, theta, F, omega, bearing):
    """Orders 1 and 3 of Fz_joint and of roller 1's Fz (as contact_orders gives them) of the
    three-roller joint, spider prescribed: {"joint": {...}, "roller": {...}}."""
    from tripod_model.model import JointModel
    m = JointModel(dict(for_model(load_joint(path), "contact"), bearing=bearing, theta=theta,
                        omega=omega, F_press=F, n_rollers=3))
    t, fj, f1, x = [], [], [], []
    for _ in range(_steps(omega)):
        o = m.step(DT, theta, omega, F)
        t.append(m.rollers[0].time)
        fj.append(o["Fz_joint"])
        f1.append(o["Fz"])
        x.append(m.rollers[0].whirl_angle)
    t, x = np.array(t), np.array(x)
    return {"joint": last_cycle_orders(t, np.array(fj), x, (1, 3)),
            "roller": last_cycle_orders(t, np.array(f1), x, (1, 3))}


def analytic_orders(path, theta, F, omega, **over):
    """The same orders of the analytic model (one roller) in the scene; over: its parameters
    other than their defaults (needle_row = False: the ideal bearing's traverse model)."""
    from reduced_model.analytic_model import AnalyticModel
    from reduced_model.analytic_kernel import INPUT_NAMES
    values = dict(defaults("analytic"), **for_model(load_joint(path), "analytic"), theta=theta,
                  omega=omega, F_press=F, n_rollers=1, **over)
    m = AnalyticModel(values)
    inputs = [values[n] for n in INPUT_NAMES]
    t, fz, x = [], [], []
    for k in range(_steps(omega)):
        m.step(DT, k * DT, inputs)
        o = m.outputs()
        t.append((k + 1) * DT)
        fz.append(o["Fz"])
        x.append(o["whirl_angle"])
    return last_cycle_orders(np.array(t), np.array(fz), np.array(x), (1, 3))


def off(o, ref, k):
    """Order k of o off ref's: the complex difference over ref's amplitude [%]."""
    z = [a * np.exp(1j * math.radians(p)) for a, p in (o[k], ref[k])]
    return 100.0 * abs(z[0] - z[1]) / ref[k][0]


# the table's head (docs/validation.md) and its columns after the resolved row's: (label, how
# the scene is run)
TABLE_HEAD = ("| # | joint | theta [deg] | load a roller [kN] | whirl [Hz] | resolved: order 1, "
              "order 3 [N] | ideal: order 1, 3 off | lumped: order 1, 3 off | analytic: order 1, "
              "3 off | analytic, ideal bearing: order 1, 3 off | wall, resolved [s] |")
COLUMNS = (("ideal", "contact", 0), ("lumped", "contact", 1), ("analytic", "analytic", True),
           ("analytic, ideal bearing", "analytic", False))


def scene_orders(i):
    """Scene i (from 1) run by the resolved row and each of COLUMNS: {"resolved": orders,
    label: orders, ..., "wall": the resolved run's wall time [s]}."""
    path, theta, F, omega = scene(i)
    t0 = time.perf_counter()
    out = {"resolved": contact_orders(path, theta, F, omega, 2)}
    out["wall"] = time.perf_counter() - t0
    for label, model, arg in COLUMNS:
        out[label] = (contact_orders(path, theta, F, omega, arg) if model == "contact" else
                      analytic_orders(path, theta, F, omega, needle_row=arg))
    return out


def inside_checked_range(i):
    """Whether scene i lies inside the analytic model's checked range (analytic_kernel.
    CHECKED_RANGES, as the analytic FMU's notes judge it)."""
    from reduced_model import analytic_kernel as K
    from reduced_model.traverse import operating_point, params_array
    path, theta, F, omega = scene(i)
    sc = validate(dict(defaults("analytic"), **for_model(load_joint(path), "analytic"),
                       theta=theta, omega=omega, F_press=F), "analytic")
    T, O = params_array(sc), operating_point(sc)
    return all(K.inside(k, v, v) for k, v in
               ((k, K.checked_value(T, O, k)) for k in range(len(K.CHECKED_RANGES))))


def markdown_row(i, r):
    """Scene i's row of docs/validation.md's table from scene_orders' r."""
    path, theta, F, omega = scene(i)
    ref = r["resolved"]
    cells = [f"{off(r[label], ref, 1):.1f} %, {off(r[label], ref, 3):.1f} %"
             for label, _m, _a in COLUMNS]
    return (f"| {i} | {path.stem} | {math.degrees(theta):.1f} | {F / 1e3:+.2f} | "
            f"{omega / 2 / math.pi:.1f} | {ref[1][0]:.2f}, {ref[3][0]:.2f} | "
            + " | ".join(cells) + f" | {r['wall']:.0f} |")
