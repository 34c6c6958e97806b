"""The contact FMU's lifecycle as scalar functions over flat arrays, as reduced_model/kernel.py
keeps the analytic FMU's: ``init``, ``step``, ``end`` and ``check_state``, compiled ahead of time
(c_functions, fmu_src/aot.py) into the FMU's binary, which then runs without Python.  They
compose the model's own functions: roller_setup.py (the parameter vector, the needle row, the
start on the settled cycle) and kernel.py (the step: the same functions the pythonfmu slave's
prebuilt kernel runs), so the binary is held to the slave bit for bit
(tests/test_native_fmu.py).

Arrays (float64; flags and counts as 0.0 / 1.0, integers as floats):
- P: the FMU's parameters in PARAM_NAMES' order (roller_setup's table values T);
- IN: its inputs in INPUT_NAMES' order; OUT: its outputs in layout.OUTPUT_NAMES' order;
- X: the state (X_* places): started, time, steps; per roller its parameter vector, operating
  point (a header row first), state Y and previous state Y2, the integrators' history hs, its
  output vector and needle diagnostics ND; sized for three rollers of N_MAX needles;
- W: work, not part of an FMU state: each roller's work arrays (layout.Work) and needle work
  (layout.NeedleWork), a probe's saved rows, the resolved offset's cache, the start's traverse
  table, the notes (the messages a call leaves for the FMU's log: codes and numbers, worded by
  NOTE_TEXT in the binary).
Views of X and W in the shapes the kernel takes are made at run time (``_at``): a joint of ideal
or lumped rollers as rows of one block each (kernel.step_joint), a needle-resolved roller's
state with its needles.  Every size is a constant or a parameter checked against its range:
nothing read from a state sizes or indexes an array.
"""
import math

from reduced_model import equations as RE
from reduced_model.equations import operating_point
from reduced_model.scene import BY_NAME, RELATIONS, TOO_LONG, params_for, pressing_load, same_step
from reduced_model.table import D_COUNT, SETTLED_TOL, traverse_table
from . import layout as K
from .budget import WHY, adapt_refusal
from .contact import trunnion_axial
from .kernel import (_roller, derive_op, inputs_moved, joint_into, outputs_into, resolved_drive,
                     run_substeps, step_joint, step_roller)
from .oppoint import P_DERIVED, OP_DERIVED, substep, v_st
from .roller_setup import (PARAM_NAMES, T_BEARING, T_D_NEEDLE, T_DRIVE_BY_ANGLE, T_L_NEEDLE,
                           T_MU_GROOVE, T_N_NEEDLES, T_N_ROLLERS, T_N_SPHERES, T_R_BORE,
                           T_R_GROOVE, T_R_ROLLER, T_RUNNING_CLEARANCE, T_S, T_AXIAL, T_TRAVERSE,
                           kernel_params, needle_params, place_on_cycle, pressing_offset,
                           start_needles, start_state, uses_table)
from .state_check import SPEED_MARGIN

# --- the FMU's variables --------------------------------------------------------------------
T_LEN = len(PARAM_NAMES)
INPUT_NAMES = tuple(p.name for p in params_for("contact") if p.causality == "input")
THETA, OMEGA, F_PRESS, TORQUE, PLUNGE_SPEED, SHAFT_ANGLE = map(INPUT_NAMES.index, (
    "theta", "omega", "F_press", "torque", "plunge_speed", "shaft_angle"))
IN_LEN = len(INPUT_NAMES)
IN_LO = tuple(BY_NAME[n].lo for n in INPUT_NAMES)
IN_HI = tuple(BY_NAME[n].hi for n in INPUT_NAMES)
VST_HI = BY_NAME["v_st"].hi                  # (a state's transition velocity)
WHIRL_HI = BY_NAME["shaft_angle"].hi + 2.0 * math.pi   # (a state's whirl angle)
OUT_LEN = K.N_OUT
# the analytic model's parameters (its traverse table starts the roller) as the contact FMU's
ANALYTIC_SLOTS = tuple(PARAM_NAMES.index(n) for n in RE.PARAM_NAMES)

