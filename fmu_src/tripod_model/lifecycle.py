"""The contact FMU's lifecycle as scalar functions over flat arrays, as
reduced_model/analytic_kernel.py keeps the analytic FMU's: ``init``, ``step`` (in parts, whose
units native_units.c runs at once), ``end`` and host_state.py's ``state_problem``, compiled
ahead of time (c_functions, fmu_src/aot.py) into the FMU's binary, which then runs without
Python.  They compose the model's own functions: roller_setup.py (the parameter vector, the
needle row, the start on the settled cycle) and kernel.py (the step), and run as Python in
process (harness/inprocess.py) they are the oracle the binary is held to bit for bit
(tests/test_native_fmu.py).  The arrays, their places and views: fmu_arrays.py.
"""
import math

from reduced_model import equations as RE
from reduced_model.equations import operating_point
from reduced_model.scene import BY_NAME, params_for, pressing_load, same_step
from reduced_model.table import D_COUNT, SETTLED_TOL, traverse_table
from . import layout as K
from .contact import trunnion_axial
from .fmu_arrays import (ANALYTIC_SLOTS, FAILS, IN_HI, IN_LEN, IN_LO, INPUT_NAMES, MAX_NOTES,
                         NOTE_ADAPT, NOTE_BORE, NOTE_CLEARANCE, NOTE_GROOVE, NOTE_SPIDER,
                         NOTE_INFO, NOTE_INFO_OP, NOTE_ROLLERS, NOTE_STEPS, NOTE_SUMMARY,
                         NOTE_SUMMARY_ADAPT, NOTE_SUMMARY_BDF, NOTE_SUMMARY_GA, NOTE_TEXT,
                         NOTE_TOO_LONG, NW_LEN, OMEGA, F_PRESS, OUT_LEN, PLUNGE_SPEED,
                         SHAFT_ANGLE, STATE_PROBLEMS, T_LEN, TABLE_N, TABLE_ROWS, THETA, TORQUE,
                         W_BS, W_LEN, W_D, W_L, W_NOTES, W_NW, W_O, W_PA, W_PS, W_SAVE, W_SS,
                         W_T, W_TKEY, W_X0, X_HS, X_LEN, X_OP, X_OUTV, X_P, X_STARTED,
                         X_STEPS, X_TIME, X_Y, X_Y2, _at, needle_work, note, op_row, shape_of,
                         work, W_A, W_B, W_G, W_GW, W_RES, W_Y1)
from .kernel import (_roller, derive_op, inputs_moved, joint_into, outputs_into, resolved_drive,
                     run_substeps, spider_into, step_joint, step_roller)
from .oppoint import substep, v_st
from .roller_setup import (PARAM_NAMES, T_BEARING, T_DRIVE_BY_ANGLE,
                           T_N_ROLLERS, T_SPIDER, T_R_BORE, T_R_GROOVE, T_R_ROLLER, T_RUNNING_CLEARANCE,
                           T_S, T_AXIAL, T_TRAVERSE, kernel_params, needle_params,
                           place_on_cycle, pressing_offset, start_needles, start_state,
                           uses_table)
# (SPEED_MARGIN, VST_HI, WHIRL_HI: globals of the compiled copies of state_check's functions)
from .state_check import (SPEED_MARGIN, VST_HI, WHIRL_HI, history_bound,  # noqa: F401
                          roller_bound, speed_limit, spider_bounds)
# (compiled with this module's functions: a state a host sets)
from .host_state import roller_problem, spider_problem, state_problem  # noqa: F401
from reduced_model.scene import SPIDER_FREE


