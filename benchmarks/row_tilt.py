"""The roller's tilt on the row about e2 (the groove's axis): the experiment behind
docs/model.md's "The roller rocks on the row".

The groove's friction along the trunnion acts at the roller's rim, r_roller from its centre; its
moment about e2 (k_t2 b2 = -r_roller f_a + lever f_row, lumped row) rocks the roller on the row's
line contacts (k_t2 = k_r l^2 / 12). A rate b2' moves the groove contact along the trunnion by
-r_roller b2' on top of the slide: the friction acts through a compliance in series.

Runs, one roller, 10 Hz, three whirl cycles from the start, orders of Fz over the last one: the
ideal bearing; the lumped row with the needles' friction and rolling resistance off (only the
row's stiffness left), its tilt stiffness (both tilts: P_LT, l^2 / 12) as built and scaled by
10 and 100; the lumped row as built; the needle-resolved row (the reference). Columns: orders 1
and 3, the tilt about e2 (peak over the cycle, its order 2 amplitude), the groove contact's travel
r_roller b2 against the slide u (peaks), with the row's friction off the tilt stiffness fitted
over the last cycle against the lumped row's k_r l^2 / 12 at its mean offset, order 3 off the
resolved row's (complex).
Usage: python -m benchmarks.row_tilt [--loads 4500,45000] [--theta-deg 8,3] (about 1 min a
scene)
"""
import argparse
import math
import time

import numpy as np

from reduced_model.orders import last_cycle_orders
from tripod_model import contact, layout as K
from tripod_model.model import ContactModel

FRICTION_OFF = {"friction_needle": False, "rolling_resistance": False}
RUNS = (   # name, overrides, the tilt stiffness's scale
    ("ideal", {"bearing": 0}, 1.0),
    ("lumped, row friction off", dict(FRICTION_OFF, bearing=1), 1.0),
    ("lumped, row friction off, tilt stiffness x10", dict(FRICTION_OFF, bearing=1), 10.0),
    ("lumped, row friction off, tilt stiffness x100", dict(FRICTION_OFF, bearing=1), 100.0),
    ("lumped", {"bearing": 1}, 1.0),
    ("lumped, tilt stiffness x100", {"bearing": 1}, 100.0),
    ("resolved, row friction off", dict(FRICTION_OFF, bearing=2), 1.0),
    ("resolved", {"bearing": 2}, 1.0),
)


def groove_moment_e2(m, omega, theta, L):
    """The groove's moment on the roller of ContactModel m about e2 = a x e1 [N m] now (e1 the
    pressing direction x made normal to the trunnion axis a)."""
    L[K.L_KX] = math.nan
    contact.line_kinematics(m.Y[K.Y_X], omega, theta, m.P, L)
    a = np.array([L[K.L_AX], L[K.L_AY], L[K.L_AZ]])
    e1 = np.array([1.0, 0.0, 0.0]) - a[0] * a
    e2 = np.cross(a, e1 / np.linalg.norm(e1))
    r = m._res
    return float(np.dot([r[K.R_MX], r[K.R_MY], r[K.R_MZ]], e2))


def run(over, tilt_scale, F, theta, omega, cycles=3, dt=1e-4):
    """One run: per sample the time [s], whirl angle [rad], Fz [N], the tilt about e2 [rad],
    the slide along the trunnion [m] and the groove's moment about e2 [N m]; the lumped row's
    tilt stiffness scaled by tilt_scale."""
    m = ContactModel(dict(over, theta=theta, omega=omega, F_press=F))
    m.P[K.P_LT] *= tilt_scale
    L = np.full(K.L_LEN, np.nan)
    rows = []
    for _ in range(int(round(cycles * 2 * math.pi / omega / dt))):
        o = m.step(dt, theta, omega, F)
        rows.append((m.time, m.whirl_angle, o["Fz"], m.Y[K.Y_B2], m.Y[K.Y_U],
                     groove_moment_e2(m, omega, theta, L)))
    Fr, kr, kw, q = contact.row_load(m.P, m.Y[K.Y_E])
    return np.array(rows), m.P[K.P_R_ROLLER], kr * m.P[K.P_LT] / tilt_scale


def tilt_stiffness(a):
    """The tilt stiffness about e2 [N m/rad] fitted as b2 = b0 + M2 / k over the rows a (run's),
    with the residual's rms over the tilt's: what holds the roller when the groove's moment
    is the only one (the row's friction off)."""
    A = np.column_stack([a[:, 5], np.ones(len(a))])
    c, res, *_ = np.linalg.lstsq(A, a[:, 3], rcond=None)
    return 1.0 / c[0], math.sqrt(res[0] / len(a)) / a[:, 3].std()


def scene_table(F, theta, omega):
    lines = [f"Load {F / 1e3:g} kN, theta {math.degrees(theta):g} deg, "
             f"{omega / 2 / math.pi:g} Hz (orders of Fz on the groove, last of three cycles):",
             "",
             "| run | order 1 | order 3 | tilt about e2 (peak, order 2) | groove contact's travel "
             "r b2 / slide u (peaks) | tilt stiffness fitted / k_r l^2/12 (residual) "
             "| order 3 off resolved | wall |",
             "|---|---|---|---|---|---|---|---|"]
    out = []
    for name, over, scale in RUNS:
        t0 = time.perf_counter()
        a, r, k_lumped = run(over, scale, F, theta, omega)
        wall = time.perf_counter() - t0
        last = a[:, 1] >= a[-1, 1] - 2 * math.pi
        fit = "-"
        if over.get("friction_needle") is False and scale == 1.0:
            k, res = tilt_stiffness(a[last])
            fit = f"{k / k_lumped:.3f} ({100 * res:.0f} %)"
        o = last_cycle_orders(a[:, 0], a[:, 2], a[:, 1])
        b2 = last_cycle_orders(a[:, 0], a[:, 3], a[:, 1], orders=(2,))[2][0]
        z3 = o[3][0] * np.exp(1j * math.radians(o[3][1]))
        out.append((name, o, np.abs(a[last, 3]).max(), b2, r * np.abs(a[last, 3]).max(),
                    np.abs(a[last, 4]).max(), fit, z3, wall))
    ref = out[-1][7]
    fmt = lambda v: f"{v[0]:.1f} N at {v[1]:.1f} deg"   # noqa: E731
    for name, o, peak, b2, travel, slide, fit, z3, wall in out:
        lines.append(f"| {name} | {fmt(o[1])} | {fmt(o[3])} | {peak:.2e} rad, {b2:.2e} rad | "
                     f"{travel * 1e6:.1f} um / {slide * 1e6:.1f} um | {fit} | "
                     f"{100 * abs(z3 - ref) / abs(ref):.1f} % | {wall:.0f} s |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], allow_abbrev=False)
    ap.add_argument("--loads", default="4500,45000", help="pressing loads per roller [N]")
    ap.add_argument("--theta-deg", default="8,3", help="joint angles [deg]")
    ap.add_argument("--whirl-hz", type=float, default=10.0, help="whirl rate [Hz]")
    args = ap.parse_args()
    for deg in (float(v) for v in args.theta_deg.split(",")):
        for F in (float(v) for v in args.loads.split(",")):
            print(scene_table(F, math.radians(deg), 2 * math.pi * args.whirl_hz), flush=True)
            print(flush=True)


if __name__ == "__main__":
    main()
