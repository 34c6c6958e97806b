"""The contact model under a master that moves the inputs: no spike after an input step, no
bias along a run-up (docs/integrators.md, "Inputs that move every communication step")."""
import math

import pytest

from harness import input_transients as T


@pytest.fixture(scope="module")
def settled_2hz():
    return T.settle({}, 3, 2)


@pytest.mark.parametrize("name,factor", [("omega", 1.01), ("theta", 1.01), ("omega", 1.10),
                                         ("torque", 0.90)])
def test_an_input_step_leaves_no_spike(settled_2hz, name, factor):
    # three rollers settled at 2 Hz, 300 N m, 8 deg (where a +1 % omega step used to move Fz_3
    # by 99 N for one sample): the 20 samples after the step within 1 % of order 3 of a
    # reference with a 10x finer substep and communication step from the same state
    assert T.case({}, 3, 2, name, factor, settled_2hz) < 1.0


@pytest.fixture(scope="module")
def lumped_10hz():
    return T.settle({"bearing": 1}, 1, 10)


@pytest.mark.parametrize("name,factor", [("omega", 1.01), ("omega", 1.10), ("theta", 0.90),
                                         ("torque", 0.90), ("torque", 1.01)])
def test_the_lumped_bearing_takes_an_input_step(lumped_10hz, name, factor):
    # the lumped bearing, one roller settled at 10 Hz (where steps missed by 10-128 % of order
    # 3 while the row's modes rang undamped in the reference): within 1 % of the reference
    # (measured 0.10-0.61 %)
    assert T.case({"bearing": 1}, 1, 10, name, factor, lumped_10hz) < 1.0


@pytest.fixture(scope="module")
def resolved_10hz():
    return T.settle({"bearing": 2}, 1, 10)


@pytest.mark.parametrize("name,factor,bound", [("omega", 1.10, 1.0), ("torque", 1.10, 2.0)])
def test_the_needle_resolved_bearing_takes_an_input_step(resolved_10hz, name, factor, bound):
    # the needle-resolved row, one roller settled at 10 Hz, read as its 1 ms running mean: that
    # mean converges even where single samples do not (one pass a substep, the default before the
    # second pass: a 1e-15 change of the row's state moved single samples of Fz_joint by up to
    # 2.3 % of order 3 within the 20 steps, references 10 to 160 times finer parted by up to
    # 1.7 %, their 1 ms means within 0.3 %: benchmarks/needle_chaos.py).  Against a reference
    # of h/20, the mean missed by 1.21-1.27 % (omega) with BDF2's history across the step at
    # its steady substep, 0.36-0.67 % with three finer communication steps.  With the finer
    # substeps over the next 0.8 ms, over twelve realizations of the one-pass row (its
    # settling whirl nudged by 1e-12 to 3e-7: another CPU's rounding is another realization),
    # at h/16: omega +10 % 0.09-0.26 %, torque +10 % 0.14-1.39 %.  The torque bound is that
    # spread with a margin, not the 1 %
    assert T.case({"bearing": 2}, 1, 10, name, factor, resolved_10hz, mean=T.MEAN_SAMPLES,
                  refine=20) < bound


@pytest.fixture(scope="module")
def resolved_10hz_one_pass():
    return T.settle(T.ONE_PASS, 1, 10)


def test_with_one_pass_the_needle_rows_single_samples_move_with_rounding(resolved_10hz_one_pass):
    # why the default takes a second Newton pass where the first moved the velocities far:
    # with one linear solve a BDF2 substep (newton_passes = 1) a 1e-15 change of the row's
    # state (the roller's spin) grows e-fold every 20-30 us (benchmarks/needle_chaos.py), some
    # 70 e-folds over 20 samples of 1e-4 s, and saturates at the row's own rattle.  The
    # table's rounding row read 0.2-2.3 % and 0.3-2.2 % of order 3 in two runs (no step, +-1 %
    # steps).  Asserted: above 0.1 % in the largest of three cells (a growth of 1e12 at least;
    # a step that stopped amplifying rounding would leave them near 1e-13), while the 1 ms mean
    # moves by less than the 1 %.  Measured on three realizations (settling whirl
    # nudged by 0, 1e-9, 1e-7): the largest single sample 2.15, 1.30 and 1.80 %, the 1 ms mean
    # 0.42, 0.15 and 0.59 %
    cells = [("omega", 1.0), ("omega", 1.01), ("torque", 1.01)]
    single = [T.case(T.ONE_PASS, 1, 10, n, f, resolved_10hz_one_pass, perturb=1e-15)
              for n, f in cells]
    mean = [T.case(T.ONE_PASS, 1, 10, n, f, resolved_10hz_one_pass, perturb=1e-15,
                   mean=T.MEAN_SAMPLES) for n, f in cells]
    assert max(single) > 0.1, single
    assert max(mean) < 1.0, mean


