"""The needle-resolved bearing (bearing = 2), 46 needles x 7 spheres: run time, where it goes,
and run time against error (issue: needle-resolved bearing, speed).

Prints Markdown tables:
1. two whirl cycles of the paper's scene through the built FMU (FMPy, one process after
   warm-up, median of --runs): seconds, seconds per cycle, substeps per cycle, contact
   evaluations per second;
2. where one substep's time goes (numba kernels timed on a mid-run state);
3. settings against the order-3 error from the reference run (the default at 1 us, a third
   of its automatic substep), next to the spread a 1e-9 perturbation of v_st alone causes (the
   needle row is chaotic: rounding-level changes move order 3, by 0.1 % with the default, by
   about 1 % with the split extrapolated step).
Usage: python benchmarks/needle_speed.py [--runs N] [--quick]
"""
import argparse
import math
import time

import numba
import numpy as np

from harness.bench import REFERENCES, time_runs
from harness.fmus import ensure_fmu
from reduced_model.orders import last_cycle_orders
from tripod_model import assembly, bdf2, needle_laws, needles, rowsolve, layout as LY
from tripod_model.model import ContactModel
from tripod_model.simulate import simulate

CYCLES = 2
STOP = 0.2
REF = {k: v for k, v in REFERENCES["contact bearing 2"][1].items() if k != "bearing"}
REF_TEXT = "integrator 4 at 1 us"
assert REF == {"max_substep": 1e-6}, "REF_TEXT says what REF is"


def contact_checks(m):
    """Sphere-contact tests of one evaluation: trunnion, bore, next needle, plus the stops."""
    p = m.p
    return p["n_needles"] * (3 * p["n_spheres"] + 1)


@numba.njit
def _loop_contacts(reps, Y, P, NW, th, x, h, L, e1, e2):
    for _ in range(reps):   # as the default step evaluates them: one system, no K v term
        assembly.resolved_forces(Y, P, NW, th, x, h, L, (e1[0], e1[1], e1[2]),
                                 (e2[0], e2[1], e2[2]), True)


@numba.njit
def _loop_solve(reps, NW, n, h, A0, b0, A, b, AN0, FN0):
    for _ in range(reps):
        NW.AN[:] = AN0
        NW.FN[:] = FN0
        A[:] = A0
        b[:] = b0
        rowsolve.coupled_solve(A, b, NW, h, n, True)


@numba.njit
def _loop_copy(reps, NW, n, h, A0, b0, A, b, AN0, FN0):
    for _ in range(reps):
        NW.AN[:] = AN0
        NW.FN[:] = FN0
        A[:] = A0
        b[:] = b0


@numba.njit
def _loop_clear(reps, Y, NW, n):
    for _ in range(reps):     # each needle's system cleared, its sphere centres placed
        for j in range(n):
            needles._clear_needle(j, Y, NW, (0.0, 0.0, 0.0))


@numba.njit
def _loop_finish(reps, Y, NW, n, frame, o):
    for _ in range(reps):     # the friction blocks from their moments, the roller's unknowns
        needles._finish_systems(Y, NW, n, True, frame, o)


@numba.njit
def _touching(Y, NW, n, ns, o, ob):
    """Sphere-contact tests that find contact, by kind: trunnion, bore, next needle (the
    tests of needles._contacts on the sphere centres NW.SP)."""
    NP, SP = NW.NP, NW.SP
    rn, Rt, Rb, hw, dc = NP[LY.N_RN], NP[LY.N_RT], NP[LY.N_RBR], NP[LY.N_HW], NP[LY.N_DC]
    t = b = c = 0
    for j in range(n):
        needles._clear_needle(j, Y, NW, (0.0, 0.0, 0.0))
    for j in range(n):
        jn = j + 1 if j + 1 < n else 0
        for k in range(ns):
            P1, P2, P3 = SP[j, k, 0], SP[j, k, 1], SP[j, k, 2]
            if math.sqrt(P1 * P1 + P2 * P2) < Rt + rn:
                t += 1
            if needle_laws.bore_gap(P1, P2, P3, o[0], o[1], o[2], ob[0], ob[1], ob[2], hw, Rb,
                                    rn)[4] > 0.0:
                b += 1
            Q1, Q2, Q3 = SP[jn, k, 0] - P1, SP[jn, k, 1] - P2, SP[jn, k, 2] - P3
            if math.sqrt(Q1 * Q1 + Q2 * Q2 + Q3 * Q3) < dc:
                c += 1
    return t, b, c