# --- set-up and start -------------------------------------------------------------------------
def check_scene(T, W):
    """The relations between parameters the table's ranges cannot state (scene.validate): a note
    naming them and False where one fails."""
    if T[T_R_GROOVE] <= T[T_R_ROLLER]:
        note(W, NOTE_GROOVE, T[T_R_GROOVE], T[T_R_ROLLER], 0.0, 0.0)
        return False
    c, c0 = T[T_RUNNING_CLEARANCE], 2.0 * (T[T_R_GROOVE] - T[T_R_ROLLER])
    if c != 0.0 and c < c0:
        note(W, NOTE_CLEARANCE, c, c0, c0, 0.0)
        return False
    if T[T_N_ROLLERS] != 1.0 and T[T_N_ROLLERS] != 3.0:
        note(W, NOTE_ROLLERS, T[T_N_ROLLERS], 0.0, 0.0, 0.0)
        return False
    if T[T_R_BORE] >= T[T_R_ROLLER]:
        note(W, NOTE_BORE, T[T_R_BORE], T[T_R_ROLLER], 0.0, 0.0)
        return False
    if T[T_SPIDER] == SPIDER_FREE and (T[T_N_ROLLERS] != 3.0
                                       or T[T_BEARING] == K.BEAR_RESOLVED):
        note(W, NOTE_SPIDER, T[T_N_ROLLERS], T[T_BEARING], 0.0, 0.0)
        return False
    return True


def setup(T, X, W):
    """X at rest for the parameters T: each roller's parameter vector and operating point (no
    key yet: set at the first step), the needle rows' parameters, the line caches empty."""
    for j in range(X_LEN):
        X[j] = 0.0
    n, resolved, nn, ns, ny, ys = shape_of(T)
    for i in range(n):
        kernel_params(T, X[X_P + i * K.P_LEN:X_P + (i + 1) * K.P_LEN])
        if resolved:
            needle_params(T, W[W_NW + i * NW_LEN:W_NW + i * NW_LEN + K.N_LEN])
        for j in range(K.L_LEN):
            W[W_L + i * K.L_LEN + j] = math.nan     # the line kinematics' cache key: none
        for j in range(3):
            W[W_X0 + 3 * i + j] = 0.0
    if n > 1 and not resolved:   # a joint stepped in one call (kernel.step_joint)
        X[X_OP + K.OP_NROLL] = n


def no_key(T, X):
    """No operating point derived yet on the rows the rollers step at (derive's first step)."""
    n, resolved, _, _, _, _ = shape_of(T)
    for i in range(n):
        X[X_OP + op_row(n, resolved, i) * K.OP_LEN + K.OP_KEY] = math.nan


def probe(ctx):
    """The kernel's (L, res) at a roller's state now, by a step of no substeps at the inputs
    in ctx: its P, OP and history kept.  ctx: (Y, P, OP, work, its output
    vector, W, theta, omega, F, vp, time, T, its needle work or None, its offset cache)."""
    Y, P, OP, Wk, out, W, theta, omega, F, vp, time, T, NW, cache = ctx
    hs = Wk.hs
    s = W_SAVE
    for j in range(K.P_LEN):
        W[s + j] = P[j]
    for j in range(K.OP_LEN):
        W[s + K.P_LEN + j] = OP[j]
    for j in range(K.H_LEN):
        W[s + K.P_LEN + K.OP_LEN + j] = hs[j]
    dt = 1e-4       # (any step: none is taken)
    if OP[K.OP_DT] > 0 and same_step(dt, OP[K.OP_DT], time):
        dt = OP[K.OP_DT]
    OP[K.OP_THETA] = theta
    OP[K.OP_W] = omega
    OP[K.OP_FP] = F
    OP[K.OP_TQ] = 0.0
    OP[K.OP_DT] = dt
    OP[K.OP_VP] = vp
    OP[K.OP_NOSTEP] = 1.0
    if NW is None:
        _roller(Y, P, OP, Wk, out, derive_op(P, OP))
    else:           # the needle-resolved row: its own pressing offset (step_unit)
        inputs_moved(P, hs, derive_op(P, OP))
        x0, rate = resolved_drive(P, T, OP, math.nan, 0, False, cache)
        # (n as the step computes it, not a literal 0: numba would compile the integrators
        # again for a literal argument)
        run_substeps(Y, P, K.Drive(OP[K.OP_THETA], OP[K.OP_W], x0, rate), OP[K.OP_H],
                     0 if OP[K.OP_NOSTEP] > 0.0 else int(OP[K.OP_N]), out, Wk, NW)
    for j in range(K.P_LEN):
        P[j] = W[s + j]
    for j in range(K.OP_LEN):
        OP[j] = W[s + K.P_LEN + j]
    for j in range(K.H_LEN):
        hs[j] = W[s + K.P_LEN + K.OP_LEN + j]
    return Wk.L, Wk.res