@pytest.mark.parametrize("name,factor", [("omega", 1.01), ("omega", 0.99), ("omega", 1.10),
                                         ("torque", 1.10), ("torque", 0.99), ("torque", 0.90)])
def test_the_needle_rows_single_samples_meet_one_percent(resolved_10hz, name, factor):
    # the default (a second Newton pass where the first moved the velocities by more than
    # newton_tol, a backward-Euler substep after a smaller jump of the slip), one roller
    # settled at 10 Hz, 300 N m, 8 deg: single samples of Fz_joint within the 1 % of
    # order 3 of the reference of h/20, and that reference converged (within 1 % of h/10).
    # Measured here (the transients table's realization) 0.64, 0.83, 0.61, 0.03, 0.15 and
    # 0.07 %; on four others (settling whirl nudged by 1e-11 to 3e-7): omega +1 % 0.68-0.75 %,
    # omega -1 % 0.72 %, omega +10 % 0.61-0.62 %, torque +10 % 0.02-0.08 %, torque -1 %
    # 0.05-0.16 %, torque -10 % 0.04-0.10 %, references moving by at most 0.60 %.  One pass a
    # substep missed these cells by 0.4-2.8 % (docs/integrators.md#needle-resolved-bearing);
    # torque -10 % read 1.24 % here while a load step jumped the row's offset (the test
    # below).  Theta steps are left out: no reference converges there with any substep
    dev, moved = T.checked_case({"bearing": 2}, 1, 10, name, factor, resolved_10hz)
    assert moved < 1.0
    assert dev < 1.0


@pytest.mark.slow   # (make test-slow: CI runs it after make test)
def test_the_needle_rows_order_3_follows_a_theta_step(resolved_10hz):
    # a held theta step moves the trunnion into the row at once: its single samples have no
    # converged reference (h/10 and h/20 part by up to 63 % of order 3 in the transients
    # table), but order 3 over the whirl cycle after the step (from 0.1 to 1.1 cycles after
    # it) has: within the 1 % of the reference of h/20, that reference within 1 % of
    # h/10.  Measured (this realization) theta +-1 % and +-10 %: 0.20-0.35 %, the references
    # 0.03-0.13 % apart, a 1e-15 twin within 0.15 %.  One pass a substep meets it too (theta
    # +-10 %: 0.49 % and 0.33 %): the test guards the order's value after the jump (a bias of
    # the step input's handling), not the row's chaos
    dev, moved = T.cycle_case({"bearing": 2}, 1, 10, "theta", 1.10, resolved_10hz)
    assert moved < 1.0
    assert dev < 1.0


def test_rounding_leaves_the_needle_rows_single_samples(resolved_10hz):
    # the counterpart of the one-pass test above: from the row settled with the default a
    # 1e-15 change of the state moves single samples by 0.01-0.15 % of order 3 in these cells
    # (four realizations; torque -10 % 0.01-0.07 % on five, 1.07 % here while a load step
    # jumped the row's offset); one pass: 0.3-2.2 %.  Asserted: below half the 1 %
    cells = [("omega", 1.0), ("omega", 1.01), ("torque", 0.99), ("torque", 0.90)]
    single = [T.case({"bearing": 2}, 1, 10, n, f, resolved_10hz, perturb=1e-15)
              for n, f in cells]
    assert max(single) < 0.5, single


def _spin_alternation(params, state, theta, torque, substeps=400):
    """From ``state``, the share of ``substeps`` needle-row substeps (one a communication
    step, at the step's own substep) at which the second difference of the roller's spin
    changes sign: about 0.2-0.5 for smooth motion, 1 for a period-2 oscillation."""
    import numpy as np
    m = T._model(params, 1)
    from tripod_model.layout import H_SUB, Y_OM   # (on the path _model put it)
    m.set_state(state)
    w = 2 * math.pi * 10
    m.step(T.DT, theta, w, 0.0, torque)
    h = m.rollers[0]._hs[H_SUB]
    om = []
    for _ in range(substeps):
        m.step(h, theta, w, 0.0, torque)
        om.append(m.rollers[0].Y[Y_OM])
    d2 = np.diff(om, 2)
    return float(np.mean(np.sign(d2[1:]) != np.sign(d2[:-1])))


