"""The contact FMU's flat arrays (lifecycle.py's): its variables' places, the sizes and places
of the state X and the work W, the views of them in the shapes the kernel takes, the notes and
their wording.  Every size is a constant or a parameter checked against its range: nothing read
from a state sizes or indexes an array.

- P: the FMU's parameters in PARAM_NAMES' order (roller_setup's table values T);
- IN: its inputs in INPUT_NAMES' order; OUT: its outputs in layout.OUTPUT_NAMES' order;
- X: the state (X_* places): started, time, steps; per roller its parameter vector, operating
  point (a header row first), state Y and previous state Y2, the integrators' history hs, its
  output vector and needle diagnostics ND; sized for three rollers of N_MAX needles;
- W: work, not part of an FMU state: each roller's work arrays (layout.Work) and needle work
  (layout.NeedleWork), a probe's saved rows, the resolved offset's cache, the start's traverse
  table, the notes (the messages a call leaves for the FMU's log: codes and numbers, worded by
  NOTE_TEXT in the binary).
Views are made at run time (_at): a joint of ideal or lumped rollers as rows of one block each
(kernel.step_joint), a needle-resolved roller's state with its needles.
"""

from reduced_model import equations as RE
from reduced_model.cfuncs import NOTE_ARGS, leave_note
from reduced_model.scene import BY_NAME, RELATIONS, TOO_LONG, params_for
from reduced_model.table import D_COUNT
from . import layout as K
from .budget import WHY, adapt_refusal
from .roller_setup import PARAM_NAMES, T_BEARING, T_N_NEEDLES, T_N_ROLLERS, T_N_SPHERES

# --- the FMU's variables --------------------------------------------------------------------
T_LEN = len(PARAM_NAMES)
INPUT_NAMES = tuple(p.name for p in params_for("contact") if p.causality == "input")
THETA, OMEGA, F_PRESS, TORQUE, PLUNGE_SPEED, SHAFT_ANGLE = map(INPUT_NAMES.index, (
    "theta", "omega", "F_press", "torque", "plunge_speed", "shaft_angle"))
IN_LEN = len(INPUT_NAMES)
IN_LO = tuple(BY_NAME[n].lo for n in INPUT_NAMES)
IN_HI = tuple(BY_NAME[n].hi for n in INPUT_NAMES)
OUT_LEN = K.N_OUT
# the analytic model's parameters (its traverse table starts the roller) as the contact FMU's;
# -1: one the contact model lacks, 0 there (needle_row: the start's table is the ideal bearing's)
ANALYTIC_SLOTS = tuple(PARAM_NAMES.index(n) if n in PARAM_NAMES else -1 for n in RE.PARAM_NAMES)

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
W_O = W_PA + RE.T_LEN                       # its operating point,
W_D = W_O + RE.O_LEN                        # its derivation,
W_T = W_D + D_COUNT * TABLE_ROWS            # the table,
W_SS = W_T + 5 * TABLE_ROWS                 # the slide slip and tilt on the settled cycle
W_PS = W_SS + TABLE_ROWS
W_BS = W_PS + TABLE_ROWS                    # (the row's tilt: 0, the ideal bearing's table)
W_TKEY = W_BS + TABLE_ROWS                  # the inputs the table is for, set, settled
W_NW = W_TKEY + 6                           # R_MAX needle works of NW_LEN
W_NOTES = W_NW + R_MAX * NW_LEN
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
    (ERROR, RELATIONS["spider"]),
) + tuple((ERROR, "roller %.0f: " + adapt_refusal(WHY[f])) for f in FAILS)
(NOTE_INFO, NOTE_INFO_OP, NOTE_SUMMARY, NOTE_SUMMARY_GA, NOTE_SUMMARY_BDF, NOTE_SUMMARY_ADAPT,
 NOTE_STEPS, NOTE_TOO_LONG, NOTE_GROOVE, NOTE_CLEARANCE, NOTE_ROLLERS, NOTE_BORE,
 NOTE_SPIDER) = range(13)
NOTE_ADAPT = 13                      # + the index of hs[H_FAIL] in FAILS


def note(W, code, a0, a1, a2, a3):
    """Leave a note (code, four numbers) for the FMU's log; beyond MAX_NOTES it is dropped."""
    leave_note(W, W_NOTES, MAX_NOTES, code, a0, a1, a2, a3)


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


# why a state is refused (state_check.py's bounds: the speeds the driven motion makes, ten
# times over; the slide within half the needle length; the row's offsets within the needle
# diameter, its tilts within half a needle across the row)
STATE_PROBLEMS = ("", "its flags or counts are none the model writes",
                  "a roller's parameters are not this instance's",
                  "a roller's operating point is not the one its inputs give",
                  "a roller's transition velocity, substep, restart weight or counts are out "
                  "of range",
                  "a roller's whirl angle is outside the shaft angle's range",
                  "a roller's slide u is beyond half the needle length: the roller off its "
                  "needles",
                  "a roller's speeds are beyond the scene's (ten times what its inputs drive)",
                  "a roller's radial offset or tilt on its needle row is beyond the row's "
                  "thickness",
                  "the free spider's pose is beyond the groove radius or its speeds beyond the "
                  "scene's (ten times what its inputs drive)")


def compiled_at():
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


# what lifecycle.py compiles of this module, callees first
COMPILED = ("leave_note", "note", "shape_of", "op_row", "work", "needle_work")