def settled_table(T, W, theta, omega, F, vp):
    """The traverse model's settled cycle at these inputs into W (W_SS, W_PS), where it places
    the rollers at the start (roller_setup.uses_table, place_on_cycle): whether it does.  A
    roller started at the groove bottom and at rest along the trunnion, its friction
    saturated, is thrown up the flank and rings (docs/integrators.md, "The start")."""
    if not uses_table(T, omega, F):
        return False
    key = W[W_TKEY:W_TKEY + 6]
    if key[4] != 0.0 and key[0] == theta and key[1] == omega and key[2] == F and key[3] == vp:
        return key[5] != 0.0      # (the start's outputs derived it at the same inputs)
    PA = W[W_PA:W_PA + RE.T_LEN]
    for j in range(RE.T_LEN):
        PA[j] = T[ANALYTIC_SLOTS[j]] if ANALYTIC_SLOTS[j] >= 0 else 0.0
    O = W[W_O:W_O + RE.O_LEN]
    O[RE.O_RA] = O[RE.O_RAF] = 0.0     # the row's offset from scratch: a start owes nothing to
    operating_point(PA, theta, omega, F, 0.0, vp, O)    # the instance's history
    cycles, mismatch, g_max = traverse_table(
        O, W[W_D:W_D + D_COUNT * TABLE_ROWS], TABLE_N, W[W_T:W_T + 5 * TABLE_ROWS],
        W[W_SS:W_SS + TABLE_ROWS], W[W_PS:W_PS + TABLE_ROWS], W[W_BS:W_BS + TABLE_ROWS])
    settled = mismatch <= SETTLED_TOL * O[RE.O_VST]
    key[0] = theta
    key[1] = omega
    key[2] = F
    key[3] = vp
    key[4] = 1.0
    key[5] = 1.0 if settled else 0.0
    return settled


def start(T, IN, X, W, F):
    """Every roller at its start at IN's inputs and the pressing load F
    [N]: at whirl angles 0, 120, 240 deg, rolling without slip, where the settled cycle has it
    (ideal and lumped bearing) or with its needles placed (resolved)."""
    n, resolved, nn, ns, ny, ys = shape_of(T)
    theta, omega, vp = IN[THETA], IN[OMEGA], IN[PLUNGE_SPEED]
    on_cycle = settled_table(T, W, theta, omega, F, vp)
    for i in range(n):
        Y = X[X_Y + i * ys:X_Y + i * ys + ny]
        P = X[X_P + i * K.P_LEN:X_P + (i + 1) * K.P_LEN]
        phase = 2.0 * math.pi * i / 3.0
        start_state(Y, P, T, phase, theta, omega, F)
        if on_cycle:
            r = op_row(n, resolved, i)
            ctx = (Y, P, X[X_OP + r * K.OP_LEN:X_OP + (r + 1) * K.OP_LEN], work(X, W, i, ny, ys),
                   X[X_OUTV + i * K.O_LEN:X_OUTV + (i + 1) * K.O_LEN], W, theta, omega, F, vp,
                   X[X_TIME], T, None, W[W_X0 + 3 * i:W_X0 + 3 * i + 3])
            place_on_cycle(Y, P, F, omega, W[W_SS:W_SS + TABLE_ROWS], W[W_PS:W_PS + TABLE_ROWS],
                           TABLE_N, probe, ctx)
        if resolved:
            start_needles(Y, T, phase, theta, nn,
                          trunnion_axial(phase, theta, T[T_S], T[T_AXIAL] != 0.0))
        hs = X[X_HS + i * K.H_LEN:X_HS + (i + 1) * K.H_LEN]
        hs[K.H_GA] = 0.0            # no previous step (generalized-alpha, BDF2) to continue from
        hs[K.H_RING] = K.RING_OPEN  # the roller's ring resolved from the start


