"""Needle-resolved bearing (bearing = 2) in a reduced configuration that keeps CI fast:
12 needles, 0.3 whirl cycles of the paper's scene with every friction on.

What is asserted is independent of the kernel: Newton's third law across the row (the needles'
push on the roller balances the groove's within 1 %, less the roller's own inertia), the
geometry of the row (no needle leaves the annulus or its axial stops), where the load sits
(the pressed side, +x) and the static load sharing of Eq. (17).  At launch loads (46 needles),
the method: the default substep against a quarter of it.
"""
import math

import numpy as np
import pytest
from rounding import solve_error

from tripod_model import contact, rowsolve, layout as LY, needles as NDL, ring
from reduced_model import needle_row
from tripod_model.model import ContactModel

SCENE = {"bearing": 2, "n_needles": 12}


@pytest.fixture(scope="module")
def run():
    m = ContactModel(SCENE)
    p = m.p
    rows = []
    for _ in range(300):      # 0.03 s = 0.3 whirl cycles at 10 Hz
        o = m.step(1e-4, p["theta"], p["omega"], p["F_press"])
        ND = m.needle_loads()
        pos = m.needle_positions()
        rows.append((o, ND, pos, m.Y.copy()))
    return m, rows


def test_needle_loads_balance_the_groove_load(run):
    m, rows = run
    err = []
    for o, ND, _, _ in rows:
        # along the pressing direction the roller feels Fx from the groove, the needles' sum
        # the other way; the rest is m * acceleration (below 0.5 % here: 0.06 kg at < 100 m/s^2)
        err.append(abs(ND[:, LY.D_R1].sum() - o["Fx"]) / o["Fx"])
    print(f"needle load sum vs groove load: median {100 * np.median(err):.3f} %, "
          f"max {100 * max(err):.3f} %")
    assert np.median(err) < 0.01
    assert max(err) < 0.03


def test_loaded_zone_on_the_pressed_side(run):
    m, rows = run
    for _, ND, pos, _ in rows[50:]:
        bore = ND[:, LY.D_BORE]
        psi = np.arctan2(pos[:, 1], pos[:, 0])
        # load-weighted direction of the loaded needles: the pressing direction e1 (psi = 0)
        c = np.sum(bore * np.cos(psi))
        s = np.sum(bore * np.sin(psi))
        assert abs(math.degrees(math.atan2(s, c))) < 20.0
        # the far side carries only the impacts of free needles rattling in the clearance
        # (critically damped contacts: ~2 sqrt(k m) v = 10-20 N at a few cm/s), not load
        assert np.sum(bore[np.cos(psi) < -0.2]) < 0.05 * np.sum(bore)


def test_needles_stay_in_the_row_and_finite(run):
    m, rows = run
    p = m.p
    rn = 0.5 * p["d_needle"]
    inner = p["r_trunnion"] + rn
    outer = m.row_bore_radius() - rn
    for o, ND, pos, Y in rows:
        assert np.all(np.isfinite(Y)) and all(math.isfinite(v) for v in o.values())
        rho = np.hypot(pos[:, 0], pos[:, 1])
        # a few micrometres of contact approach at most, never out of the annulus
        assert np.all(rho > inner - 5e-6) and np.all(rho < outer + 5e-6 + 2e-5)
        d = contact.trunnion_axial(Y[LY.Y_X], p["theta"], p["s"], p["axial"])
        assert np.all(np.abs(pos[:, 2] - d) < p["needle_axial_clearance"] + 2e-5)