def test_the_second_pass_removes_the_one_pass_steps_period_2_oscillation():
    # one roller at 25 deg and 2000 N m (30 kN), settled with one pass a substep: its
    # velocities oscillate from substep to substep, the second difference of the spin changing
    # sign at every substep (measured 1.00 over 400), which no motion the 2.6 us substep
    # resolves does.  From the same state at half that substep it changes sign at 0.14 of
    # them, as smooth motion does (300 N m, 8 deg: 0.21-0.29); with the default's second pass
    # at its own, 36 % longer substep at 0.27 (0.20 from the default's own settled state)
    theta, torque = math.radians(25.0), 2000.0
    m, _ = T.settle(T.ONE_PASS, 1, 10, theta=theta, torque=torque)
    st = m.get_state()
    h = m.rollers[0].substep(theta, 2 * math.pi * 10, m.pressing(0.0, torque),
                             m.rollers[0].v_st(theta, 2 * math.pi * 10))
    assert _spin_alternation(T.ONE_PASS, st, theta, torque) > 0.9
    assert _spin_alternation(dict(T.ONE_PASS, max_substep=h / 2), st, theta, torque) < 0.6
    assert _spin_alternation({"bearing": 2}, st, theta, torque) < 0.6


@pytest.fixture(scope="module")
def launch_resolved():
    return T.settle({"bearing": 2}, 1, 10, theta=T.LAUNCH_THETA, torque=T.LAUNCH_TORQUE)


@pytest.mark.parametrize("name,factor", [("omega", 1.0), ("omega", 1.01), ("torque", 0.99)])
def test_the_needle_row_follows_a_launchs_angle(launch_resolved, name, factor):
    # one roller settled at 10 Hz, 25 deg and 3000 N m (45 kN) with the default: single
    # samples of Fz_joint within the 1 % of order 3 of the reference of h/20 with no
    # step and after +-1 % steps, the reference within 1 % of h/10.  Measured 0.00-0.15 % (no
    # step, omega and torque cells, two realizations; the second pass in four fifths of the
    # substeps there); one pass keeps its period-2 oscillation and misses these cells by
    # 1.3-1.5 % (the transients table)
    kw = {"theta": T.LAUNCH_THETA, "torque": T.LAUNCH_TORQUE}
    dev, moved = T.checked_case({"bearing": 2}, 1, 10, name, factor, launch_resolved, **kw)
    assert moved < 1.0
    assert dev < 1.0


def test_the_needle_resolved_bearing_takes_a_torque_step_at_a_launchs_load():
    # one roller settled at 10 Hz, 8 deg and 3000 N m (45 kN on the roller), then torque +10 %:
    # single samples of Fz_joint within the 1 % of order 3 of the reference of h/20,
    # and that reference converged (within 1 % of the one at h/10).  Measured over six
    # realizations (settling whirl nudged by 0 to 1e-7; benchmarks.md): 0.29-0.72 %, the
    # reference moving 0.08-0.43 %; with the row's offset ramped over the load step
    # 0.06 % on three (nudged by 0, 1e-9, 1e-7), the reference within 0.02 %.  The step
    # input's substeps of h/4 (the split before BDF_FINE_SPLIT) missed by 1.41 % (bdf2.BDF_FINE_SPLIT)
    base = T.settle({"bearing": 2}, 1, 10, torque=3000.0)
    dev, moved = T.checked_case({"bearing": 2}, 1, 10, "torque", 1.10, base, torque=3000.0)
    assert moved < 1.0
    assert dev < 1.0


def test_a_jump_below_a_step_input_restarts_bdf2_by_backward_euler():
    # the mechanism: a jump of the slip's amplitude above oppoint.JUMP_RELAX v_st (about 0.5 % of
    # omega) and up to JUMP_STEP restarts BDF2 by one backward-Euler substep; a ramp's
    # smaller jumps keep the history, a larger one is a step input.  Carrying the history across
    # an omega step of 1 % read 0.89-0.99 % of order 3 against h/20 on sixteen realizations at
    # 300 N m (a first-order error of the substep), restarted 0.64-0.83 % on five
    import numpy as np
    from tripod_model import bdf2, layout as LY, oppoint
    P = np.zeros(LY.P_LEN)
    for jump, want in ((0.5 * oppoint.JUMP_RELAX, 1.0),
                       (0.5 * (oppoint.JUMP_RELAX + oppoint.JUMP_STEP), bdf2.BDF_RESTART),
                       (2.0 * oppoint.JUMP_STEP, bdf2.BDF_STEP_IN)):
        hs = np.zeros(LY.H_LEN)
        hs[LY.H_GA] = 1.0
        bdf2.inputs_jumped(P, hs, jump)
        assert hs[LY.H_GA] == want, (jump, hs[LY.H_GA])