def joint_outputs(out, n, s, F, theta, OUT):
    """The FMU's outputs from the rollers' output vectors out (n rows) at the pressing load F
    [N] per roller and the joint angle theta [rad].  Returns 1, or 2 (a
    non-finite output)."""
    total = 0.0   # left to right (sum() compensates from Python 3.12 on)
    for i in range(n):
        total += out[i, K.O_FZ]
    if not math.isfinite(total) or not outputs_into(out[0], F, OUT):
        return 2
    if not joint_into(out, n, s, F, OUT) or not spider_into(out, n, theta, s, F, out[0], False,
                                                           OUT):
        return 2
    OUT[K.OUT_FZ_JOINT] = total
    OUT[K.OUT_FZ_2] = out[1, K.O_FZ] if n > 1 else 0.0
    OUT[K.OUT_FZ_3] = out[2, K.O_FZ] if n > 2 else 0.0
    return 1


def init(T, IN, X, OUT, W):
    """The start's outputs (every roller started at IN's inputs and
    probed), the model then at rest: the first step starts from its own inputs.  Returns 1; 2
    for a non-finite output; 3 for a scene refused (its note says why)."""
    W[W_NOTES] = 0.0
    if not check_scene(T, W):
        return 3
    n, resolved, nn, ns, ny, ys = shape_of(T)
    setup(T, X, W)
    F = pressing_load(IN[F_PRESS], IN[TORQUE], T[T_S])
    P0 = X[X_P:X_P + K.P_LEN]
    vst = v_st(P0, IN[THETA], IN[OMEGA])
    note(W, NOTE_INFO, n, T[T_BEARING], T[T_TRAVERSE], 0.0)
    note(W, NOTE_INFO_OP, F, vst, substep(P0, IN[THETA], IN[OMEGA], F, vst, True),
         pressing_offset(P0, T, F))
    no_key(T, X)
    start(T, IN, X, W, F)
    for i in range(n):
        r = op_row(n, resolved, i)
        ctx = (X[X_Y + i * ys:X_Y + i * ys + ny], X[X_P + i * K.P_LEN:X_P + (i + 1) * K.P_LEN],
               X[X_OP + r * K.OP_LEN:X_OP + (r + 1) * K.OP_LEN], work(X, W, i, ny, ys),
               X[X_OUTV + i * K.O_LEN:X_OUTV + (i + 1) * K.O_LEN], W, IN[THETA], IN[OMEGA], F,
               IN[PLUNGE_SPEED], X[X_TIME], T)
        cache = W[W_X0 + 3 * i:W_X0 + 3 * i + 3]
        if resolved:
            probe(ctx + (needle_work(X, W, i, nn, ns), cache))
        else:
            probe(ctx + (None, cache))
    rc = joint_outputs(_at(X, X_OUTV, (n, K.O_LEN)), n, T[T_S], F, IN[THETA], OUT)
    setup(T, X, W)
    return rc


# --- the step ---------------------------------------------------------------------------------
def set_inputs(OP, IN, dt):
    """IN's inputs and the step dt [s] where the kernel reads them."""
    OP[K.OP_THETA] = IN[THETA]
    OP[K.OP_W] = IN[OMEGA]
    OP[K.OP_FP] = IN[F_PRESS]
    OP[K.OP_TQ] = IN[TORQUE]
    OP[K.OP_DT] = dt
    OP[K.OP_VP] = IN[PLUNGE_SPEED]