def test_static_load_sharing_eq17():
    # at rest the row is a statically indeterminate set of Eq. (17) springs: the central needle
    # carries P0 with sum_j P0 (approach_j/approach_0)^(10/9) cos(psi_j) = F; compare with the
    # kernel's contacts after the row has settled
    m = ContactModel(dict(SCENE, n_needles=12))
    for _ in range(200):
        m.step(1e-4, 0.0, 0.0, 1000.0)
    ND = m.needle_loads()
    pos = m.needle_positions()
    psi = np.arctan2(pos[:, 1], pos[:, 0])
    E = -m.Y[LY.Y_E]
    c = np.cos(psi)
    ap = np.maximum(E * c - m.p["needle_clearance"], 0.0)
    Cl = needle_row.needle_line_stiffness(m.p["l_needle"])
    expect = Cl * (0.5 * ap) ** (10 / 9)        # two races in series, whole needle
    got = ND[:, LY.D_BORE]
    assert np.sum(got * c) == pytest.approx(1000.0, rel=1e-3)
    loaded = expect > 1.0
    assert np.allclose(got[loaded], expect[loaded], rtol=0.02)


@pytest.mark.parametrize("gaps", [(), (0,), (2,), ("last",), (1, 2), (0, 2, 5), "all"])
def test_ring_solve_against_dense_solve(gaps):
    # the coupled needle system is block-cyclic tridiagonal; compare with numpy's dense solve
    # of the same matrix assembled independently (random SPD-like blocks), the ring closed or
    # open where neighbours do not touch (zero coupling blocks: the chain solve)
    rng = np.random.default_rng(7)
    for n in (3, 4, 12):
        AN = rng.normal(size=(n, 6, 6))
        AN = np.einsum("nij,nkj->nik", AN, AN) + 10 * np.eye(6)
        UN = 0.5 * rng.normal(size=(n, 6, 6))
        for g in (range(n) if gaps == "all" else gaps):
            UN[n - 1 if g == "last" else g % n] = 0.0
        FN = rng.normal(size=(n, 6))
        h = 0.37
        A = np.zeros((6 * n, 6 * n))
        for j in range(n):
            jn = (j + 1) % n
            A[6 * j:6 * j + 6, 6 * j:6 * j + 6] += AN[j]
            A[6 * j:6 * j + 6, 6 * jn:6 * jn + 6] += UN[j]
            A[6 * jn:6 * jn + 6, 6 * j:6 * j + 6] += UN[j].T
        expect = np.linalg.solve(A, h * FN.ravel()).reshape(n, 6)
        got = FN.copy()
        ring.ring_solve(AN.copy(), UN.copy(), got, h, n, np.zeros((n, 6, 6)),
                       np.zeros((n, 6, 7)), np.zeros((6, 6)), np.zeros((6, 13)))
        assert np.linalg.norm(got - expect) <= solve_error(A, expect), n
        # several right-hand sides in one elimination (the coupled step's seven)
        RHS = rng.normal(size=(n, 6, 7))
        expect = np.linalg.solve(A, RHS.reshape(6 * n, 7)).reshape(n, 6, 7)
        got = RHS.copy()
        ring.ring_solve_m(AN.copy(), UN.copy(), got, 7, n, np.zeros((n, 6, 6)),
                         np.zeros((n, 6, 13)), np.zeros((6, 6)), np.zeros((6, 19)))
        assert np.linalg.norm(got - expect) <= solve_error(A, expect), n


