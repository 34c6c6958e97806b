"""The needle row's terms in the reduced traverse model, tried before they are built in
(issue 67 point 3): how much of the resolved row's effect on orders 1 and 3 they carry.

The reduced traverse model (reduced_model/traverse.py, T1-T6) with the row's laws added the way
the lumped row has them (docs/model.md, "What the needle row does to the thrust"), nothing
fitted:

- T2 + rolling resistance (Eq. 12): the moment mu_rolling q r_bore tanh(3 v_r / v_st) against
  the roller's spin relative to the trunnion, v_r = (z'/r - psi') r_bore, psi the trunnion's
  yaw (Eq. 3) and q the row's summed needle loads (oppoint.row_sums, Eq. 17 with clearance);
- T1 + the needles' sliding friction: mu_needle q tanh(3 u_r / (2 v_st)) along the trunnion
  against the roller's slide relative to the trunnion's material, u_r = s - V' - d' (T4's
  slide less Eq. 7's stroke d'; half the slip at each of a needle's two contacts), on a line
  of 7 points along the needles whose slip across is the roller's tilt rate about e1 under the
  spin moment (Eq. 16, held by k_t1 = k_w l^2 / 12) times the point's place, at the loaded
  arc's two sides, +-r_bore sqrt(sum q_j sin^2 psi_j / q) across the pressing direction, where
  the same tilt rate moves the bore along the trunnion (half the load each);
- the roller rocking on the row (docs/model.md, "The roller rocks on the row"): the tilt b2
  about e2 (the groove's axis) held quasi-statically by the row's tilt stiffness,
  k_t2 b2 = -r_roller f_a + lever f_row + c F (d - rho_c p) (k_t2 = k_r l^2 / 12, k_r the
  row's stiffness along the load; lever = r_bore F_r / q, where the loaded needles meet the
  bore; the last the row's load F acting at c = 1/2 of the trunnion's stroke d relative to
  the roller, the whole with the needles' friction off: contact.row_load_moment), whose rate
  moves the groove contact along the trunnion by -r_roller b2' and the bore by -lever b2'.

The analytic FMU carries the last variant (needle_row = true: reduced_model/equations.py,
row_step); this march, by scipy's fsolve on (s, b2) with T3 inverted at each point, is its
independent check (tests/test_reduced_row.py).

The slide is marched by T4's trapezoidal rule over whole cycles from the groove bottom (four
cycles, 360 steps a cycle; the tilt by backward differences), T6 with the friction along the
trunnion in place of p.  Each variant is compared with the needle-resolved row (run here:
benchmarks/needle_mechanism.run), orders of Fz over the last cycle, complex differences.
Prints a Markdown table.
Usage: python -m benchmarks.reduced_row [--grid] (about 3 min: four resolved runs of 10-20 s;
--grid: the envelope grid's drive scenes, about 8 min)
"""
import argparse
import math
import time

import numpy as np
from scipy.optimize import brentq, fsolve, root

from benchmarks.needle_mechanism import phasor, run
from reduced_model import equations as E, scene as S
from reduced_model.friction import spin_moment
from reduced_model.needle_row import ROW_CARRY
from reduced_model.orders import last_cycle_orders, order_component
from reduced_model.traverse import operating_point
from tripod_model import layout as K, oppoint
from tripod_model.contact import trunnion_axial, trunnion_yaw
from tripod_model.roller_setup import PARAM_NAMES, kernel_params

SCENES = ((8.0, 4500.0), (8.0, 45000.0), (3.0, 4500.0), (3.0, 45000.0))   # deg, N a roller
VARIANTS = (("reduced traverse model", False, False, False),
            ("+ rolling resistance", False, True, False),
            ("+ sliding friction", True, False, False), ("+ both", True, True, False),
            ("+ both + rocking on the row", True, True, True),
            ("+ the row's load with f_n (the analytic FMU)", True, True, True, True))


def row_terms(sc, F):
    """The row at the pressing load |F| [N] (Eq. 17 over the row, oppoint.row_sums): the summed
    needle loads q [N], the tilt stiffness about e2 k_t2 [N m/rad], the lever [m] from the
    trunnion axis at which the loaded needles meet the bore (on the pressed side) and the tilt
    stiffness about e1 k_t1 [N m/rad], where across the load the needles meet the bore, the
    rms r_bore sin(psi_j) weighted by their loads [m], and the row's stiffness along the load
    k_r [N/m]."""
    T = np.array([float(sc[n]) for n in PARAM_NAMES])
    P = np.zeros(K.P_LEN)
    kernel_params(T, P)
    a = brentq(lambda a: oppoint.row_sums(P, a)[0] - abs(F),
               P[K.P_NEEDLE_CLEARANCE] * (1 + 1e-12), 1e-3)
    Fr, kr, kw, q, qs = oppoint.row_sums(P, a)
    return (q, kr * P[K.P_LT], P[K.P_R_BORE] * Fr / q, kw * P[K.P_LT],
            P[K.P_R_BORE] * math.sqrt(qs / q), kr)