# --- sizes: three rollers, the table's most needles and spheres -------------------------------
R_MAX = 3
N_MAX = int(BY_NAME["n_needles"].hi)
S_MAX = int(BY_NAME["n_spheres"].hi)
Y_MAX = K.Y_LEN + K.N_F * N_MAX
TABLE_N = RE.N_PER_CYCLE              # the start's traverse table: its intervals
TABLE_ROWS = TABLE_N + 1
GW_LEN = (K.NV + 8) * K.NV
# a roller's needle work (layout.NeedleWork but ND, which is state): per needle, then fixed
NW_PER_NEEDLE = 6 + 36 + 10 + 10 + 36 + 36 + 42 + 36 + 10 + 42 + 78 + 36 + 36 + 1
NW_FIXED = K.N_LEN + 6 + 36 + 6 + 78 + 10 + 6 + 36 + 78 + 114
NW_LEN = NW_FIXED + N_MAX * (S_MAX * 3 + NW_PER_NEEDLE)

# --- the state X ------------------------------------------------------------------------------
X_STARTED, X_TIME, X_STEPS = 0, 1, 2
X_P = 3                                     # R_MAX rows of K.P_LEN
X_OP = X_P + R_MAX * K.P_LEN                # a header row, then R_MAX rows of K.OP_LEN
X_Y = X_OP + (R_MAX + 1) * K.OP_LEN         # R_MAX states (a row's stride: ystride)
X_Y2 = X_Y + R_MAX * Y_MAX
X_HS = X_Y2 + R_MAX * Y_MAX                 # R_MAX rows of K.H_LEN
X_OUTV = X_HS + R_MAX * K.H_LEN             # R_MAX rows of K.O_LEN
X_ND = X_OUTV + R_MAX * K.O_LEN             # R_MAX blocks of N_MAX x K.D_LEN
X_LEN = X_ND + R_MAX * N_MAX * K.D_LEN

# --- the work W -------------------------------------------------------------------------------
W_L = 0
W_RES = W_L + R_MAX * K.L_LEN
W_Y1 = W_RES + R_MAX * K.R_LEN
W_G = W_Y1 + R_MAX * Y_MAX
W_A = W_G + R_MAX * K.NV * 3
W_B = W_A + R_MAX * K.NV * K.NV
W_GW = W_B + R_MAX * K.NV
W_SAVE = W_GW + R_MAX * GW_LEN              # a probe's P, OP and hs, kept
W_X0 = W_SAVE + K.P_LEN + K.OP_LEN + K.H_LEN   # per roller: the resolved offset's cache (3)
W_PA = W_X0 + 3 * R_MAX                     # the traverse table: the analytic parameters,
W_O = W_PA + RE.P_LEN                       # its operating point,
W_D = W_O + RE.O_LEN                        # its derivation,
W_T = W_D + D_COUNT * TABLE_ROWS            # the table,
W_SS = W_T + 5 * TABLE_ROWS                 # the slide slip and tilt on the settled cycle
W_PS = W_SS + TABLE_ROWS
W_NW = W_PS + TABLE_ROWS                    # R_MAX needle works of NW_LEN
W_NOTES = W_NW + R_MAX * NW_LEN
NOTE_ARGS = 4
MAX_NOTES = 8
W_LEN = W_NOTES + 1 + MAX_NOTES * (1 + NOTE_ARGS)

# --- the notes: a code and up to four numbers each; NOTE_TEXT words them (printf formats, which
# Python's % applies alike).  A note whose text starts with "; " continues the one before.
INFO, WARNING, ERROR = 0, 1, 2
FAILS = (K.FAIL_ESTIMATE, K.FAIL_FLOOR, K.FAIL_TRIES)
NOTE_TEXT = (
    (INFO, "%.0f roller(s), bearing %.0f, traverse %.0f"),
    (INFO, "; pressing %.6g N per roller, v_st %.4g m/s, substep %.3g s, pressing offset "
           "%.6g m; kernel compiled ahead of time (no Python)"),
    (INFO, "roller 1: %.0f steps, %.6g s"),
    (INFO, "; generalized-alpha, %.0f step(s) handed to the extrapolated substeps when Newton "
           "did not converge"),
    (INFO, "; BDF2, a second Newton pass in %.0f substep(s), %.0f pass(es) refused as not "
           "contracting"),
    (INFO, "; %.0f substep(s) rejected by the error estimate"),
    (INFO, "communication steps: %.0f, each compiled (no Python)"),
    (ERROR, "roller %.0f: " + TOO_LONG),
    (ERROR, RELATIONS["groove"]),
    (ERROR, RELATIONS["running_clearance"]),
    (ERROR, RELATIONS["n_rollers"]),
    (ERROR, RELATIONS["bore"]),
) + tuple((ERROR, "roller %.0f: " + adapt_refusal(WHY[f])) for f in FAILS)
(NOTE_INFO, NOTE_INFO_OP, NOTE_SUMMARY, NOTE_SUMMARY_GA, NOTE_SUMMARY_BDF, NOTE_SUMMARY_ADAPT,
 NOTE_STEPS, NOTE_TOO_LONG, NOTE_GROOVE, NOTE_CLEARANCE, NOTE_ROLLERS, NOTE_BORE) = range(12)