@pytest.mark.parametrize("gaps", [(), (3,), (0,), (-1,), (1, 5, 9), "all", "indefinite"])
def test_coupled_solve_against_dense_solve(gaps):
    # the roller bordering the needle ring (BDF2 step): its 6 unknowns y coupled to every
    # needle by BN (needle rows, the roller's standard velocities, mapped to its unknowns by
    # TM: B' = BN TM^T), [[R, B'], [B'^T, A]] [x; y] = [g FN; b]; against numpy's dense solve.
    # Closed ring: the general elimination; open (gaps): the block Cholesky along the chain;
    # a block that is not positive definite (indefinite) falls back to the general one
    rng = np.random.default_rng(11)
    m = ContactModel(SCENE)
    NW, n = m.NW, m.n_needle_bodies
    AN = rng.normal(size=(n, 6, 6))
    NW.AN[:] = np.einsum("nij,nkj->nik", AN, AN) + 10 * np.eye(6)
    NW.UN[:] = 0.5 * rng.normal(size=(n, 6, 6))
    if gaps == "indefinite":
        gaps = (4,)
        NW.AN[6, 2, 2] = -50.0
    for g in (range(n) if gaps == "all" else gaps):
        NW.UN[g] = 0.0
    NW.BN[:] = 0.3 * rng.normal(size=(n, 6, 6))
    NW.ND[:, LY.D_BORE] = 1.0        # needles on the bore; two clear of it (no coupling)
    for j in (2, 7):
        NW.BN[j] = 0.0
        NW.ND[j, LY.D_BORE] = 0.0
    TM = rng.normal(size=(6, 6))
    NW.RS[:, 7:13] = TM
    FN = rng.normal(size=(n, 6))
    NW.FN[:] = FN
    A = rng.normal(size=(6, 6))
    A = A @ A.T + 30 * np.eye(6)
    b = rng.normal(size=6)
    g = 0.37
    D = np.zeros((6 * n + 6, 6 * n + 6))
    for j in range(n):
        jn = (j + 1) % n
        D[6 * j:6 * j + 6, 6 * j:6 * j + 6] += NW.AN[j]
        D[6 * j:6 * j + 6, 6 * jn:6 * jn + 6] += NW.UN[j]
        D[6 * jn:6 * jn + 6, 6 * j:6 * j + 6] += NW.UN[j].T
        Bj = NW.BN[j] @ TM.T
        D[6 * j:6 * j + 6, 6 * n:] = Bj
        D[6 * n:, 6 * j:6 * j + 6] = Bj.T
    D[6 * n:, 6 * n:] = A
    sol = np.linalg.solve(D, np.concatenate([g * FN.ravel(), b]))
    Ac, bc = A.copy(), b.copy()
    rowsolve.coupled_solve(Ac, bc, NW, g, n, True)
    got = np.concatenate([NW.FN.ravel(), bc])
    assert np.linalg.norm(got - sol) <= solve_error(D, sol)


def test_fast_tanh_matches_math_tanh():
    # the kernel's tanh (one exp, or Lambert's fraction below 1/2, instead of libm's tanh)
    # against math.tanh: relative error within 4 eps (the fraction's own is 1.5e-22 at 1/2, its
    # rounding and the exp's a few eps; math.tanh within an ulp) from 1e-12 to saturation,
    # either sign, across the switch at 1/2, and NaN stays NaN (the contact tests are written
    # so that NaN skips).  The exp alone was 3e-13 off at 1e-4
    xs = np.concatenate([np.logspace(-12, 2, 4001), np.linspace(0.45, 0.55, 1001),
                         [0.5, math.nextafter(0.5, 0.0), 19.0, 0.0, 1e300]])
    for x in np.concatenate([xs, -xs]):
        want = math.tanh(x)
        got = contact.tanh_clipped(float(x))
        assert abs(got - want) <= 4 * np.finfo(float).eps * abs(want), x
    assert math.isnan(contact.tanh_clipped(float("nan")))