def refused(X, W, n):
    """A note on the first roller whose step ran out of its budget."""
    for i in range(n):
        hs = X[X_HS + i * K.H_LEN:X_HS + (i + 1) * K.H_LEN]
        P = X[X_P + i * K.P_LEN:X_P + (i + 1) * K.P_LEN]
        if hs[K.H_FAIL] == K.FAIL_LONG:
            note(W, NOTE_TOO_LONG, i + 1.0, hs[K.H_FAIL_DONE], hs[K.H_FAIL_H], 0.0)
            return
        for k in range(len(FAILS)):
            if hs[K.H_FAIL] == FAILS[k]:
                note(W, NOTE_ADAPT + k, i + 1.0, 100.0 * hs[K.H_FAIL_DONE], hs[K.H_FAIL_H],
                     P[K.P_HMAX])
                return


UNITS_NEXT = 4   # step_begin's code: the step's units next (native_model.h: model_step_begin)


def step_units(T):
    """How many independent parts a step has, each a step_unit: a joint's needle-resolved
    rollers (the spider prescribed, each reads and writes only its own slices of X and W, so
    the native layer steps them at once on the machine's cores, and any order gives the same
    bits); 0 for the other bearings (step_begin takes the step whole)."""
    n, resolved, _, _, _, _ = shape_of(T)
    return n if resolved else 0


def step_unit(T, X, W, i):
    """Needle-resolved roller i's step at its OP row's inputs (step_begin set them).  Returns
    1; 3 when it ran out of its budget (step_finish then refuses the step)."""
    n, resolved, nn, ns, ny, ys = shape_of(T)
    ramped = X[X_P + K.P_INTEGRATOR] == K.INT_DEFAULT   # (model.Roller.load_ramped)
    Y = X[X_Y + i * ys:X_Y + i * ys + ny]
    P = X[X_P + i * K.P_LEN:X_P + (i + 1) * K.P_LEN]
    OP = X[X_OP + (i + 1) * K.OP_LEN:X_OP + (i + 2) * K.OP_LEN]
    Wk = work(X, W, i, ny, ys)
    # the load the last step ran at (none before the first: its key's theta is NaN)
    F_was = (pressing_load(OP[K.OP_KEY + 2], OP[K.OP_KEY + 3], T[T_S])
             if OP[K.OP_KEY] == OP[K.OP_KEY] else math.nan)
    inputs_moved(P, Wk.hs, derive_op(P, OP))
    m = 0 if OP[K.OP_NOSTEP] > 0 else int(OP[K.OP_N])
    x0, rate = resolved_drive(P, T, OP, F_was, m, ramped, W[W_X0 + 3 * i:W_X0 + 3 * i + 3])
    if not run_substeps(Y, P, K.Drive(OP[K.OP_THETA], OP[K.OP_W], x0, rate), OP[K.OP_H], m,
                        X[X_OUTV + i * K.O_LEN:X_OUTV + (i + 1) * K.O_LEN], Wk,
                        needle_work(X, W, i, nn, ns)):
        return 3
    return 1


def step_finish(T, X, OUT, W, ok):
    """A step's end after step_unit of each of step_units(T) (ok: 1.0 when each returned 1):
    the joint's outputs, or the step refused; the step counted.  Returns step's codes."""
    n, resolved, _, _, _, _ = shape_of(T)
    rc = 3
    if ok == 1.0:
        rc = joint_outputs(_at(X, X_OUTV, (n, K.O_LEN)), n, T[T_S], X[X_OP + K.OP_LEN + K.OP_F],
                           X[X_OP + K.OP_LEN + K.OP_THETA], OUT)
    return counted(X, W, n, rc, X[X_OP + op_row(n, resolved, 0) * K.OP_LEN + K.OP_DT])


def counted(X, W, n, rc, dt):
    """A step of dt [s] done with code rc: a refused one's note, the time and the count."""
    if rc == 3:
        refused(X, W, n)
    X[X_TIME] += dt
    X[X_STEPS] += 1.0
    return rc