def _roller_pose(Y, e1, a):
    """The roller's centre and bore axis in the trunnion frame T (assembly.resolved_forces)."""
    E, W, u = Y[LY.Y_E], Y[LY.Y_W], Y[LY.Y_U]
    e1x, ax = e1[0], a[0]
    b1, b2 = Y[LY.Y_B1], Y[LY.Y_B2]
    ib = 1.0 / math.sqrt(1.0 + b1 * b1 + b2 * b2)
    return (E * e1x, W, u + E * ax), (b2 * ib, -b1 * ib, ib), (e1x, ax)


def _all_clear(m, Y):
    """Y with the roller centred on the trunnion and every needle at mid-gap, untilted: no
    trunnion or bore contact (the contact tests without a law behind them)."""
    Y = Y.copy()
    for i in (LY.Y_E, LY.Y_W, LY.Y_B1, LY.Y_B2):
        Y[i] = 0.0
    NP = m.NW.NP
    r_mid = 0.5 * (NP[LY.N_RT] + NP[LY.N_RBR])
    for j in range(m.n_needle_bodies):
        q = LY.Y_LEN + LY.N_F * j
        rho = math.hypot(Y[q], Y[q + 1])
        Y[q], Y[q + 1] = Y[q] * r_mid / rho, Y[q + 1] * r_mid / rho
        Y[q + 3] = Y[q + 4] = 0.0
    return Y


def _best_us(f, reps, *args):
    """[us] per call of f(reps, *args), the best of 5 rounds after a warm-up: on a shared
    machine the others carry its load."""
    f(10, *args)
    best = np.inf
    for _ in range(5):
        t0 = time.perf_counter()
        f(reps, *args)
        best = min(best, (time.perf_counter() - t0) / reps * 1e6)
    return best


def _trunnion_frame(L):
    """The trunnion axis a (from the kinematics L), e1 its normal toward the pressing x, e2."""
    a = L[LY.L_AX:LY.L_AZ + 1]
    e1 = np.array([1 - a[0] ** 2, -a[0] * a[1], -a[0] * a[2]])
    e1 /= np.linalg.norm(e1)
    return a, e1, np.cross(a, e1)


def evaluation_profile(m, reps=1000):
    """[us] of one contact evaluation's parts on the model's state, the best of 5 rounds
    (substep_profile's timing): the needles' systems cleared and their sphere centres placed;
    the contact loop (what is left of the whole evaluation); the contact loop with every
    needle clear (tests alone: _all_clear); the friction blocks and the roller's unknowns
    (_finish_systems); and how many of the 3 x n x ns sphere tests find contact."""
    th = m.p["theta"]
    NW, L, n, ns = m.NW, m._L, m.n_needle_bodies, m.p["n_spheres"]
    h = m._OP[LY.OP_H]
    a, e1, e2 = _trunnion_frame(L)
    Y = m.Y.copy()
    o, ob, frame = _roller_pose(Y, e1, a)

    def timed(f, *args):
        return _best_us(f, reps, *args)
    whole = timed(_loop_contacts, Y, m.P, NW, th, Y[LY.Y_X], h, L, e1, e2)
    clear = timed(_loop_clear, Y, NW, n)
    finish = timed(_loop_finish, Y, NW, n, frame, o)
    Yc = _all_clear(m, Y)
    whole_clear = timed(_loop_contacts, Yc, m.P, NW, th, Yc[LY.Y_X], h, L, e1, e2)
    finish_clear = timed(_loop_finish, Yc, NW, n, frame, _roller_pose(Yc, e1, a)[0])
    touching = _touching(Y, NW, n, ns, o, ob)
    clear_touch = _touching(Yc, NW, n, ns, *_roller_pose(Yc, e1, a)[:2])
    return {"whole": whole, "clear": clear, "finish": finish,
            "contacts": whole - clear - finish,
            "tests_only": whole_clear - clear - finish_clear, "touching": touching,
            "clear_touching": clear_touch, "tests": 3 * n * ns}