def test_pair_blocks_match_per_contact_sums():
    # a touching pair's blocks built once from S = sum kq g g^T (_pair_blocks) against the
    # sums over its contacts written out: needle jn sees the same contact at arm R = r + d, so
    # Ajn = sum kq g_n g_n^T, the coupling -sum kq g g_n^T, and jn's friction moments of R
    rng = np.random.default_rng(7)
    d = rng.normal(size=3) * 3e-3
    Aj0, Ajn0 = rng.normal(size=(6, 6)), rng.normal(size=(6, 6))
    Mj0, Mjn0 = rng.normal(size=10), rng.normal(size=10)
    U, PM = np.zeros((6, 6)), np.zeros(10)
    Aj, Ajn, Uw, M = Aj0.copy(), Ajn0.copy(), np.zeros((6, 6)), [np.zeros(10), np.zeros(10)]

    def moments(w, r):
        return w * np.array([1, *r, r[0] ** 2, r[1] ** 2, r[2] ** 2, r[0] * r[1], r[0] * r[2],
                             r[1] * r[2]])
    for _ in range(7):
        nv = rng.normal(size=3)
        nv /= np.linalg.norm(nv)
        r = rng.normal(size=3) * 4e-3
        kq, w = rng.uniform(1e3, 1e6), rng.uniform(0.0, 10.0)
        g, g2 = np.r_[nv, np.cross(r, nv)], np.r_[nv, np.cross(r + d, nv)]
        U += np.triu(kq * np.outer(g, g))   # what _contacts leaves: the upper triangle
        PM += moments(w, r)
        Aj += kq * np.outer(g, g)
        Ajn += kq * np.outer(g2, g2)
        Uw -= kq * np.outer(g, g2)
        M[0] += moments(w, r)
        M[1] += moments(w, r + d)
    Mj, Mjn = Mj0.copy(), Mjn0.copy()
    Ajg, Ajng = Aj0.copy(), Ajn0.copy()
    NDL._pair_blocks(Ajg, Ajng, U, Mj, Mjn, PM.copy(), *d)
    iu = np.triu_indices(6)   # the systems' upper triangles (mirrored later)
    assert np.allclose(Ajg[iu], Aj[iu], rtol=1e-12, atol=1e-14 * np.abs(Aj).max())
    assert np.allclose(Ajng[iu], Ajn[iu], rtol=1e-12, atol=1e-14 * np.abs(Ajn).max())
    assert np.allclose(U, Uw, rtol=1e-12, atol=1e-12 * np.abs(Uw).max())
    assert np.allclose(Mj, Mj0 + M[0], rtol=1e-12, atol=1e-15)
    assert np.allclose(Mjn, Mjn0 + M[1], rtol=1e-12, atol=1e-15)


def _orders_last_cycle(params, F, cycles=1.5, dt=1e-4, last=1):
    """Orders 1 and 3 of Fz [N] of a run from the start at the paper's scene (with params) and
    F_press = F [N]: over the last whirl cycle, or their mean over the ``last`` whole cycles."""
    from reduced_model.orders import last_cycle_orders
    m = ContactModel(params)
    p = m.p
    t, x, y = [], [], []
    for k in range(int(round(cycles * 2 * math.pi / p["omega"] / dt))):
        o = m.step(dt, p["theta"], p["omega"], F)
        t.append((k + 1) * dt)
        x.append(m.whirl_angle)
        y.append(o["Fz"])
    ends = [x[-1] - 2 * math.pi * i for i in range(last)]
    orders = [last_cycle_orders(t, y, x, x_end=e) for e in ends]
    return np.mean([[o[1][0], o[3][0]] for o in orders], axis=0)


@pytest.mark.slow   # (about 35 s each: make test-slow, which CI runs after make test)
@pytest.mark.parametrize("F, tol", [(15e3, 0.005), (45e3, 0.015)])
def test_the_row_converges_at_a_launch_load(F, tol):
    # 15 kN (1000 N m through the default joint) and a launch's 45 kN per roller, 46 needles:
    # orders 1 and 3 of Fz at the default substep (about 2.6 us) against a quarter of it.
    # BDF2 converges as h^2, so the default's own error is the difference (measured 0.01 % at
    # 15 kN; 0.2 % and 0.8 % at 45 kN); the bounds leave room for the row's chaos, which moves
    # a cycle's orders by a few 0.1 % between realizations.  A step that took the
    # groove friction along the slip with its tangent, ~0 once saturated: above about 12 kN the
    # explicit friction impulse on the spin overshot the tanh's range and the spin flipped every
    # substep (Fz swinging +-700 N at 15 kN, orders off by 20-90 %, worse at a finer substep);
    # with the secant but the spin moment explicit, order 3 was 1.9 % off at 45 kN
    base = {"bearing": 2, "theta": math.radians(8.0)}
    got = _orders_last_cycle(base, F)
    ref = _orders_last_cycle(dict(base, max_substep=6.5e-7), F)
    err = np.abs(got / ref - 1.0)
    print(f"F = {F:g} N: orders 1, 3 {got} against {ref}: {100 * err} %")
    assert np.all(err < tol)


