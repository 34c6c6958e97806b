"""The needle-resolved bearing (bearing = 2), 46 needles x 7 spheres: run time, where it goes,
and run time against error (issue: needle-resolved bearing, speed).

Prints Markdown tables:
1. two whirl cycles of the paper's scene through the built FMU (FMPy, one process after
   warm-up, median of --runs): seconds, seconds per cycle, substeps per cycle, contact
   evaluations per second;
2. where one substep's time goes (numba kernels timed on a mid-run state);
3. settings against the order-3 error from a reference run at a quarter of the default
   substep, next to the spread a 1e-9 perturbation of v_st alone causes (the needle row is
   chaotic: rounding-level changes move order 3 by a few tenths of a percent).
Usage: python benchmarks/needle_speed.py [--runs N] [--quick]
"""
import argparse
import sys
import time
from pathlib import Path

import numba
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "fmu_src"))
from harness.bench import time_runs  # noqa: E402
from harness.fmus import ensure_fmu  # noqa: E402
from reduced_model.orders import last_cycle_orders  # noqa: E402
from tripod_model import kernel as K, layout as LY, needles as NDL  # noqa: E402
from tripod_model.model import ContactModel, simulate  # noqa: E402

CYCLES = 2
STOP = 0.2


def contact_checks(m):
    """Sphere-contact tests of one evaluation: trunnion, bore, next needle, plus the stops."""
    p = m.p
    return p["n_needles"] * (3 * p["n_spheres"] + 1)


@numba.njit
def _loop_contacts(reps, Y, P, NW, th, x, h, L, e1, e2):
    for _ in range(reps):
        K.resolved_forces(Y, P, NW, th, x, h, L, e1[0], e1[1], e1[2], e2[0], e2[1], e2[2], h,
                          False)


@numba.njit
def _loop_ring(reps, Y, NW, h, AN0, FN0):
    for _ in range(reps):
        NW[3][:] = AN0
        NW[2][:] = FN0
        NDL.needle_update(Y, K.Y_LEN, NW[0], h, NW[2], NW[3], NW[11], NW[14], NW[15], NW[16],
                          NW[17])


@numba.njit
def _loop_copy(reps, NW, AN0, FN0):
    for _ in range(reps):
        NW[3][:] = AN0
        NW[2][:] = FN0


@numba.njit
def _loop_substep(reps, Y0, Ys, P, th, om, F, x0, h, L, res, G, A, b, NW):
    for _ in range(reps):
        Ys[:] = Y0
        K.substep(Ys, P, th, om, F, x0, h, L, res, G, A, b, NW)