def test_a_load_change_moves_the_needle_rows_offset_over_its_step(monkeypatch):
    # the mechanism: the needle-resolved bearing's pressing offset moves from the old load's
    # value to the new one's over the step in which the load changed (lifecycle.step_unit),
    # ending where the held load puts it; no ramp at the first step, at an unchanged load,
    # after a restore at the load the state was stepped at, or with a comparison integrator
    m = T._model({"bearing": 2, "n_needles": 12}, 1)
    from tripod_model import lifecycle
    seen, run = [], lifecycle.run_substeps
    monkeypatch.setattr(lifecycle, "run_substeps",
                        lambda Y, P, drive, *a: (seen.append(drive), run(Y, P, drive, *a))[1])
    w, dt = 2 * math.pi * 10, 1e-4
    for tq in (300.0, 300.0, 270.0, 270.0):
        m.step(dt, T.THETA, w, 0.0, tq)
    st = m.get_state()
    m.step(dt, T.THETA, w, 0.0, 270.0)
    m.set_state(st)
    m.step(dt, T.THETA, w, 0.0, 300.0)
    m.set_state(st)   # again, now with the offset of 300 N m cached: the old one is computed
    m.step(dt, T.THETA, w, 0.0, 300.0)
    r = m.rollers[0]
    x300, x270 = (r.pressing_offset(m.pressing(0.0, tq)) for tq in (300.0, 270.0))
    assert [d.x0_rate for d in seen[:2]] == [0.0, 0.0]
    assert seen[2].x0_rate == pytest.approx((x270 - x300) / dt, rel=1e-12)
    assert seen[2].x0 == x270
    assert [d.x0_rate for d in seen[3:5]] == [0.0, 0.0]
    assert seen[5].x0_rate == pytest.approx((x300 - x270) / dt, rel=1e-12)
    assert seen[6] == seen[5]
    # a comparison integrator moves its offset at once (only BDF2's substeps follow the ramp)
    split = T._model({"bearing": 2, "n_needles": 12, "integrator": 3}, 1)
    seen.clear()
    for tq in (300.0, 270.0):
        split.step(dt, T.THETA, w, 0.0, tq)
    assert [d.x0_rate for d in seen] == [0.0, 0.0]


def test_a_load_step_leaves_the_needle_row_deterministic():
    # torque -10 % at 300 N m on the realization (settling whirl nudged by 1e-9) where the
    # offset's jump at once (before the ramp) missed the reference of h/20 by 1.63 % of order
    # 3, that reference 1.47 % from h/10: the jump drove the roller into the groove at infinite
    # speed and the row answered chaotically.  With the offset ramped over the step: single
    # samples within the 1 %, the reference converged (within 1 % of h/10), and a
    # 1e-15 change of the state moving them by less than half of it.  Measured 0.04 %, the
    # reference 0.01 % from h/10, the twin 0.01 %; on four other realizations 0.07-0.10 %
    base = T.settle({"bearing": 2}, 1, 10, nudge=1e-9)
    dev, moved = T.checked_case({"bearing": 2}, 1, 10, "torque", 0.90, base)
    twin = T.case({"bearing": 2}, 1, 10, "torque", 0.90, base, perturb=1e-15)
    assert moved < 1.0
    assert dev < 1.0
    assert twin < 0.5


@pytest.mark.parametrize("dt,fine", [(1e-4, [16] * 7 + [2]), (1e-3, [16, 16, 2])])
def test_the_resolved_rows_bdf2_takes_a_step_input_in_finer_substeps(dt, fine):
    # the mechanism: a step input takes the communication steps of the next 0.8 ms, at least
    # three, in substeps of h/16, the last h/2 (bdf2.BDF_STEP_IN); a ramp's small change
    # leaves the steady substep
    from tripod_model import layout as LY
    m = T._model({"bearing": 2}, 1)
    w = 2 * math.pi * 10
    r = m.rollers[0]
    for _ in range(3):
        m.step(dt, T.THETA, w, 0.0, T.TORQUE)
    taken = []
    for k in range(len(fine) + 2):
        before = r._hs[LY.H_TAKEN]
        m.step(dt, T.THETA, w * (1.001 if k == 0 else 1.101), 0.0, T.TORQUE)
        taken.append(r._hs[LY.H_TAKEN] - before)
    steady = taken[0]                 # the ramp's small step (jump 0.004 < oppoint.JUMP_STEP)
    assert steady == pytest.approx(math.ceil(dt / r.substep(
        T.THETA, w * 1.001, m.pressing(0.0, T.TORQUE), r.v_st(T.THETA, w * 1.001))), abs=1)
    assert taken[1:] == pytest.approx([k * steady for k in fine] + [steady], abs=max(fine))
    assert r._hs[LY.H_GA] == 1.0                  # the countdown over: BDF2's history valid