@numba.njit
def _loop_substep(reps, Y0, Yp0, Y, P, drive, h, W, NW):
    for _ in range(reps):
        Y[:] = Y0
        W.Y2[:] = Yp0
        bdf2.bdf2_substep(Y, P, drive, h, h, W, NW)


def substep_profile(m, reps=1000):
    """[us] per substep of the default (integrator 4: BDF2, one contact evaluation a Newton pass),
    timed inside numba on the model's state, the best of 5 rounds of reps each: every needle
    contact with the implicit system's blocks (roller and row in one system), its solve (block
    Cholesky along the open ring, forward for seven right-hand sides, and the roller's Schur
    complement), and one whole substep."""
    th, om = m.p["theta"], m.p["omega"]
    NW, L = m.NW, m._L
    h = m._OP[LY.OP_H]
    n = m.n_needle_bodies
    _, e1, e2 = _trunnion_frame(L)
    Y = m.Y.copy()

    def timed(f, *args):
        return _best_us(f, reps, *args)
    tc = timed(_loop_contacts, Y, m.P, NW, th, Y[LY.Y_X], h, L, e1, e2)
    AN0, FN0 = NW.AN.copy(), NW.FN.copy()
    for j in range(n):   # the solve's ring matrix carries the needles' masses
        AN0[j] += np.diag([NW.NP[LY.N_MN]] * 3 + [NW.NP[LY.N_I1]] * 2 + [NW.NP[LY.N_I3]])
    A0 = NW.AR.copy() + np.diag([m.P[LY.P_M_ROLLER], m.P[LY.P_IS], m.P[LY.P_M_ROLLER], m.P[LY.P_IT],
                                 m.P[LY.P_IT], m.P[LY.P_M_ROLLER]])
    a = (NW, n, h, A0, NW.FR.copy(), np.empty((6, 6)), np.empty(6), AN0, FN0)
    tr = timed(_loop_solve, *a) - timed(_loop_copy, *a)
    W = m._W._replace(Y2=m._Y2.copy())   # the model's own previous state left as it is
    drive = LY.Drive(th, om, m._OP[LY.OP_X0], 0.0)
    args = (Y, m._Y2.copy(), Y.copy(), m.P, drive, h, W, NW)
    ts = timed(_loop_substep, *args)
    p0 = W.hs[LY.H_PASSES]     # Newton passes a substep on this state (bdf2_substep counts
    _loop_substep(reps, *args)     # those after the first)
    passes = 1.0 + (W.hs[LY.H_PASSES] - p0) / reps
    touching = [int(np.sum(NW.ND[:, k] > 0)) for k in (LY.D_BORE, LY.D_TRUN, LY.D_NEIGH)]
    return tc, tr, ts, touching, passes


def orders(sv):
    t0 = time.perf_counter()
    r = simulate(dict({"bearing": 2}, **sv), cycles=CYCLES)
    wall = time.perf_counter() - t0
    o = last_cycle_orders(r["t"], r["Fz_mod"], r["whirl"])
    return o, wall, r["substeps"]


def _c(o):
    return o[0] * np.exp(1j * np.radians(o[1]))