def reduced_orders(sc, slide, rolling, rock=False, load=False, cycles=4, n=360):
    """Orders 1 and 3 of Fz [N] (complex) of the reduced traverse model with the row's terms;
    load: the row's load follows the groove's normal force (T6's Fx), the row yielding under it
    in series with the Hertz contact (T5) and its friction and rolling resistance in
    proportion to it."""
    O = operating_point(sc)
    O[E.O_KRR] = 0.0        # T5 of a rigid row: normal() below gives the row's give (load)
    F, rho, vst, r, w = O[E.O_F], O[E.O_RHO], O[E.O_VST], O[E.O_R], O[E.O_W]
    side = 1.0 if F >= 0 else -1.0          # coast: the other flank, the row's other side
    q, kt2, lever, kt1, arc, kr = row_terms(sc, F)
    ln = sc["l_needle"]
    tilt1 = [0.0, 0.0]     # the tilt about e1 at the last step's end [rad], its rate over it
    lever, rim = side * lever, side * sc["r_roller"]
    mq = sc["mu_needle"] * q if slide else 0.0
    mr = sc["mu_rolling"] * q * sc["r_bore"] if rolling else 0.0
    k_row = 0.5 * 3.0 / vst
    # the row's load F where its needles are along the trunnion (half the stroke relative to
    # the roller with their friction on, the whole with it off: contact.row_load_moment)
    carry = (ROW_CARRY if slide else 1.0) * F
    th, hx = O[E.O_TH], 1e-6
    h = 2 * math.pi / w / n

    def normal(p):
        """T5 [N] at p; with load, the roller's centre giving way by the row's load beyond F
        over k_r (brentq on f_n)."""
        if not load:
            return E.normal_force(O, p)
        c = math.sqrt(1.0 - p * p)

        def excess(f):
            d = (rho - (f * (c + p * p) - F) / kr) / c - O[E.O_CLEAR]
            return O[E.O_K] * max(d, 0.0) ** 1.5 - f
        top = O[E.O_K] * (rho / c - O[E.O_CLEAR]) ** 1.5 + F
        return brentq(excess, 0.0, top, xtol=1e-13, rtol=1e-15)

    def at(x, s, b2d):
        """p, the friction along the trunnion over f_n, beta, f_n, phi and the row's axial
        friction [N] at whirl angle x, slide slip s [m/s] and tilt rate b2d [rad/s]."""
        phi, xi, V, dphi, spin, bi = E.drive_at(O, x)
        vax = (trunnion_axial(x + hx, th, sc["s"], True)
               - trunnion_axial(x - hx, th, sc["s"], True)) * w / (2 * hx)
        yaw = (trunnion_yaw(x + hx, th, True) - trunnion_yaw(x - hx, th, True)) * w / (2 * hx)
        sg = s - rim * b2d                  # the groove contact's slip along the trunnion
        ur = s - V - vax - lever * b2d
        row = 0.0                   # a line along the needles, 7 points: the slide along, the
        for x2 in (arc, -arc):      # tilt about e1 across (the step before's rate), on the
            ua = ur + x2 * tilt1[1]     # arc's two sides, where that tilt slides the bore
            for j in range(7):
                c = tilt1[1] * ln * ((j + 0.5) / 7 - 0.5)
                v = math.hypot(ua, c)
                row += mq / 14 * (math.tanh(k_row * v) * ua / v if v > 0 else 0.0)
        p = 0.0
        for _ in range(40):         # beta depends weakly on p (f_n, the spin moment)
            fn = normal(p)
            # the row's load over F: T6's Fx less its p xi term, over F (or 1)
            carried = fn * (math.sqrt(1.0 - p * p) + p * p) / F if load else 1.0
            beta = E.beta_at(O, p, fn, bi, dphi, spin)
            beta -= carried * mr * math.tanh(3.0 * (spin - yaw) * sc["r_bore"] / vst) / (r * fn)
            fa = (-1.0 if sg > 0 else 1.0) * E.share(O, sg, abs(beta))
            pn = fa - carried * row / fn
            if abs(pn - p) < 1e-14:
                break
            p = pn
        return pn, fa, beta, fn, phi, carried * row

    def g(x):
        """T4's inclination term [m/s]: -r a_y' (a_y = cos xi cos phi) by central differences."""
        ay = [math.cos(d[1]) * math.cos(d[0])
              for d in (E.drive_at(O, x + hx), E.drive_at(O, x - hx))]
        return -r * (ay[0] - ay[1]) * w / (2 * hx)

    s = E.drive_at(O, 0.0)[2]
    b2 = 0.0
    p = at(0.0, s, 0.0)[0]
    fz = []
    for i in range(cycles * n):
        x1 = w * h * (i + 1)
        # T4 by the trapezoidal rule, its g p term implicit where g >= 0 and from the step's
        # start where g < 0 (equations.t4_rhs): rho4 p1 - h/2 s1 = rhs0
        g0, g1 = g(w * h * i), g(x1)
        rho4 = rho + 0.5 * h * max(g1, 0.0)
        rhs0 = rho * p + 0.5 * h * (s - E.drive_at(O, w * h * i)[2] - E.drive_at(O, x1)[2]
                                    - (g0 + min(g1, 0.0)) * p)
        if rock:
            def residual(z):
                pp, fa, _b, fn, _p, row = at(x1, z[0], (z[1] * 1e-3 - b2) / h)
                d = trunnion_axial(x1, th, sc["s"], True)
                return [(rho4 * pp - 0.5 * h * z[0] - rhs0) / (h * 1e-2),
                        (kt2 * z[1] * 1e-3 + rim * fn * fa - lever * row
                         - carry * (d - rho * pp)) / (kt2 * 1e-3)]
            z, info, _ier, msg = fsolve(residual, [s, b2 * 1e3], xtol=1e-12, full_output=True)
            if max(abs(info["fvec"])) > 1e-6:      # Levenberg-Marquardt where hybrd stalls
                sol = root(residual, [s, b2 * 1e3], method="lm", options={"xtol": 1e-14})
                z, msg = sol.x, sol.message
                if max(abs(np.asarray(residual(z)))) > 1e-6:
                    raise RuntimeError(f"the rocking step did not converge at {x1:.4f} rad: "
                                       f"{msg}")
            s, b2d = z[0], (z[1] * 1e-3 - b2) / h
        else:
            s = brentq(lambda z: rho4 * at(x1, z, 0.0)[0] - 0.5 * h * z - rhs0, s - 1.0, s + 1.0,
                       xtol=1e-15, rtol=1e-12)
            b2d = 0.0
        p, fa, beta, fn, phi, _row = at(x1, s, b2d)
        b2 += h * b2d
        if sc["spin_moment"] and slide:
            # the tilt about e1 under the spin moment (Eq. 16), held elastically: M_s / k_t1
            _phi, _xi, _V, dphi, spin, _bi = E.drive_at(O, x1)
            b1 = spin_moment(sc["mu_groove"], normal(p), O[E.O_A1],
                             dphi + spin * p, vst) / kt1
            tilt1[:] = [b1, (b1 - tilt1[0]) / h]
        if i >= (cycles - 1) * n:
            fz.append(-fn * (fa * math.sin(phi) + beta * math.cos(phi)))
    fz = np.array([fz[-1]] + fz[:-1])      # samples at 0, h w, ...: the cycle's end is its start
    return {k: phasor(order_component(fz, k)) for k in (1, 3)}