ULP_CASES = {"ideal": ({}, 300.0), "lumped": ({"bearing": 1}, 300.0),
             "floating-spider": ({"spider": 1}, 300.0),
             "floating-spider-lumped": ({"spider": 1, "bearing": 1}, 300.0),
             "floating-spider-lumped-launch": ({"spider": 1, "bearing": 1}, 3000.0)}
# The floating spider's lumped rows start each substep's Newton from their forces, and where a
# last bit flips whether Newton stops, the step it did not take is left: at most GA_NTOL v_st
# in a velocity, which moves the friction by at most its slope, 3 mu f_n / v_st, times that:
# 3 GA_NTOL of mu f_n, and mu f_n is several times Fz_joint's scale; held to 3 GA_NTOL of the
# scale.  Measured 2.4e-8 at 300 N m (two isolated spikes a cycle) and 4.5e-12 at 3000 N m;
# the other cases 0-2.5e-12, held to 1e-9 (docs/integrators.md).
ULP_NEWTON = {"floating-spider-lumped", "floating-spider-lumped-launch"}


@pytest.mark.parametrize("case", sorted(ULP_CASES))
def test_an_ulp_of_an_input_moves_the_outputs_by_a_rounding(case):
    # outputs continuous in the inputs (oppoint.JUMP_FULL, genalpha.GA_NTOL, the driving
    # motions' rates in closed form): the whole joint settled at 10 Hz, 8 deg, 300 N m (and a
    # launch's 3000 N m on the floating spider); omega, theta and torque each moved by one ulp
    # and held: Fz_joint within 1e-9 of its scale of the unmoved run over the next 1,000 steps
    # (the floating spider's lumped rows: ULP_NEWTON).
    # A restart taken in full on any change moved it by 6.8e-5 to 1.9e-4; Newton stopped at
    # 1e-3 v_st, the floating spider's lumped rows by 1.2e-4 to 2.6e-4; the rates by finite
    # differences, theta by 1.1e-9 to 3.1e-9 whatever its move.  Measured 0-9.0e-12
    # (docs/integrators.md); the bound leaves a factor of 100 for other CPUs
    import numpy as np
    params, torque = ULP_CASES[case]
    m, _ = T.settle(params, 3, 10, torque=torque)
    state = m.get_state()
    held = {"theta": T.THETA, "omega": 2 * math.pi * 10, "torque": torque}

    def run(name):
        r = T._model(params, 3)
        r.set_state(state)
        inputs = dict(held)
        if name:
            inputs[name] = math.nextafter(inputs[name], math.inf)
        return np.array([r.step(T.DT, inputs["theta"], inputs["omega"], 0.0,
                                inputs["torque"])["Fz_joint"] for _ in range(1000)])

    base = run(None)
    scale = np.abs(base).max()
    moved = {n: np.abs(run(n) - base).max() / scale for n in T.INPUTS}
    from tripod_model.genalpha import GA_NTOL
    assert max(moved.values()) < (3 * GA_NTOL if case in ULP_NEWTON else 1e-9), moved


def test_the_integrator_restarts_where_the_inputs_jumped():
    # the mechanism itself: a jump flags the next step (restart), no jump leaves the history
    from tripod_model import genalpha, kernel, layout as LY, oppoint
    m = T._model({}, 1)
    w = 2 * math.pi * 10
    for _ in range(5):
        m.step(1e-4, T.THETA, w, 0.0, T.TORQUE)
    r = m.rollers[0]
    r.set_inputs(1e-4, T.THETA, w, 0.0, T.TORQUE)
    assert kernel.derive_op(r.P, r._OP) == -1.0            # the same inputs: no jump
    r.set_inputs(1e-4, T.THETA, w * 1.001, 0.0, T.TORQUE)
    jump = kernel.derive_op(r.P, r._OP)
    assert 0.0 < jump < oppoint.JUMP_RELAX                 # a ramp's step: the cheap restart
    r.set_inputs(1e-4, T.THETA, w * 1.1, 0.0, T.TORQUE)
    assert kernel.derive_op(r.P, r._OP) > oppoint.JUMP_RELAX    # a step input: the adaptive one
    r.set_inputs(1e-4, T.THETA, w * 1.1, 0.0, T.TORQUE * 1.001)
    assert kernel.derive_op(r.P, r._OP) == 0.0               # a load change alone: no slip jump
    assert r.P[LY.P_DF] == pytest.approx(1e-3, rel=1e-3)  # (its own size)
    hs3 = r._hs[LY.H_GA]
    genalpha.inputs_jumped(r.P, r._hs, 0.0)
    assert r._hs[LY.H_GA] == hs3                               # small: no restart (ideal bearing)
    r.set_inputs(1e-4, T.THETA, w * 1.1, 0.0, T.TORQUE * 1.1)
    assert kernel.derive_op(r.P, r._OP) == 0.0
    genalpha.inputs_jumped(r.P, r._hs, 0.0)
    assert r._hs[LY.H_GA] == genalpha.GA_STEP_IN                      # a load step: the adaptive one


