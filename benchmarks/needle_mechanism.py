"""What the needle row does to the thrust: the experiments behind docs/model.md's "What the
needle row does to the thrust".

One roller, 10 Hz whirl, three whirl cycles from the start, orders over the last whole one. Each
run's groove force on the roller is split in the contact plane: its friction along the trunnion
axis (the paper's mechanism, Eqs. 18-27: the thrust is this friction times sin phi) and along the
rolling direction (the traction that turns the roller against the row's rolling resistance, the
spin moment's share and the spin inertia).  The two parts add up to Fz exactly (the normal has no
z component).  Runs: the needle-resolved row with every law on and with one law off at a time,
the lumped row and the ideal bearing, at the loads given.

Prints a Markdown table per scene: orders 1 and 3 of Fz, order 3 of each part, the roller's
steering tilt (about the pressing direction e1) and its slide along the trunnion, and each run's
order 3 off the resolved row's (complex: amplitude and phase together).
Usage: python benchmarks/needle_mechanism.py [--loads 4500,45000] [--theta-deg 8] [--quick]
(about 2 min a load for the resolved runs once numba's cache is warm; --quick: the resolved row
with every law on, the lumped row and the ideal bearing only)
"""
import argparse
import math
import time

import numpy as np

from reduced_model.orders import last_cycle_orders
from tripod_model import contact, layout as K
from tripod_model.model import ContactModel

RUNS = (   # name, overrides of the scene's parameters
    ("resolved", {"bearing": 2}),
    ("resolved, spin_moment off", {"bearing": 2, "spin_moment": False}),
    ("resolved, friction_needle off", {"bearing": 2, "friction_needle": False}),
    ("resolved, rolling_resistance off", {"bearing": 2, "rolling_resistance": False}),
    ("lumped", {"bearing": 1}),
    ("lumped, spin_moment off", {"bearing": 1, "spin_moment": False}),
    ("lumped, rolling_resistance off", {"bearing": 1, "rolling_resistance": False}),
    ("ideal", {"bearing": 0}),
)
QUICK = ("resolved", "lumped", "ideal")


def friction_parts(m, L):
    """The groove's friction on the roller of ContactModel m now, split along the trunnion
    axis a and the rolling direction n x a (both in the contact plane): the two parts of the
    thrust on the groove [N] (they sum to Fz)."""
    r = m._res
    n = np.array([r[K.R_NX], r[K.R_NY], 0.0])
    f = np.array([r[K.R_FX], r[K.R_FY], r[K.R_FZ]]) + r[K.R_FN] * n   # less the normal force
    a = np.array([L[K.L_AX], L[K.L_AY], L[K.L_AZ]])
    ah = a - a.dot(n) * n
    ah /= np.linalg.norm(ah)
    rh = np.cross(n, ah)
    return -f.dot(ah) * ah[2], -f.dot(rh) * rh[2]


def run(over, F, theta, omega, cycles=3, dt=1e-4):
    """One run: per sample the time [s], whirl angle [rad], Fz [N], the thrust's axial and
    rolling parts [N], the roller's tilt about e1 [rad] and slide along the trunnion [m]."""
    p = {"theta": theta, "omega": omega, "F_press": F}
    p.update(over)
    m = ContactModel(p)
    L = np.full(K.L_LEN, np.nan)
    rows = []
    for _ in range(int(round(cycles * 2 * math.pi / omega / dt))):
        o = m.step(dt, theta, omega, F)
        L[K.L_KX] = math.nan
        contact.line_kinematics(m.Y[K.Y_X], omega, theta, m.P, L)
        ax, ro = friction_parts(m, L)
        rows.append((m.time, m.whirl_angle, o["Fz"], ax, ro, m.Y[K.Y_B1], m.Y[K.Y_U]))
    return np.array(rows)


def phasor(o):
    a, p = o
    return a * np.exp(1j * math.radians(p))


def scene_table(F, theta, omega, names):
    lines = [f"Load {F / 1e3:g} kN, theta {math.degrees(theta):g} deg, "
             f"{omega / 2 / math.pi:g} Hz (orders of Fz on the groove, last of three cycles):",
             "",
             "| run | order 1 | order 3 | axial-friction part, order 3 | rolling-traction part, "
             "order 3 | tilt about e1 (peak) | slide u (peak) | order 3 off resolved | wall |",
             "|---|---|---|---|---|---|---|---|---|"]
    ref = None
    for name, over in RUNS:
        if name not in names:
            continue
        t0 = time.perf_counter()
        a = run(over, F, theta, omega)
        wall = time.perf_counter() - t0
        t, x = a[:, 0], a[:, 1]
        o = {k: last_cycle_orders(t, a[:, k], x) for k in (2, 3, 4)}
        last = x >= x[-1] - 2 * math.pi
        z3 = phasor(o[2][3])
        if ref is None:
            ref = z3
        off = abs(z3 - ref) / abs(ref)
        fmt = lambda v: f"{v[0]:.1f} N at {v[1]:.1f} deg"   # noqa: E731
        lines.append(f"| {name} | {fmt(o[2][1])} | {fmt(o[2][3])} | {fmt(o[3][3])} | "
                     f"{fmt(o[4][3])} | {np.abs(a[last, 5]).max():.2e} rad | "
                     f"{np.abs(a[last, 6]).max() * 1e6:.1f} um | {100 * off:.1f} % | "
                     f"{wall:.0f} s |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], allow_abbrev=False)
    ap.add_argument("--loads", default="4500,45000", help="pressing loads per roller [N]")
    ap.add_argument("--theta-deg", type=float, default=8.0, help="joint angle [deg]")
    ap.add_argument("--whirl-hz", type=float, default=10.0, help="whirl rate [Hz]")
    ap.add_argument("--quick", action="store_true", help="resolved, lumped and ideal only")
    args = ap.parse_args()
    names = QUICK if args.quick else tuple(n for n, _ in RUNS)
    for F in (float(v) for v in args.loads.split(",")):
        print(scene_table(F, math.radians(args.theta_deg), 2 * math.pi * args.whirl_hz, names))
        print()


if __name__ == "__main__":
    main()