def step(T, IN, X, OUT, W, t, h):
    """From t to t + h [s] at IN's inputs (driven by angle: omega from the shaft angle), every
    roller started at the first.  Returns 1; 2 for a non-finite output (OUT untouched); 3 for a
    step refused (its note says why); 5 for an omega derived from the shaft angle out of its
    range (written into IN; nothing stepped).  In parts: step_begin, a needle-resolved row's
    step_unit a roller, step_finish (the native layer runs the units at once)."""
    rc = step_begin(T, IN, X, OUT, W, t, h)
    if rc != UNITS_NEXT:
        return rc
    ok = 1.0
    for i in range(step_units(T)):
        if step_unit(T, X, W, i) != 1:
            ok = 0.0
    return step_finish(T, X, OUT, W, ok)


def step_begin(T, IN, X, OUT, W, t, h):
    """step up to its units: UNITS_NEXT when step_units(T) rollers are then to be stepped
    (step_unit) and the step finished (step_finish); otherwise the step taken whole, and its
    code."""
    W[W_NOTES] = 0.0
    n, resolved, nn, ns, ny, ys = shape_of(T)
    if T[T_DRIVE_BY_ANGLE] != 0.0:   # the whirl reaches the master's angle at the step's end
        w = (IN[SHAFT_ANGLE] - X[X_Y + K.Y_X]) / h    # (roller 1's whirl angle)
        IN[OMEGA] = w
        if not (IN_LO[OMEGA] <= w <= IN_HI[OMEGA]):
            return 5
    if X[X_STARTED] == 0.0:
        no_key(T, X)
        start(T, IN, X, W, pressing_load(IN[F_PRESS], IN[TORQUE], T[T_S]))
        X[X_STARTED] = 1.0
    # a step within the rounding of the master's times of the last one is that step
    first = X[X_OP + op_row(n, resolved, 0) * K.OP_LEN + K.OP_DT]
    dt = first if (first > 0 and same_step(h, first, t)) else h
    if resolved:
        for i in range(n):
            set_inputs(X[X_OP + (i + 1) * K.OP_LEN:X_OP + (i + 2) * K.OP_LEN], IN, dt)
        return UNITS_NEXT
    set_inputs(X[X_OP:X_OP + K.OP_LEN], IN, dt)
    if n == 1:
        rc = step_roller(X[X_Y:X_Y + K.Y_LEN], X[X_P:X_P + K.P_LEN], X[X_OP:X_OP + K.OP_LEN],
                         work(X, W, 0, K.Y_LEN, K.Y_LEN), X[X_OUTV:X_OUTV + K.O_LEN], OUT)
        one = _at(X, X_OUTV, (1, K.O_LEN))
        if rc == 1 and not (joint_into(one, 1, X[X_P + K.P_S], X[X_OP + K.OP_F], OUT)
                            and spider_into(one, 1, X[X_OP + K.OP_THETA], X[X_P + K.P_S],
                                            X[X_OP + K.OP_F], X[X_OP:X_OP + K.OP_LEN],
                                            False, OUT)):
            rc = 2
    else:
        Wn = K.Work(_at(W, W_L, (n, K.L_LEN)), _at(W, W_RES, (n, K.R_LEN)),
                    _at(W, W_Y1, (n, K.Y_LEN)), _at(X, X_Y2, (n, K.Y_LEN)),
                    _at(W, W_G, (n, K.NV, 3)), _at(W, W_A, (n, K.NV, K.NV)),
                    _at(W, W_B, (n, K.NV)), _at(X, X_HS, (n, K.H_LEN)),
                    _at(W, W_GW, (n, K.NV + 8, K.NV)))
        rc = step_joint(n, _at(X, X_Y, (n, K.Y_LEN)), _at(X, X_P, (n, K.P_LEN)),
                        _at(X, X_OP, (n + 1, K.OP_LEN)), Wn, _at(X, X_OUTV, (n, K.O_LEN)),
                        OUT)
    return counted(X, W, n, rc, dt)