NOTE_ADAPT = 12                      # + the index of hs[H_FAIL] in FAILS


def note(W, code, a0, a1, a2, a3):
    """Leave a note (code, four numbers) for the FMU's log; beyond MAX_NOTES it is dropped."""
    n = int(W[W_NOTES])
    if n >= MAX_NOTES:
        return
    at = W_NOTES + 1 + n * (1 + NOTE_ARGS)
    W[at] = code
    W[at + 1] = a0
    W[at + 2] = a1
    W[at + 3] = a2
    W[at + 4] = a3
    W[W_NOTES] = n + 1


# --- views ------------------------------------------------------------------------------------
def _at(A, offset, shape):
    """A's doubles from offset on as an array of this shape (plain Python: a reshaped slice;
    compiled: a view at that address, compiled_namespace)."""
    size = 1
    for d in shape:
        size *= d
    return A[offset:offset + size].reshape(shape)


def shape_of(T):
    """(rollers, whether the needles are resolved, needles, spheres a needle, a roller state's
    length, its stride in X): from the parameters (checked against their ranges)."""
    resolved = T[T_BEARING] == K.BEAR_RESOLVED
    nn = int(T[T_N_NEEDLES]) if resolved else 0
    ny = K.Y_LEN + K.N_F * nn
    return int(T[T_N_ROLLERS]), resolved, nn, int(T[T_N_SPHERES]), ny, \
        (Y_MAX if resolved else K.Y_LEN)


def op_row(n, resolved, i):
    """The row of X's operating points roller i steps at: the header itself for one roller
    without resolved needles (kernel.step_roller), else its own row under the header."""
    return 0 if (n == 1 and not resolved) else i + 1


def work(X, W, i, ny, ys):
    """Roller i's work arrays (layout.Work) over W, with its Y2 in X."""
    return K.Work(W[W_L + i * K.L_LEN:W_L + (i + 1) * K.L_LEN],
                  W[W_RES + i * K.R_LEN:W_RES + (i + 1) * K.R_LEN],
                  W[W_Y1 + i * ys:W_Y1 + i * ys + ny], X[X_Y2 + i * ys:X_Y2 + i * ys + ny],
                  _at(W, W_G + i * K.NV * 3, (K.NV, 3)),
                  _at(W, W_A + i * K.NV * K.NV, (K.NV, K.NV)),
                  W[W_B + i * K.NV:W_B + (i + 1) * K.NV],
                  X[X_HS + i * K.H_LEN:X_HS + (i + 1) * K.H_LEN],
                  _at(W, W_GW + i * GW_LEN, (K.NV + 8, K.NV)))