@pytest.mark.parametrize("params", [{}, {"bearing": 1}], ids=["ideal", "lumped"])
def test_the_step_after_a_restart_takes_the_restarts_forces(params):
    # GA_RESTART has alpha_f = 0: its equation holds at t_{n+1}, at the state the step then
    # writes, so the accelerations it leaves for the regular step after it (hs[H_FACC:]) are
    # those the forces give at that state: evaluated there, or, where Newton stops on a step
    # below its tolerance without evaluating them, implied by the equation, off by its residual
    # there, second order in that step: below 1 % of the tolerance in the velocity change it
    # makes over the step (measured 1e-4 and 1e-7 of it; the accelerations before the step
    # would be 10 and 1 tolerances off).  With one substep a communication step (2e-5 s at
    # 10 Hz, 300 N m) the restart is the step's last
    import numpy as np
    from tripod_model import genalpha, layout as LY
    m = T._model(params, 1)
    w = 2 * math.pi * 10
    for i in range(40):     # a ramp of +1e-4 a step: the cheap restart at every step
        m.step(2e-5, T.THETA, w * (1 + 1e-4 * i), 0.0, T.TORQUE)
    r = m.rollers[0]
    assert r._OP[LY.OP_N] == 1 and r._hs[LY.H_GA] == genalpha.GA_AFTER_RESTART
    drive = LY.Drive(r._OP[LY.OP_THETA], r._OP[LY.OP_W], r._OP[LY.OP_X0], 0.0)
    Q, M = np.zeros(LY.NV), np.zeros(LY.NV)
    nv = genalpha.ga_forces(r.Y.copy(), r.P, drive, r._L.copy(), r._res.copy(), Q, M)
    kept = r._hs[LY.H_FACC:LY.H_FACC + nv]
    # each unknown's velocity change over the restart step, h gamma a, against the tolerance
    # (a rotation's at the roller radius)
    per_tol = r._OP[LY.OP_H] * genalpha.GA_RESTART[2] / (genalpha.GA_NTOL * r.P[LY.P_VST_OP]) * \
        np.array([r.P[LY.P_R_ROLLER] if LY.V_ROT[i] > 0.0 else 1.0 for i in range(nv)])
    assert np.all(np.abs(kept - Q[:nv] / M[:nv]) * per_tol <= 0.01) and np.all(kept != 0.0)


@pytest.mark.parametrize("params", [{}, {"bearing": 1}], ids=["ideal", "lumped"])
def test_what_a_joint_copies_from_one_derive_is_all_derive_writes(params):
    # kernel.step derives the first roller's operating point and copies it to the others
    # (oppoint.copy_derived, by its lists OP_DERIVED and P_DERIVED): every slot derive changes
    # must be on those lists, and the copy must be what derive would have written
    import numpy as np
    from tripod_model import kernel, oppoint
    m = T._model(params, 3)
    w = 2 * math.pi * 10
    m.step(1e-4, T.THETA, w, 0.0, T.TORQUE)
    a, b = m.rollers[0], m.rollers[1]
    for r in (a, b):      # new values of every input and a new step
        r.set_inputs(5e-5, 1.1 * T.THETA, 1.2 * w, 0.0, 1.3 * T.TORQUE, 0.01)
    P0, OP0 = b.P.copy(), b._OP.copy()
    kernel.derive_op(a.P, a._OP)
    kernel.derive_op(b.P, b._OP)
    assert set(np.flatnonzero(b.P != P0)) <= set(oppoint.P_DERIVED)
    assert set(np.flatnonzero(b._OP != OP0)) <= set(oppoint.OP_DERIVED)
    P1, OP1 = P0.copy(), OP0.copy()
    kernel.copy_op(a.P, a._OP, P1, OP1)
    assert np.array_equal(P1, b.P) and np.array_equal(OP1, b._OP)