def end(T, IN, X, OUT, W):
    """The run's end: notes on how roller 1 was stepped and the
    communication steps.  Returns 1."""
    W[W_NOTES] = 0.0
    hs = X[X_HS:X_HS + K.H_LEN]
    note(W, NOTE_SUMMARY, hs[K.H_TAKEN], X[X_TIME], 0.0, 0.0)
    integ = X[X_P + K.P_INTEGRATOR]
    if integ == K.INT_DEFAULT and T[T_BEARING] != K.BEAR_RESOLVED:
        note(W, NOTE_SUMMARY_GA, hs[K.H_FALLBACK], 0.0, 0.0, 0.0)
    elif integ == K.INT_DEFAULT:
        if X[X_P + K.P_NEWTON_PASSES] > 1.0:
            note(W, NOTE_SUMMARY_BDF, hs[K.H_PASSES], hs[K.H_REJECTED], 0.0, 0.0)
    elif integ == K.INT_ADAPTIVE:
        note(W, NOTE_SUMMARY_ADAPT, hs[K.H_REJECTED], 0.0, 0.0, 0.0)
    note(W, NOTE_STEPS, X[X_STEPS], 0.0, 0.0, 0.0)
    return 1


# what the FMU's binary compiles of this module (c_functions), callees first
COMPILED = ("check_scene", "setup", "no_key",
            "probe", "settled_table", "start", "joint_outputs", "init", "set_inputs", "refused",
            "step_units", "step_unit", "counted", "step_finish", "step_begin", "step", "end",
            "speed_limit", "history_bound", "roller_bound",
            "roller_problem", "spider_bounds", "spider_problem", "state_problem")


def compiled_namespace():
    """This module's and roller_setup's COMPILED functions as numba njit copies calling each
    other, with the reduced model's (the traverse table: reduced_model.analytic_kernel's compiled
    namespace) and the kernel's; the modules themselves stay plain Python."""
    import numba as nb

    from reduced_model.cfuncs import compile_over
    from reduced_model.analytic_kernel import compiled_namespace as reduced
    from reduced_model.thrust import spin_inertia
    from . import fmu_arrays, host_state, kernel, roller_setup

    def jit(f):
        return nb.njit(f)

    red = reduced()
    g = {**vars(roller_setup), **vars(fmu_arrays), **vars(host_state), **globals()}
    for name in ("operating_point", "traverse_table", "table_state_at", "hertz_point",
                 "pressing_load", "same_step"):
        g[name] = red[name]
    g["spin_inertia"] = jit(spin_inertia)
    # (the kernel's copies: lumped_offset calls row_sums, compiled beside it there)
    g["groove_offset"], g["lumped_offset"] = kernel._op.groove_offset, kernel._op.lumped_offset
    g["v_st"], g["substep"] = kernel._op.v_st, kernel._op.substep   # (the kernel's copies)
    g["_at"] = fmu_arrays.compiled_at()
    return compile_over(g, ("needle_line_stiffness", "row_constants") + roller_setup.COMPILED
                        + fmu_arrays.COMPILED + COMPILED, jit)


def c_functions():
    """init, step, end and check_state as the native layer's C functions (reduced_model/
    cfuncs.py), for fmu_src/aot.py."""
    from reduced_model.cfuncs import c_functions as wrap
    return wrap(compiled_namespace(), (T_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN))


def native_layout() -> dict:
    """Where each of the contact FMU's variables lives in this module's arrays, the arrays'
    sizes, the order the variables are checked in at initialisation (the table's, as
    scene.validate checks them) and the notes' wording: for the FMU whose binary runs this
    module compiled (fmu_src/native_fmu.py)."""
    from reduced_model.cfuncs import native_layout as layout
    return layout(BY_NAME, PARAM_NAMES, INPUT_NAMES, K.OUTPUT_NAMES,
                  [p.name for p in params_for("contact")],
                  (T_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN), W_NOTES, MAX_NOTES, NOTE_TEXT,
                  STATE_PROBLEMS)