def needle_work(X, W, i, nn, ns):
    """Roller i's needle work (layout.NeedleWork) over W, its diagnostics ND in X: nn needles of
    ns spheres, laid out one after the other in NeedleWork's order."""
    a = W_NW + i * NW_LEN
    NP = W[a:a + K.N_LEN]
    a += K.N_LEN
    SP = _at(W, a, (nn, ns, 3))
    a += nn * ns * 3
    FN = _at(W, a, (nn, 6))
    a += nn * 6
    AN = _at(W, a, (nn, 6, 6))
    a += nn * 36
    FR = W[a:a + 6]
    a += 6
    AR = _at(W, a, (6, 6))
    a += 36
    MOM = _at(W, a, (nn, 10))
    a += nn * 10
    gn = W[a:a + 6]
    a += 6
    PM = _at(W, a, (nn, 10))
    a += nn * 10
    RS = _at(W, a, (6, 13))
    a += 78
    UN = _at(W, a, (nn, 6, 6))
    a += nn * 36
    MR = W[a:a + 10]
    a += 10
    gn2 = W[a:a + 6]
    a += 6
    CW = _at(W, a, (nn, 6, 6))
    a += nn * 36
    XW = _at(W, a, (nn, 6, 7))
    a += nn * 42
    S = _at(W, a, (6, 6))
    a += 36
    T = _at(W, a, (6, 13))
    a += 78
    BN = _at(W, a, (nn, 6, 6))
    a += nn * 36
    PB = _at(W, a, (nn, 10))
    a += nn * 10
    RH = _at(W, a, (nn, 6, 7))
    a += nn * 42
    XW7 = _at(W, a, (nn, 6, 13))
    a += nn * 78
    T7 = _at(W, a, (6, 19))
    a += 114
    BP = _at(W, a, (nn, 6, 6))
    a += nn * 36
    LF = _at(W, a, (nn, 6, 6))
    a += nn * 36
    ZF = W[a:a + nn]
    ND = _at(X, X_ND + i * N_MAX * K.D_LEN, (nn, K.D_LEN))
    return K.NeedleWork(NP, SP, FN, AN, FR, AR, ND, MOM, gn, PM, RS, UN, MR, gn2, CW, XW, S, T,
                        BN, PB, RH, XW7, T7, BP, LF, ZF)


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
    in ctx (ContactModel.probe): its P, OP and history kept.  ctx: (Y, P, OP, work, its output
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
    dt = 1e-4       # (ContactModel.set_inputs: any step; none is taken)
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
    else:           # the needle-resolved row: its own pressing offset (step_resolved)
        inputs_moved(P, hs, derive_op(P, OP))
        x0, rate = resolved_drive(P, T, OP, math.nan, 0, False, cache)
        run_substeps(Y, P, K.Drive(OP[K.OP_THETA], OP[K.OP_W], x0, rate), OP[K.OP_H], 0, out,
                     Wk, NW)
    for j in range(K.P_LEN):
        P[j] = W[s + j]
    for j in range(K.OP_LEN):
        OP[j] = W[s + K.P_LEN + j]
    for j in range(K.H_LEN):
        hs[j] = W[s + K.P_LEN + K.OP_LEN + j]
    return Wk.L, Wk.res


def settled_table(T, W, theta, omega, F, vp):
    """The traverse model's settled cycle at these inputs into W (W_SS, W_PS), where it places
    the rollers at the start (roller_setup.uses_table; start_slide.traverse_table): whether it
    does."""
    if not uses_table(T, omega, F):
        return False
    PA = W[W_PA:W_PA + RE.P_LEN]
    for j in range(RE.P_LEN):
        PA[j] = T[ANALYTIC_SLOTS[j]]
    O = W[W_O:W_O + RE.O_LEN]
    operating_point(PA, theta, omega, F, 0.0, vp, O)
    cycles, mismatch, g_max = traverse_table(
        O, W[W_D:W_D + D_COUNT * TABLE_ROWS], TABLE_N, W[W_T:W_T + 5 * TABLE_ROWS],
        W[W_SS:W_SS + TABLE_ROWS], W[W_PS:W_PS + TABLE_ROWS])
    return mismatch <= SETTLED_TOL * O[RE.O_VST]


def start(T, IN, X, W, F):
    """Every roller at its start (ContactModel.start) at IN's inputs and the pressing load F
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


def joint_outputs(out, n, s, F, OUT):
    """The FMU's outputs from the rollers' output vectors out (n rows) at the pressing load F
    [N] per roller (model._joint_outputs).  Returns 1, or 2 (a non-finite output)."""
    total = 0.0   # left to right, as model._joint_outputs
    for i in range(n):
        total += out[i, K.O_FZ]
    if not math.isfinite(total) or not outputs_into(out[0], F, OUT):
        return 2
    if not joint_into(out, n, s, F, OUT):
        return 2
    OUT[K.OUT_FZ_JOINT] = total
    OUT[K.OUT_FZ_2] = out[1, K.O_FZ] if n > 1 else 0.0
    OUT[K.OUT_FZ_3] = out[2, K.O_FZ] if n > 2 else 0.0
    return 1


def init(T, IN, X, OUT, W):
    """The start's outputs (JointModel.initial_outputs: every roller started at IN's inputs and
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
    rc = joint_outputs(_at(X, X_OUTV, (n, K.O_LEN)), n, T[T_S], F, OUT)
    setup(T, X, W)
    return rc


# --- the step ---------------------------------------------------------------------------------
def set_inputs(OP, IN, dt):
    """IN's inputs and the step dt [s] where the kernel reads them (ContactModel.set_inputs)."""
    OP[K.OP_THETA] = IN[THETA]
    OP[K.OP_W] = IN[OMEGA]
    OP[K.OP_FP] = IN[F_PRESS]
    OP[K.OP_TQ] = IN[TORQUE]
    OP[K.OP_DT] = dt
    OP[K.OP_VP] = IN[PLUNGE_SPEED]


def refused(X, W, n):
    """A note on the first roller whose step ran out of its budget (JointModel.refusal)."""
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


def step_resolved(T, X, W, n, nn, ns, ny, ys, OUT):
    """Each needle-resolved roller's step at its OP row's inputs (ContactModel._run), then the
    joint's outputs.  Returns kernel.step's codes."""
    ramped = X[X_P + K.P_INTEG] == K.INT_DEFAULT   # (ContactModel.load_ramped)
    for i in range(n):
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
    return joint_outputs(_at(X, X_OUTV, (n, K.O_LEN)), n, T[T_S], X[X_OP + K.OP_LEN + K.OP_F],
                         OUT)


def step(T, IN, X, OUT, W, t, h):
    """From t to t + h [s] at IN's inputs (driven by angle: omega from the shaft angle), every
    roller started at the first.  Returns 1; 2 for a non-finite output (OUT untouched); 3 for a
    step refused (its note says why); 5 for an omega derived from the shaft angle out of its
    range (written into IN; nothing stepped)."""
    W[W_NOTES] = 0.0
    n, resolved, nn, ns, ny, ys = shape_of(T)
    if T[T_DRIVE_BY_ANGLE] != 0.0:   # the whirl reaches the master's angle at the step's end
        w = (IN[SHAFT_ANGLE] - X[X_Y + K.Y_X]) / h    # (slavekit.omega_by_angle; roller 1)
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
        rc = step_resolved(T, X, W, n, nn, ns, ny, ys, OUT)
    else:
        set_inputs(X[X_OP:X_OP + K.OP_LEN], IN, dt)
        if n == 1:
            rc = step_roller(X[X_Y:X_Y + K.Y_LEN], X[X_P:X_P + K.P_LEN], X[X_OP:X_OP + K.OP_LEN],
                             work(X, W, 0, K.Y_LEN, K.Y_LEN), X[X_OUTV:X_OUTV + K.O_LEN], OUT)
            if rc == 1 and not joint_into(_at(X, X_OUTV, (1, K.O_LEN)), 1, X[X_P + K.P_S],
                                          X[X_OP + K.OP_F], OUT):
                rc = 2
        else:
            rc = step_joint(n, _at(X, X_Y, (n, K.Y_LEN)), _at(X, X_P, (n, K.P_LEN)),
                            _at(X, X_OP, (n + 1, K.OP_LEN)), _at(W, W_L, (n, K.L_LEN)),
                            _at(W, W_RES, (n, K.R_LEN)), _at(W, W_Y1, (n, K.Y_LEN)),
                            _at(X, X_Y2, (n, K.Y_LEN)), _at(W, W_G, (n, K.NV, 3)),
                            _at(W, W_A, (n, K.NV, K.NV)), _at(W, W_B, (n, K.NV)),
                            _at(X, X_HS, (n, K.H_LEN)), _at(W, W_GW, (n, K.NV + 8, K.NV)),
                            _at(X, X_OUTV, (n, K.O_LEN)), OUT)
    if rc == 3:
        refused(X, W, n)
    X[X_TIME] += dt
    X[X_STEPS] += 1.0
    return rc


def end(T, IN, X, OUT, W):
    """The run's end: notes on how roller 1 was stepped (JointModel.summary) and the
    communication steps.  Returns 1."""
    W[W_NOTES] = 0.0
    hs = X[X_HS:X_HS + K.H_LEN]
    note(W, NOTE_SUMMARY, hs[K.H_TAKEN], X[X_TIME], 0.0, 0.0)
    integ = X[X_P + K.P_INTEG]
    if integ == K.INT_DEFAULT and T[T_BEARING] != K.BEAR_RESOLVED:
        note(W, NOTE_SUMMARY_GA, hs[K.H_FALLBACK], 0.0, 0.0, 0.0)
    elif integ == K.INT_DEFAULT:
        if X[X_P + K.P_NPASS] > 1.0:
            note(W, NOTE_SUMMARY_BDF, hs[K.H_PASSES], hs[K.H_REJECTED], 0.0, 0.0)
    elif integ == K.INT_ADAPTIVE:
        note(W, NOTE_SUMMARY_ADAPT, hs[K.H_REJECTED], 0.0, 0.0, 0.0)
    note(W, NOTE_STEPS, X[X_STEPS], 0.0, 0.0, 0.0)
    return 1


# --- a state a host sets ----------------------------------------------------------------------
def within(v, bound):
    return abs(v) <= bound


def roller_problem(T, IN, X, W, i, n, resolved, ny, ys):
    """0 when roller i's state can be stepped (state_check.check_roller_state's bounds), else a
    code of STATE_PROBLEMS."""
    P = X[X_P + i * K.P_LEN:X_P + (i + 1) * K.P_LEN]
    OP = X[X_OP + op_row(n, resolved, i) * K.OP_LEN:X_OP + (op_row(n, resolved, i) + 1) * K.OP_LEN]
    hs = X[X_HS + i * K.H_LEN:X_HS + (i + 1) * K.H_LEN]
    # its parameters: what the table's values derive; its operating point: what its inputs do
    S = W[W_SAVE:W_SAVE + K.P_LEN]
    kernel_params(T, S)
    for j in range(K.P_LEN):
        derived = False
        for d in P_DERIVED:
            if j == d:
                derived = True
        if not derived and P[j] != S[j]:
            return 2
    for j in P_DERIVED:
        S[j] = P[j]
    SO = W[W_SAVE + K.P_LEN:W_SAVE + K.P_LEN + K.OP_LEN]
    for j in range(K.OP_LEN):
        SO[j] = OP[j]
    SO[K.OP_KEY + 4] = math.nan      # derived again at its inputs
    derive_op(S, SO)
    for j in OP_DERIVED:
        if SO[j] != OP[j]:
            return 3
    for j in P_DERIVED:
        if j != K.P_DF and S[j] != P[j]:
            return 3
    if not (0.0 <= P[K.P_DF] <= 2.0) or OP[K.OP_NOSTEP] != 0.0:
        return 3
    if not (0.0 < P[K.P_VST] <= VST_HI):
        return 4
    if not (0.0 <= hs[K.H_SUB] <= 1.0) or hs[K.H_TAKEN] < 0.0:
        return 4
    # the speeds the driven motion makes (state_check.speed_bound), at the larger of the
    # inputs and the key
    theta = max(abs(IN[THETA]), abs(OP[K.OP_KEY]))
    omega = max(abs(IN[OMEGA]), abs(OP[K.OP_KEY + 1]))
    vp = max(abs(IN[PLUNGE_SPEED]), abs(OP[K.OP_KEY + 5]))
    kin = (T[T_S] + T[T_R_ROLLER]) * omega * (1.0 + abs(math.tan(min(theta, math.pi / 4)))) + vp
    v = SPEED_MARGIN * max(kin, 1.0)
    tilt = math.atan(T[T_D_NEEDLE] / (0.5 * T[T_L_NEEDLE]))
    for k in range(2):
        Y = X[(X_Y if k == 0 else X_Y2) + i * ys:(X_Y if k == 0 else X_Y2) + i * ys + ny]
        if not within(Y[K.Y_X], WHIRL_HI):
            return 5
        if not (within(Y[K.Y_U], 0.5 * T[T_L_NEEDLE]) and within(Y[K.Y_UD], v)
                and within(Y[K.Y_OM], v / T[T_R_ROLLER])):
            return 5
        if T[T_BEARING] == K.BEAR_IDEAL:
            continue
        if not (within(Y[K.Y_E], T[T_D_NEEDLE]) and within(Y[K.Y_W], T[T_D_NEEDLE])
                and within(Y[K.Y_B1], tilt) and within(Y[K.Y_B2], tilt)
                and within(Y[K.Y_ED], v) and within(Y[K.Y_WD], v)
                and within(Y[K.Y_B1D], v / T[T_R_BORE]) and within(Y[K.Y_B2D], v / T[T_R_BORE])):
            return 5
    return 0


def state_problem(T, IN, X, W):
    """0 when the state X is one the model can step (every value finite is the layer's
    check), else a code of STATE_PROBLEMS: its flags or counts none the model writes (1), a
    roller's parameters not this instance's (2), its operating point not its inputs' (3), its
    transition velocity, substep or counts out of range (4), its motion beyond the scene's
    bounds (5: state_check.py)."""
    if X[X_STARTED] != 0.0 and X[X_STARTED] != 1.0:
        return 1
    if X[X_TIME] < 0.0 or X[X_STEPS] < 0.0:
        return 1
    if X[X_STARTED] == 0.0:   # the first step starts it afresh
        return 0
    n, resolved, nn, ns, ny, ys = shape_of(T)
    for i in range(n):
        code = roller_problem(T, IN, X, W, i, n, resolved, ny, ys)
        if code != 0:
            return code
    return 0


STATE_PROBLEMS = ("", "its flags or counts are none the model writes",
                  "a roller's parameters are not this instance's",
                  "a roller's operating point is not the one its inputs give",
                  "a roller's transition velocity, substep or counts are out of range",
                  "a roller's motion is beyond the scene's bounds (state_check.py)")

# what the FMU's binary compiles of this module (c_functions), callees first
COMPILED = ("note", "shape_of", "op_row", "work", "needle_work", "check_scene", "setup", "no_key",
            "probe", "settled_table", "start", "joint_outputs", "init", "set_inputs", "refused",
            "step_resolved", "step", "end", "within", "roller_problem", "state_problem")


def _compiled_at():
    """_at compiled: a view of an array's doubles from an offset on, at that address (no copy,
    no allocation: what the binary can run)."""
    from numba import carray, njit, types
    from numba.extending import intrinsic

    @intrinsic
    def data_at(typingctx, arr, offset):
        sig = types.CPointer(types.float64)(arr, types.intp)

        def codegen(context, builder, signature, args):
            ary = context.make_array(signature.args[0])(context, builder, args[0])
            return builder.gep(ary.data, [args[1]])
        return sig, codegen

    @njit
    def at(A, offset, shape):
        return carray(data_at(A, offset), shape)
    return at


def compiled_namespace():
    """This module's and roller_setup's COMPILED functions as numba njit copies calling each
    other, with the reduced model's (the traverse table: reduced_model.kernel's compiled
    namespace) and the kernel's; the modules themselves stay plain Python."""
    import types

    import numba as nb

    from reduced_model.kernel import compiled_namespace as reduced
    from reduced_model.thrust import spin_inertia
    from . import hertz, oppoint, roller_setup

    def jit(f):
        return nb.njit(f)

    red = reduced()
    g = {**vars(roller_setup), **globals()}
    for name in ("operating_point", "traverse_table", "table_state_at", "hertz_point",
                 "pressing_load", "same_step"):
        g[name] = red[name]
    for f in (spin_inertia, hertz.needle_line_stiffness, oppoint.groove_offset,
              oppoint.lumped_offset):
        g[f.__name__] = jit(f)
    for name in ("v_st", "substep"):
        g[name] = getattr(oppoint_compiled(), name)
    g["_at"] = _compiled_at()
    for name in roller_setup.COMPILED + COMPILED:
        f = g[name]
        g[name] = jit(types.FunctionType(f.__code__, g, f.__name__, f.__defaults__,
                                         f.__closure__))
    return g


def oppoint_compiled():
    """oppoint's functions as the kernel compiles them (kernel._op)."""
    from . import kernel
    return kernel._op


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
    arrays = {n: ("IN_P", i) for i, n in enumerate(PARAM_NAMES)}
    arrays.update({n: ("IN_IN", i) for i, n in enumerate(INPUT_NAMES)})
    arrays.update({n: ("IN_OUT", i) for i, n in enumerate(K.OUTPUT_NAMES)})
    return {"by_name": BY_NAME, "arrays": arrays,
            "check_order": [p.name for p in params_for("contact")],
            "sizes": {"P": T_LEN, "IN": IN_LEN, "X": X_LEN, "OUT": OUT_LEN, "W": W_LEN, "TH": 2},
            "notes": {"at": W_NOTES, "args": NOTE_ARGS, "max": MAX_NOTES, "text": NOTE_TEXT,
                      "state_problems": STATE_PROBLEMS}}