@pytest.mark.slow   # (about 20 s)
def test_the_row_converges_at_40_hz():
    # One roller at 40 Hz, 8 deg and 300 N m's 4.5 kN, 46 needles: orders 1 and 3 of Fz (mean
    # over cycles 2-3) at the default substep against half of it.  A default of the row's
    # 2.9 us at any speed (BDF2's one linearization a substep, with the needles' friction by
    # its secant) put order 1 4.5 % high at 40 Hz (3.6-5 % against half
    # the substep; oppoint.ROW_WHIRL_STEP).  The bound: the row's chaos moves these means by
    # up to 1 % between realizations and substeps (measured), doubled
    base = {"bearing": 2, "theta": math.radians(8.0), "omega": 2 * math.pi * 40.0}
    from reduced_model.scene import BY_NAME, pressing_load
    F = pressing_load(0.0, 300.0, BY_NAME["s"].default)
    got = _orders_last_cycle(base, F, cycles=3.0, last=2)
    ref = _orders_last_cycle(dict(base, max_substep=1e-6), F, cycles=3.0, last=2)
    err = np.abs(got / ref - 1.0)
    print(f"orders 1, 3 {got} against {ref}: {100 * err} %")
    assert np.all(err < 0.02)


def test_the_second_newton_pass_is_made_where_the_first_moved_far():
    # the mechanism (bdf2.bdf2_substep): a second pass only where the first pass's velocity
    # correction exceeds newton_tol.  At 0 every BDF2 substep takes it (all but the one-step
    # start), at 1 m/s none does, and the default's 3e-4 m/s some (0.35 of them in the
    # paper's scene with 46 needles); newton_passes = 1 never.  The FMU's log line counts them
    def passes(**kw):
        m = ContactModel(dict(SCENE, **kw))
        for _ in range(20):
            m.step(1e-4, m.p["theta"], m.p["omega"], m.p["F_press"])
        return m._hs[LY.H_PASSES], m._hs[LY.H_TAKEN]

    every, taken = passes(newton_tol=0.0)
    assert taken - 2 <= every < taken
    assert passes(newton_tol=1.0)[0] == 0
    assert passes(newton_passes=1)[0] == 0
    some, taken = passes()
    assert 0 < some < taken


def test_rolling_resistance_is_eq12_at_each_race():
    """Eq. (12) and Fig. 9: mu_r = F / P, F the force that rolls a needle between two plates
    under P; the moment F D that F puts on the needle is resisted at its two contacts,
    M_r = mu_r P D / 2 at each.  A needle sphere turning far faster than v_st / r_n (the tanh
    saturated) on the trunnion and in the bore: each contact's moment is mu_r f D / 2, both
    together F D with F = mu_r f (exact but for the saturated tanh, 1 - 1e-16)."""
    from tripod_model.needle_laws import bore_law, trunnion_law
    rn, mur, vst = 0.8e-3, 0.002, 1e-3
    c = (rn, 5e7, 1e-4, 0.05, mur, vst, 1e-6, 1.0)
    w3 = 100.0                  # 3 rn w3 / vst = 240: tanh is 1 to rounding
    x = 0.0113                  # sphere centre off the axis [m]
    body = (x, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, w3)
    t = trunnion_law((x, 0.0, 0.0), x, 1e-6, body, c, 1.0, 0.0, 0.0)
    b = bore_law((x, 0.0, 0.0), (x, 0.0, 0.0), x, 1e-6, body,
                 (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), c, 1.0)
    f_t, m_t, f_b, m_b = t[11], t[12], b[17], b[18]
    assert f_t > 0 and f_t == f_b
    D = 2 * rn
    assert m_t == pytest.approx(mur * f_t * D / 2, rel=1e-12)
    assert m_b == pytest.approx(mur * f_b * D / 2, rel=1e-12)
    assert m_t + m_b == pytest.approx(mur * f_t * D, rel=1e-12)
