"""The needle row's terms in the reduced traverse model, tried before they are built in
(issue 67 point 3): how much of the resolved row's effect on orders 1 and 3 two terms carry.

The reduced traverse model (reduced_model/traverse.py, T1-T6) with the row's two laws added the
way the lumped row has them (docs/model.md, "What the needle row does to the thrust"), nothing
fitted:

- T2 + rolling resistance (Eq. 12): the moment mu_rolling q r_bore tanh(3 v_r / v_st) against
  the roller's spin relative to the trunnion, v_r = (z'/r - psi') r_bore, psi the trunnion's
  yaw (Eq. 3) and q the row's summed needle loads (oppoint.row_sums, Eq. 17 with clearance);
- T1 + the needles' sliding friction: mu_needle q tanh(3 u_r / (2 v_st)) along the trunnion
  against the roller's slide relative to the trunnion's material, u_r = rho_c p' - d' (T4's
  slide less Eq. 7's stroke d'; half the slip at each of a needle's two contacts);
- optionally (`--tilt`) the spin moment carried by that friction alone, as a tilt about the
  pressing direction whose slip across the needles uses up their axial friction.

The slide is marched by T4's trapezoidal rule over whole cycles from the groove bottom (six
cycles, 720 steps a cycle), T6 with the friction along the trunnion in place of p.  Each variant
is compared with the needle-resolved row (run here: benchmarks/needle_mechanism.run), orders of
Fz over the last cycle, complex differences.  Prints a Markdown table.
Usage: python -m benchmarks.reduced_row [--tilt] (about 3 min: four resolved runs of 15-20 s)
"""
import argparse
import math
import time

import numpy as np
from scipy.optimize import brentq

from benchmarks.needle_mechanism import phasor, run
from reduced_model import equations as E, scene as S
from reduced_model.friction import spin_moment
from reduced_model.orders import last_cycle_orders, order_component
from reduced_model.traverse import operating_point
from tripod_model import layout as K, oppoint
from tripod_model.contact import trunnion_axial, trunnion_yaw
from tripod_model.roller_setup import PARAM_NAMES, kernel_params

SCENES = ((8.0, 4500.0), (8.0, 45000.0), (3.0, 4500.0), (3.0, 45000.0))   # deg, N a roller
VARIANTS = (("reduced traverse model", False, False, False),
            ("+ rolling resistance", False, True, False),
            ("+ sliding friction", True, False, False), ("+ both", True, True, False))
LINE = [(k + 0.5) / 7 - 0.5 for k in range(7)]   # the line's points along a needle [l]


def row_q(sc, F):
    """The row's summed needle loads q [N] at the pressing load F [N] (Eq. 17 over the row)."""
    T = np.array([float(sc[n]) for n in PARAM_NAMES])
    P = np.zeros(K.P_LEN)
    kernel_params(T, P)
    a = brentq(lambda a: oppoint.row_sums(P, a)[0] - F, P[K.P_NEEDLE_CLEARANCE] * (1 + 1e-12),
               1e-3)
    return oppoint.row_sums(P, a)[3]


def _line(c, k, sa, b, length):
    """Axial force and moment about e1 of the line of needle contacts at axial slip sa [m/s]
    and tilt rate b [rad/s] about e1 (the tanh law on each point's 2-D slip)."""
    fa = m1 = 0.0
    for d in LINE:
        st = d * length * b
        v = math.hypot(sa, st)
        if v > 0.0:
            g = math.tanh(k * v) / v
            fa += c * g * sa
            m1 += c * g * st * d * length
    return fa, m1


def row_axial(mq, k, sa, ms, length):
    """The needles' axial friction [N] at slip sa [m/s] (mq = mu_needle q [N]); with ms > 0 [N m]
    the line also carries the spin moment ms by a tilt about e1 that friction alone resists."""
    if ms <= 0.0:
        return mq * math.tanh(k * sa)
    c = mq / len(LINE)
    if ms >= c * length * sum(abs(d) for d in LINE):
        return 0.0                  # the line cannot hold it: the tilt takes all the friction
    lo, hi = 0.0, 1.0
    while _line(c, k, sa, hi, length)[1] < ms:
        hi *= 4.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _line(c, k, sa, mid, length)[1] < ms else (lo, mid)
    return _line(c, k, sa, 0.5 * (lo + hi), length)[0]