def ensemble(k):
    """K realizations of the default scene differing by a rounding-level change of v_st: how
    far order 3 of one run can be from another (the chaos floor) and from the reference."""
    ref, wref, _ = orders(REF)
    m = ContactModel({"bearing": 2})
    vst = m.v_st(m.p["theta"], m.p["omega"])
    print(f"{k} realizations of the default, v_st x (1 + k 1e-11); reference: {REF_TEXT}, "
          f"order 3 {ref[3][0]:.4f} N at {ref[3][1]:.2f} deg\n")
    print("| k | wall [s] | substeps (2 cycles) | order 3 [N] | phase [deg] | error order 3 |")
    print("|---|---|---|---|---|---|")
    z, errs = [], []
    for i in range(1, k + 1):
        o, w, n = orders({"v_st": vst * (1 + i * 1e-11)})
        z.append(_c(o[3]))
        errs.append(abs(z[-1] - _c(ref[3])) / abs(_c(ref[3])))
        print(f"| {i} | {w:.1f} | {n} | {o[3][0]:.4f} | {o[3][1]:.2f} | {100 * errs[-1]:.2f} % |")
    z = np.array(z)
    print(f"\nSpread (std of the complex order 3 / its mean): {100 * np.std(z) / abs(z.mean()):.2f} %; "
          f"error against the reference: median {100 * np.median(errs):.2f} %, max "
          f"{100 * max(errs):.2f} %; the ensemble mean's: "
          f"{100 * abs(z.mean() - _c(ref[3])) / abs(_c(ref[3])):.2f} %")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="skip the run-time-against-error table")
    ap.add_argument("--ensemble", type=int, metavar="K", default=0,
                    help="only: K realizations of the default (v_st x (1 + k 1e-11)), the "
                         "row's chaos floor against the reference")
    args = ap.parse_args()
    if args.ensemble:
        return ensemble(args.ensemble)
    fmu = ensure_fmu("TripodRoller")
    sv = {"bearing": 2}
    r = time_runs(fmu, [{"sv": sv, "dt": 1e-4, "stop": STOP}], runs=args.runs, read=("Fz_mod",))[0]
    m = ContactModel(sv)           # two cycles in process: substeps taken and rejected
    for _ in range(int(round(STOP / 1e-4))):
        m.step(1e-4, m.p["theta"], m.p["omega"], m.p["F_press"])
    adaptive = m.p["integrator"] == 3
    per_cycle = m.substeps / CYCLES
    attempts = (m._hs[LY.H_TAKEN] + m._hs[LY.H_REJECTED]) / CYCLES if adaptive else per_cycle
    # contact evaluations a substep: the extrapolated steps three, BDF2 one a Newton pass (a
    # refused pass has evaluated too; the second only where the first moved far)
    evals = 3 if m.p["integrator"] in (1, 3) else 1 + m._hs[LY.H_PASSES] / m._hs[LY.H_TAKEN]
    checks = contact_checks(m)
    rate = attempts * CYCLES * evals * checks / r["wall"]
    m = ContactModel(sv)           # a loaded, rolling state at 0.03 s for the profile
    for _ in range(300):
        m.step(1e-4, m.p["theta"], m.p["omega"], m.p["F_press"])
    print(f"Needle-resolved bearing, {m.p['n_needles']} needles x {m.p['n_spheres']} spheres, "
          f"paper's scene, two whirl cycles at a 1e-4 s communication step\n")
    print("| wall, 2 cycles (FMU, in process, median of %d) | s per cycle | substeps per cycle "
          "(rejected) | contact evaluations per substep | sphere-contact tests per second |"
          % args.runs)
    print("|---|---|---|---|---|")
    print(f"| {r['wall']:.2f} s [{min(r['walls']):.2f}-{max(r['walls']):.2f}] | "
          f"{r['wall'] / CYCLES:.2f} | {per_cycle:.0f} ({attempts - per_cycle:.0f}) | "
          f"{evals:.2f} x {checks} tests | {rate:.3g} |")
    tc, tr, ts, touching, passes = substep_profile(m)
    print(f"\nWhere one substep's time goes (timed inside numba on a mid-cycle state; needles "
          f"touching the bore, the trunnion, a neighbour: {touching[0]}, {touching[1]}, "
          f"{touching[2]} of {m.p['n_needles']}; {passes:.2f} Newton passes a substep on it, "
          f"each an evaluation and a solve):\n")
    print("| part | us a substep | share |")
    print("|---|---|---|")
    # the parts are timed apart: the contacts on the state itself, the substep evaluates them
    # at a predicted one, so the rest (a difference of timings) can come out negative
    rest = ts - passes * (tc + tr)
    for name, t in (("needle contacts: geometry, Table 1 law, friction, implicit blocks",
                     passes * tc),
                    ("solve: block Cholesky of the ring (7 right-hand sides forward), the "
                     "roller's Schur complement", passes * tr)):
        print(f"| {name} | {t:.1f} | {100 * t / ts:.0f} % |")
    print("| roller, prediction and update of every state (the rest) | "
          + (f"{rest:.1f} | {100 * rest / ts:.0f} % |" if rest > 0 else
             "- | - (the parts, timed apart, add to more than the whole) |"))
    print(f"| whole substep | {ts:.1f} | 100 % |\n")
    ev = evaluation_profile(m)
    t, b, c = ev["touching"]
    per = ev["tests"] // 3
    print(f"One contact evaluation's parts on the same state (a substep's {evals:.2f} "
          f"evaluations each pay these; sphere tests that find contact: trunnion {t}, bore "
          f"{b}, next needle {c}, of {per} each):\n")
    print("| part | us | share of the evaluation |")
    print("|---|---|---|")
    for name, tt in (("the needles' systems cleared, sphere centres placed", ev["clear"]),
                     (f"the contact loop: {ev['tests']} sphere tests, the laws and tangent "
                      f"blocks of the {t + b + c} contacts found", ev["contacts"]),
                     ("of it, the tests alone (every needle at mid-gap: "
                      f"{sum(ev['clear_touching'])} neighbour contacts left)", ev["tests_only"]),
                     ("the friction blocks from their moments, the roller's unknowns",
                      ev["finish"])):
        print(f"| {name} | {tt:.1f} | {100 * tt / ev['whole']:.0f} % |")
    print(f"| whole evaluation (assembly.resolved_forces) | {ev['whole']:.1f} | 100 % |\n")
    avg = r["wall"] / (evals * attempts * CYCLES) * 1e6
    print(f"Averaged over the run: {avg:.1f} us of wall time per evaluation, FMI boundary, slave "
          f"and model Python included (the state profiled has more needles in touch than the "
          f"average).")
    if args.quick:
        return
    ref, wref, _ = orders(REF)
    vst = ContactModel(sv).v_st(m.p["theta"], m.p["omega"])
    print(f"\nRun time against error (in process, one run each; reference: {REF_TEXT}, order 3 "
          f"{ref[3][0]:.4f} N at {ref[3][1]:.2f} deg, {wref:.1f} s; errors: the complex "
          f"difference):\n")
    print("| setting | wall [s] | order 3 [N] | error order 3 | error order 1 |")
    print("|---|---|---|---|---|")
    cases = [("integrator 4 (default): BDF2, roller and row in one system", {}),
             ("the same, v_st x (1 + 1e-9): chaos spread", {"v_st": vst * (1 + 1e-9)}),
             ("integrator 4, max_substep 2 us", {"max_substep": 2e-6}),
             ("integrator 4, max_substep 4 us", {"max_substep": 4e-6}),
             ("integrator 3: split, extrapolated, adaptive (the default before)",
              {"integrator": 3}),
             ("integrator 1, automatic substep (1.8 us)", {"integrator": 1}),
             ("integrator 1, 7.6 us", {"integrator": 1, "max_substep": 7.6e-6}),
             ("integrator 0, 3.8 us", {"integrator": 0, "max_substep": 3.8e-6})]
    for name, s in cases:
        o, w, _ = orders(s)
        e3 = abs(_c(o[3]) - _c(ref[3])) / ref[3][0]
        e1 = abs(_c(o[1]) - _c(ref[1])) / ref[1][0]
        print(f"| {name} | {w:.1f} | {o[3][0]:.4f} | {100 * e3:.2f} % | {100 * e1:.2f} % |")


if __name__ == "__main__":
    main()