@pytest.mark.parametrize("dt", [1e-4, 2e-5])
def test_a_run_up_reads_the_settled_order_3(dt):
    # 2 -> 40 Hz in 0.5 s, three rollers, 300 N m, 8 deg, the master holding omega over each
    # communication step (a staircase: a jump every step); before the restart order 3 read
    # 10.7 % low at 7.2 Hz (1e-4 s).  Each revolution against the settled order 3 at its mean
    # speed: within 1 % (the bound; measured 0.0-0.16 %)
    revs = T.runup({}, 3, 2.0, 40.0, 0.5, dt=dt)
    assert len(revs) >= 5
    for f, a in (revs[0], revs[len(revs) // 2], revs[-1]):
        ref = T.settle({}, 3, f, cycles=4)[1]
        assert abs(a / ref - 1) < 0.01, (f, a, ref)


def test_runup_command_tracks_orders_of_both_fmus(tmp_path):
    # a short run-up through both FMUs in FMPy: one row per whole revolution, speeds rising,
    # order 3 of the joint three times a roller's (about 67 N here), the analytic FMU within 3 %
    # of the contact FMU along the run (the bound), files written
    import csv
    import json
    from harness.cli import main
    assert main(["runup", "--from-hz", "4", "--to-hz", "12", "--duration", "0.4",
                 "--out", str(tmp_path)]) == 0
    rows = json.loads((tmp_path / "runup.json").read_text())
    assert all(r["signal"] == "Fz_joint" for r in rows)
    assert len(rows) >= 2 and all(b["speed_hz"] > a["speed_hz"] for a, b in zip(rows, rows[1:]))
    assert all(abs(r["order3_diff_pct"]) < 3.0 for r in rows)
    assert all(60 < r["contact_order3"] < 75 for r in rows)
    assert len(list(csv.DictReader(open(tmp_path / "runup.csv")))) == len(rows)
    assert (tmp_path / "runup.png").stat().st_size > 0


def test_runup_of_one_roller_tracks_its_modified_thrust(tmp_path):
    # one roller: orders of Fz_mod (the paper's Fz' = Fz F_press / Fx, section 3.2), as the
    # issue asks, not of Fz_joint (which is then the roller's Fz): order 3 of Fz_mod is
    # 21.6-21.7 N at 300 N m and 8 deg, of Fz 22.4-22.5 N (the transients table, 2 and 10 Hz);
    # a run-up reads the settled value within 1 % (test_a_run_up_reads_the_settled_order_3),
    # so the bound 22.05 N (midway) tells the two apart; the analytic FMU within 3 % along the
    # run; the files and the plot name the signal
    import json
    from harness.cli import main
    assert main(["runup", "--set", "n_rollers=1", "--from-hz", "4", "--to-hz", "12",
                 "--duration", "0.3", "--out", str(tmp_path)]) == 0
    rows = json.loads((tmp_path / "runup.json").read_text())
    assert len(rows) >= 1 and all(r["signal"] == "Fz_mod" for r in rows)
    assert all(20 < r["contact_order3"] < 22.05 for r in rows)
    assert all(abs(r["order3_diff_pct"]) < 3.0 for r in rows)


def test_orders_per_revolution_in_reverse_whirl():
    # a reverse-gear history (whirl angle falling) gave "no whole revolution": it counts the
    # revolutions of the angle travelled, its speed negative; a signal of orders 1 and 3 in
    # that angle reads the same per revolution as forward (resampled at 720 points a
    # revolution from 2000 samples: within 1e-3); a whirl that turns back is refused
    import numpy as np
    t = np.linspace(0.0, 0.4, 4001)
    u = 2 * math.pi * 5.0 * t                       # 5 Hz, two whole revolutions
    y = 2.0 * np.sin(3 * u + 0.5) + np.sin(u)
    fwd, rev = T.revolution_orders(t, u, y), T.revolution_orders(t, -u, y)
    assert len(fwd) == len(rev) == 2
    for f, r in zip(fwd, rev):
        assert r["speed_hz"] == pytest.approx(-5.0) and f["speed_hz"] == pytest.approx(5.0)
        assert r["order3"] == pytest.approx(2.0, rel=1e-3)
        assert r["order1"] == pytest.approx(1.0, rel=1e-3)
        assert r["order3_deg"] == pytest.approx(f["order3_deg"], abs=1e-9)
    with pytest.raises(ValueError, match="changes direction at t = 0.2"):
        T.revolution_orders(t, np.where(t < 0.2, u, 2 * u[2000] - u), y)


def test_runup_gives_each_fmu_the_parameters_its_model_has():
    # a contact-only parameter (running_clearance; the analytic FMU has no such variable and
    # FMPy refused the whole run) reaches the contact FMU only, shared ones (spin_inertia)
    # both; a name neither has, or a value out of range, is refused by name before any run
    sv = dict(T.RUNUP_START, running_clearance=1e-3, spin_inertia=False)
    by = T.start_values_by_model(sv)
    assert by["contact"] == sv
    # (the analytic model paired with the contact model's default, the ideal bearing)
    assert by["analytic"] == dict(T.RUNUP_START, spin_inertia=False, needle_row=False)
    with pytest.raises(ValueError, match="no_such"):
        T.start_values_by_model({"no_such": 1.0})
    with pytest.raises(ValueError, match="running_clearance"):
        T.start_values_by_model({"running_clearance": 1e-4})


def test_runup_refuses_a_bad_input_file(tmp_path, capsys):
    from harness.cli import main
    bad = tmp_path / "in.csv"
    bad.write_text("time,speed\n0,1\n1,2\n")
    assert main(["runup", "--input", str(bad), "--out", str(tmp_path)]) == 2
    assert "column 'speed' is no input" in capsys.readouterr().err
    # a communication step that is no step: refused by name (it reached the FMU's doStep,
    # whose failure was the only message)
    assert main(["runup", "--dt", "-1", "--out", str(tmp_path)]) == 2
    assert "dt = -1.0: allowed range (0, inf) s" in capsys.readouterr().err


def test_launch_from_standstill_both_fmus_agree():
    # omega 0 -> 5 Hz in 1 s at 500 N m, 8 deg, three rollers (the contact FMU peaked at 292 N
    # against the analytic FMU's 113 N before the restart): order 3 per revolution within 5 %
    # of each other from the second revolution on, and no sample beyond what the groove
    # friction can carry, mu F (F = 500 N m / (3 s) per roller, Fx up to 10 % above F with the
    # roller's traverse, model.md) summed over the rollers, plus the spin-inertia thrust
    # (I_spin / r^2) s tan(theta) w^2 per roller at the end speed
    import numpy as np
    from harness.fmus import ensure_fmu
    from harness.runs import run_fmu
    from reduced_model.scene import defaults
    sv = dict(T.RUNUP_START, torque=500.0)
    inputs = T.ramp_inputs(0.0, 5.0, 1.0)
    p = defaults("contact")
    F = 500.0 / (3 * p["s"])
    w1 = 2 * math.pi * 5.0
    spin = 0.5 * p["m_roller"] * p["s"] * math.tan(T.THETA) * w1 ** 2   # I = m r^2 / 2 at most
    bound = 3 * (1.1 * p["mu_groove"] * F + spin)
    revs = {}
    # (paired as the cross-check pairs them: the ideal bearing and the traverse model without
    # the needle row)
    for name, over in (("TripodRoller", {}), ("TripodRollerAnalytic", {"needle_row": False})):
        r = run_fmu(ensure_fmu(name), dict(sv, **over), stop_time=1.0, output_interval=1e-4,
                    outputs=["Fz_joint", "whirl_angle"], inputs=inputs)
        assert np.isfinite(r["Fz_joint"]).all() and np.abs(r["Fz_joint"]).max() < bound
        revs[name] = T.revolution_orders(r["time"], r["whirl_angle"], r["Fz_joint"])
    c, a = revs["TripodRoller"], revs["TripodRollerAnalytic"]
    assert len(c) >= 2
    for rc, ra in list(zip(c, a))[1:]:
        assert abs(ra["order3"] / rc["order3"] - 1) < 0.05


def test_a_varying_communication_step_adds_no_error():
    # three rollers settled at 10 Hz, 300 N m, 8 deg; from that state 200 communication steps
    # drawn from 20-200 us (a variable-step master: each new size sets a new substep, the
    # step's history carried across) against a reference from the same state at a tenth of
    # the substep and of each step: within 1 % of order 3 (the input steps' criterion) and
    # within 1.25x what 200 fixed 100 us steps miss the same way by (0.58 % each, measured;
    # the varying steps average 110 us, coarser)
    import numpy as np
    from tripod_model.layout import H_GA   # (on the path T._model put it)
    m, a3 = T.settle({}, 3, 10)
    st = m.get_state()
    w = 2 * math.pi * 10
    h = m.rollers[0].substep(T.THETA, w, m.pressing(0.0, T.TORQUE), m.rollers[0].v_st(T.THETA, w))

    def miss(steps):
        m.set_state(st)
        y = [m.step(dt, T.THETA, w, 0.0, T.TORQUE)["Fz_joint"] for dt in steps]
        r = T._model({}, 3, max_substep=h / 10)
        r.set_state(st)
        for roller in r.rollers:
            roller._hs[H_GA] = 0.0
        ref = []
        for dt in steps:
            for _ in range(10):
                o = r.step(dt / 10, T.THETA, w, 0.0, T.TORQUE)
            ref.append(o["Fz_joint"])
        return 100 * np.abs(np.array(y) - np.array(ref)).max() / a3

    varying = miss(np.random.default_rng(3).uniform(2e-5, 2e-4, 200))
    fixed = miss(np.full(200, 1e-4))
    assert varying < 1.0 and varying < 1.25 * fixed, (varying, fixed)