def reduced_orders(sc, slide, rolling, tilt=False, cycles=6, n=720):
    """Orders 1 and 3 of Fz [N] (complex) of the reduced traverse model with the row's terms."""
    O = operating_point(sc)
    F, rho, vst, r, w = O[E.O_F], O[E.O_RHO], O[E.O_VST], O[E.O_R], O[E.O_W]
    q = row_q(sc, F)
    mq = sc["mu_needle"] * q if slide else 0.0
    mr = sc["mu_rolling"] * q * sc["r_bore"] if rolling else 0.0
    k_row = 0.5 * 3.0 / vst
    th, hx = O[E.O_TH], 1e-6

    def at(x, s):
        """p, the friction along the trunnion over f_n, beta, f_n, phi, V at angle x, slip s."""
        phi, xi, V, dphi, spin, bi = E.drive_at(O, x)
        vax = (trunnion_axial(x + hx, th, sc["s"], True)
               - trunnion_axial(x - hx, th, sc["s"], True)) * w / (2 * hx)
        yaw = (trunnion_yaw(x + hx, th, True) - trunnion_yaw(x - hx, th, True)) * w / (2 * hx)
        p = 0.0
        for _ in range(8):          # beta depends weakly on p (f_n, the spin moment)
            fn = E.normal_force(O, p)
            beta = E.beta_at(O, p, fn, bi, dphi, spin)
            beta -= mr * math.tanh(3.0 * (spin - yaw) * sc["r_bore"] / vst) / (r * fn)
            fa = (-1.0 if s > 0 else 1.0) * E.share(O, s, abs(beta))
            ms = (abs(spin_moment(O[E.O_MU], fn, O[E.O_A1], dphi + spin * p, vst))
                  if tilt and O[E.O_SM] else 0.0)
            pn = fa - row_axial(mq, k_row, s - V - vax, ms, sc["l_needle"]) / fn
            if abs(pn - p) < 1e-13:
                break
            p = pn
        return pn, fa, beta, fn, phi, V

    h = 2 * math.pi / w / n
    s = E.drive_at(O, 0.0)[2]
    p = at(0.0, s)[0]
    fz = []
    for i in range(cycles * n):
        x1 = w * h * (i + 1)
        rhs0 = rho * p + 0.5 * h * (s - E.drive_at(O, w * h * i)[2] - E.drive_at(O, x1)[2])
        s = brentq(lambda z: rho * at(x1, z)[0] - 0.5 * h * z - rhs0, s - 1.0, s + 1.0,
                   xtol=1e-15, rtol=1e-12)
        p, fa, beta, fn, phi, V = at(x1, s)
        if i >= (cycles - 1) * n:
            fz.append(-fn * (fa * math.sin(phi) + beta * math.cos(phi)))
    fz = np.array([fz[-1]] + fz[:-1])      # samples at 0, h w, ...: the cycle's end is its start
    return {k: phasor(order_component(fz, k)) for k in (1, 3)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], allow_abbrev=False)
    ap.add_argument("--tilt", action="store_true",
                    help="also the spin moment held by the needles' friction alone")
    args = ap.parse_args()
    variants = VARIANTS + ((("+ both + tilt held by friction", True, True, True),)
                           if args.tilt else ())
    print("| scene | model | order 1 | order 3 | order 1 off resolved | order 3 off resolved "
          "| wall |")
    print("|---|---|---|---|---|---|---|")
    fmt = lambda z: f"{abs(z):.1f} N at {math.degrees(np.angle(z)):.1f} deg"   # noqa: E731
    omega = 20 * math.pi
    for deg, F in SCENES:
        theta = math.radians(deg)
        scene = f"{deg:g} deg, {F / 1e3:g} kN"
        t0 = time.perf_counter()
        a = run({"bearing": 2}, F, theta, omega)
        o = last_cycle_orders(a[:, 0], a[:, 2], a[:, 1])
        ref = {k: phasor(o[k]) for k in (1, 3)}
        print(f"| {scene} | needle-resolved row | {fmt(ref[1])} | {fmt(ref[3])} | reference | "
              f"reference | {time.perf_counter() - t0:.0f} s |", flush=True)
        sc = S.validate({"theta": theta, "F_press": F, "omega": omega}, "contact")
        for name, slide, rolling, tilt in variants:
            t0 = time.perf_counter()
            z = reduced_orders(sc, slide, rolling, tilt)
            off = {k: 100 * abs(z[k] - ref[k]) / abs(ref[k]) for k in (1, 3)}
            print(f"| {scene} | {name} | {fmt(z[1])} | {fmt(z[3])} | {off[1]:.1f} % | "
                  f"{off[3]:.1f} % | {time.perf_counter() - t0:.0f} s |", flush=True)


if __name__ == "__main__":
    main()