def grid_table():
    """The drive scenes of the envelope grid (harness.envelope_grid; coast needs the analytic model's
    mirror, which this march lacks): the lumped row and the reduced model with both row terms,
    without and with the rocking, against the needle-resolved row."""
    from harness import envelope_grid as G
    from reduced_model.joint import for_model, load_joint
    print("| # | joint | theta [deg] | load a roller [kN] | whirl [Hz] | lumped: order 1, 3 off "
          "| reduced + both: order 1, 3 off | + rocking, the row's load with f_n: order 1, 3 "
          "off | wall |")
    print("|---|---|---|---|---|---|---|---|---|")
    for i in range(1, 25):
        path, theta, F, omega = G.scene(i)
        if F < 0:
            continue
        t0 = time.perf_counter()
        ref = G.contact_orders(path, theta, F, omega, 2)
        lumped = G.contact_orders(path, theta, F, omega, 1)
        sc = S.validate(dict(for_model(load_joint(path), "contact"), theta=theta, F_press=F,
                             omega=omega), "contact")
        cells = [f"{G.off(lumped, ref, 1):.1f} %, {G.off(lumped, ref, 3):.1f} %"]
        for rock in (False, True):
            z = reduced_orders(sc, True, True, rock, rock)
            o = {k: (abs(z[k]), math.degrees(np.angle(z[k]))) for k in (1, 3)}
            cells.append(f"{G.off(o, ref, 1):.1f} %, {G.off(o, ref, 3):.1f} %")
        print(f"| {i} | {path.stem} | {math.degrees(theta):.1f} | {F / 1e3:.2f} | "
              f"{omega / 2 / math.pi:.1f} | {' | '.join(cells)} | "
              f"{time.perf_counter() - t0:.0f} s |", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], allow_abbrev=False)
    ap.add_argument("--grid", action="store_true",
                    help="the envelope grid's drive scenes instead (about 8 min)")
    if ap.parse_args().grid:
        grid_table()
        return
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
        for name, *terms in VARIANTS:
            t0 = time.perf_counter()
            z = reduced_orders(sc, *terms)
            off = {k: 100 * abs(z[k] - ref[k]) / abs(ref[k]) for k in (1, 3)}
            print(f"| {scene} | {name} | {fmt(z[1])} | {fmt(z[3])} | {off[1]:.1f} % | "
                  f"{off[3]:.1f} % | {time.perf_counter() - t0:.0f} s |", flush=True)


if __name__ == "__main__":
    main()