def substep_profile(m, reps=3000):
    """[us] per evaluation, timed inside numba on the model's state: every needle contact with
    its implicit system, the ring solve with the needles' update, and one whole substep."""
    th, om = m.p["theta"], m.p["omega"]
    NW, L = m.NW, m._L
    h = m._hs[0] if m.p["integrator"] >= 3 else m._OP[LY.OP_H]   # 4 runs as 3 on this bearing
    e1 = np.array([1 - L[0] ** 2, -L[0] * L[1], -L[0] * L[2]])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(L[:3], e1)
    Y = m.Y.copy()

    def timed(f, *a):
        f(10, *a)
        t0 = time.perf_counter()
        f(reps, *a)
        return (time.perf_counter() - t0) / reps * 1e6
    tc = timed(_loop_contacts, Y, m.P, NW, th, Y[K.Y_X], h, L, e1, e2)
    AN0, FN0 = NW[3].copy(), NW[2].copy()
    tr = timed(_loop_ring, Y.copy(), NW, h, AN0, FN0) - timed(_loop_copy, NW, AN0, FN0)
    ts = timed(_loop_substep, Y, Y.copy(), m.P, th, om, m.p["F_press"], m._x0, h, L,
               m._res, m._G, m._A, m._b, NW)
    touching = [int(np.sum(NW[6][:, k] > 0)) for k in (NDL.D_BORE, NDL.D_TRUN, NDL.D_NEIGH)]
    return tc, tr, ts, touching


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
    ref, wref, _ = orders({"integrator": 1, "max_substep": 9.5e-7})
    m = ContactModel({"bearing": 2})
    vst = m.v_st(m.p["theta"], m.p["omega"])
    print(f"{k} realizations of the default, v_st x (1 + k 1e-11); reference: integrator 1 at "
          f"0.95 us, order 3 {ref[3][0]:.4f} N at {ref[3][1]:.2f} deg\n")
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
    adaptive = m.p["integrator"] >= 3   # integrator 4 (the default) runs as 3 on this bearing
    per_cycle = m.substeps / CYCLES
    attempts = (m._hs[1] + m._hs[2]) / CYCLES if adaptive else per_cycle
    evals = 3 if m.p["integrator"] in (1, 3, 4) else 1
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
          f"{evals} x {checks} tests | {rate:.3g} |")
    tc, tr, ts, touching = substep_profile(m)
    print(f"\nWhere one substep's time goes (timed inside numba on a mid-cycle state; needles "
          f"touching the bore, the trunnion, a neighbour: {touching[0]}, {touching[1]}, "
          f"{touching[2]} of {m.p['n_needles']}):\n")
    print("| part | us per evaluation | share |")
    print("|---|---|---|")
    rest = max(ts - tc - tr, 0.0)   # the difference of three timings: noisy on a busy machine
    for name, t in (("needle contacts: geometry, Table 1 law, friction, implicit blocks", tc),
                    ("ring solve (block-cyclic tridiagonal) and needle update", tr),
                    ("roller: groove contact, 6 x 6 step, kinematics", rest)):
        print(f"| {name} | {t:.1f} | {100 * t / ts:.0f} % |")
    print(f"| whole substep | {ts:.1f} | 100 % |\n")
    avg = r["wall"] / (evals * attempts * CYCLES) * 1e6
    print(f"Averaged over the run: {avg:.1f} us of wall time per evaluation, FMI boundary, slave "
          f"and model Python included (the state profiled has more needles in touch than the "
          f"average).")
    if args.quick:
        return
    ref, wref, _ = orders({"integrator": 1, "max_substep": 9.5e-7})
    vst = ContactModel(sv).v_st(m.p["theta"], m.p["omega"])
    print(f"\nRun time against error (in process, one run each; reference: integrator 1 at "
          f"0.95 us, order 3 {ref[3][0]:.4f} N at {ref[3][1]:.2f} deg, {wref:.1f} s):\n")
    print("| setting | wall [s] | order 3 [N] | error order 3 | error order 1 |")
    print("|---|---|---|---|---|")
    cases = [("integrator 3, step_tolerance 1e-3 (default)", {}),
             ("the same, v_st x (1 + 1e-9): chaos spread", {"v_st": vst * (1 + 1e-9)}),
             ("integrator 3, step_tolerance 3e-3", {"step_tolerance": 3e-3}),
             ("integrator 1, automatic substep (1.8 us)", {"integrator": 1}),
             ("integrator 1, 7.6 us", {"integrator": 1, "max_substep": 7.6e-6}),
             ("integrator 1, 3.8 us", {"integrator": 1, "max_substep": 3.8e-6}),
             ("integrator 0, 3.8 us", {"integrator": 0, "max_substep": 3.8e-6}),
             ("integrator 0, 0.95 us", {"integrator": 0, "max_substep": 9.5e-7})]
    for name, s in cases:
        o, w, _ = orders(s)
        e3 = abs(o[3][0] - ref[3][0]) / ref[3][0]
        e1 = abs(o[1][0] - ref[1][0]) / ref[1][0]
        print(f"| {name} | {w:.1f} | {o[3][0]:.4f} | {100 * e3:.2f} % | {100 * e1:.2f} % |")


if __name__ == "__main__":
    main()
