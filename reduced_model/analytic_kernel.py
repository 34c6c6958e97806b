"""The analytic FMU's lifecycle as scalar functions over flat arrays: one source for the analytic
FMU's model as Python (analytic_model, harness/inprocess.py) and its binary, which compiles
``init``, ``step``, ``end`` and ``check_state`` with the equations they call (equations.py,
table.py) ahead of time (c_functions, fmu_src/aot.py) and runs them without Python.

Arrays (float64; flags and counts as 0.0 / 1.0, integers as floats; Python lists or numpy
arrays on the Python path):
- T: the analytic FMU's parameters in PARAM_NAMES' order (the table's, inputs left out);
- IN: its inputs in INPUT_NAMES' order; OUT: its outputs in OUTPUT_NAMES' order;
- X: the model's state (X_* slots): whirl angles, the step, the operating point's inputs (key)
  and constants (O_* slots, from X_OP on), the mode (Eqs. 18-27, the settled table, or the
  slide stepped in time), the march's rows, the table, the span of the inputs, counters;
- W: work (the table's derivation) and the notes (NOTES: the messages a call leaves for the
  FMU's log, as codes and numbers; the wording is NOTE_TEXT's, here and in the binary alike);
- TH: (t, h) [s].
Equations: traverse.py's header (T1-T6) and thrust.py (Eqs. 18-27); docs/model.md.  Every size
is a constant: nothing read from a state sizes or indexes an array.
"""
import math

from . import equations, needle_row, table
from .equations import (DRIVE_BY_ANGLE, M_ROLLER, MU_GROOVE, N_PER_CYCLE, N_ROLLERS, O_CLEAR,
                        L_NEEDLE, MU_NEEDLE, N_NEEDLES, NEEDLE_CLEARANCE, NEEDLE_ROW, O_MQ,
                        O_RA, O_RAF, O_RC1, O_RKR, O_RL, O_RN, O_ROW,
                        O_F, O_K, O_LEN, O_LOAD, O_MIRROR, O_MU, O_TH, O_VP, O_VST, O_W,
                        T_LEN, PARAM_NAMES, R_BORE, R_FX, R_FY, R_FZ, R_FZ_MOD, R_GROOVE,
                        R_B1D, R_B2, R_B2D, R_HAS_OUT, R_HAS_S, R_LEN, R_P, R_ROLLER, R_S, R_SD,
                        R_SLIP, R_T, S, TRAVERSE,
                        march, operating_point, substeps, thrust_at)
from .cfuncs import NOTE_ARGS, compile_over, finite_into, leave_note, worded_notes
from .friction import spin_moment, tanh_clipped
from .hertz import groove_curvature_radii, hertz_point
from .housing import housing_forces
from .needle_row import row_constants, sum_row
from .scene import (BY_NAME, CONTACT_ONLY_OUTPUTS, MAX_SUBSTEPS, OUTPUTS, RELATIONS, ROW_MU,
                    TOO_LONG,
                    params_for,
                    pressing_load, same_step, same_value)   # (pressing_load: compiled_namespace)
from .table import D_COUNT, SETTLED_TOL, regime, table_at, table_state_at, traverse_table
from .thrust import fz_mod

# --- the FMU's inputs and outputs -----------------------------------------------------------
INPUT_NAMES = tuple(p.name for p in params_for("analytic") if p.causality == "input")
OUTPUT_NAMES = tuple(n for n, _, _ in OUTPUTS if n not in CONTACT_ONLY_OUTPUTS) + ("regime",)
THETA, OMEGA, F_PRESS, TORQUE, PLUNGE_SPEED, SHAFT_ANGLE = map(INPUT_NAMES.index, (
    "theta", "omega", "F_press", "torque", "plunge_speed", "shaft_angle"))
IN_LEN = len(INPUT_NAMES)
N_KEY = 5                    # the inputs an operating point is derived at: IN[:N_KEY]
(FX, FY, FZ, FZ_MOD, DFX, SLIP_SPEED, FZ_JOINT, FZ_2, FZ_3, WHIRL_ANGLE, FX_2, FY_2, FX_3, FY_3,
 F_HOUSING_X, F_HOUSING_Y, T_HOUSING, F_ROLLER, PLUNGE, REGIME) = map(OUTPUT_NAMES.index, (
    "Fx", "Fy", "Fz", "Fz_mod", "dFx", "slip_speed", "Fz_joint", "Fz_2", "Fz_3", "whirl_angle",
    "Fx_2", "Fy_2", "Fx_3", "Fy_3", "F_housing_x", "F_housing_y", "T_housing", "F_roller",
    "plunge", "regime"))
OUT_LEN = len(OUTPUT_NAMES)
# the inputs' ranges as compiled constants (a derived omega and a state's inputs are checked)
IN_LO = tuple(BY_NAME[n].lo for n in INPUT_NAMES)
IN_HI = tuple(BY_NAME[n].hi for n in INPUT_NAMES)


# --- the state X ------------------------------------------------------------------------------
MODE_THRUST, MODE_TABLE, MODE_MARCH = 0, 1, 2
TABLE_ROWS = N_PER_CYCLE + 1
X_WHIRL = 0                        # 3 whirl angles [rad]
X_DT, X_HAS_DT = 3, 4              # the communication step taken [s] (same_step)
X_KEY, X_HAS_KEY = 5, 10           # the inputs the operating point was derived at
X_MODE, X_REGIME, X_TOLD, X_PLUNGE, X_STEPS, X_TABLES = 11, 12, 13, 14, 15, 16
X_SETTLED, X_CYCLES, X_MISMATCH, X_GMAX = 17, 18, 19, 20    # the table's derivation
X_SPAN = 21                        # theta, |omega|, |load| lowest (3) and highest (3)
X_HAS_SPAN = 27
X_OP = 28                          # O_LEN constants
X_MARCH = X_OP + O_LEN             # 3 rows of R_LEN
X_TABLE = X_MARCH + 3 * R_LEN      # TABLE_ROWS rows of (Fz, Fz_mod, Fx, Fy, slip speed)
X_TABLE_SS = X_TABLE + 5 * TABLE_ROWS   # the settled cycle's slide slip s [m/s] and p [1] at
X_TABLE_PS = X_TABLE_SS + TABLE_ROWS    # the table's points (where a march starts), and the
X_TABLE_BS = X_TABLE_PS + TABLE_ROWS    # roller's tilt b2 [rad] on the needle row there
X_LEN = X_TABLE_BS + TABLE_ROWS

# --- the work W: the table's derivation, then the notes ---------------------------------------
W_NOTES = D_COUNT * TABLE_ROWS
MAX_NOTES = 16
W_LEN = W_NOTES + 1 + MAX_NOTES * (1 + NOTE_ARGS)

# --- where the traverse model was checked against the contact model (docs/validation.md: the
# scenes of the paper's joint and the grid of joints of every size, harness/validation.py),
# in the dimensionless groups that govern its error: (quantity, unit, lowest, highest).  Its
# error grows with the roller's inertia against the load (the quasi-static balance misses it:
# -19 % at 32 Hz and 470 N), so the range bounds that ratio, where the grids stayed within 5 %.
# The whirl and the load enter through it and through the Hertz approach over the clearance;
# a joint's size through the proportions (a joint scaled as a whole keeps them).
INERTIA = "roller inertia m r (2 omega)^2 / load"
INERTIA_LIMIT = 0.1
CHECKED_RANGES = (("theta", "deg", 2.0, 25.0), ("mu_groove", "", 0.03, 0.12),
                  (INERTIA, "", 0.0, INERTIA_LIMIT),
                  ("clearance / r_roller", "", 0.0026, 0.042),
                  ("r_roller / s", "", 0.8, 0.9),
                  ("r_bore / r_roller", "", 0.6, 0.78),
                  ("Hertz approach / clearance", "", 0.004, 0.5),
                  ("plunge speed", "m/s", -0.1, 0.1))
(C_THETA, C_MU, C_INERTIA, C_CLEARANCE, C_ROLLER, C_BORE, C_HERTZ,
 C_PLUNGE) = range(len(CHECKED_RANGES))
# held at their defaults in that check (yaw and axial are not here: the ideal bearing's traverse
# model does not use them; the needle row does, and the envelope grid that checks it ran them at
# their defaults, which this list does not yet say)
CHECKED_AT_DEFAULT = ("v_st", "pitch", "roll", "spin_inertia", "spin_moment", "E", "nu")
DEFAULT_SLOTS = tuple(PARAM_NAMES.index(n) for n in CHECKED_AT_DEFAULT)
DEFAULT_VALUES = tuple(float(BY_NAME[n].default) for n in CHECKED_AT_DEFAULT)

# --- the notes: a code and up to four numbers each; NOTE_TEXT words them (printf formats, which
# Python's % applies alike).  A note whose text starts with "; " continues the one before.
INFO, WARNING, ERROR = 0, 1, 2
_RANGE_HEAD = "the traverse model was checked against the contact model in (docs/validation.md): "


def _unit(u):
    return f" {u}" if u else ""


def phrase(k, span):
    """The printf format of CHECKED_RANGES[k]'s phrase: one value (%.4g), or a span of two."""
    name, unit, lo, hi = CHECKED_RANGES[k]
    values = "%.4g-%.4g" if span else "%.4g"
    return f"{name} {values}{_unit(unit)} (checked {lo:g}-{hi:g}{_unit(unit)})"


def default_phrase(j):
    """The printf format of CHECKED_AT_DEFAULT[j]'s phrase (its value: %g)."""
    p = BY_NAME[CHECKED_AT_DEFAULT[j]]
    u = _unit(p.unit if p.unit not in ("1", "") else "")
    return f"{p.name} = %g{u} (checked at {p.default:g}{u} only)"


NOTE_TEXT = (
    (WARNING, "the scene is outside the range " + _RANGE_HEAD),
    (WARNING, "the traverse table at theta = %.6g rad, omega = %.6g rad/s is not periodic: "
              "s(2 pi) - s(0) = %.2e m/s after %.0f cycles of the cycle map; its outputs are the "
              "best cycle run"),
    (INFO, "the inputs moved: from here on the traverse model steps the roller's slide in time "
           "at each step's inputs (no new settled table; regime stays that of the start)"),
    (WARNING, "during the run the inputs left the range " + _RANGE_HEAD),
    (INFO, "communication steps: %.0f; traverse tables derived: %.0f"),
    (INFO, "; the slide stepped in time since the inputs moved"),
    (ERROR, TOO_LONG),
    (ERROR, RELATIONS["groove"]),
    (ERROR, RELATIONS["bore"]),
    (ERROR, RELATIONS["n_rollers"]),
    (ERROR, "mu_groove = %g: the traverse model needs mu_groove < 1 (the friction it balances "
            "tilts the contact normal by asin(mu_groove)); allowed range [0, 1) (or traverse = "
            "false)"),
    (ERROR, RELATIONS["row_mu"]),
) + tuple((WARNING, "; " + phrase(k, False)) for k in range(len(CHECKED_RANGES))) \
  + tuple((WARNING, "; " + phrase(k, True)) for k in range(len(CHECKED_RANGES))) \
  + tuple((WARNING, "; " + default_phrase(j)) for j in range(len(CHECKED_AT_DEFAULT)))
(NOTE_OUTSIDE, NOTE_UNSETTLED, NOTE_MARCH, NOTE_RUN_OUTSIDE, NOTE_STEPS, NOTE_STEPS_MARCH,
 NOTE_TOO_LONG, NOTE_GROOVE, NOTE_BORE, NOTE_ROLLERS, NOTE_MU, NOTE_ROW_MU) = range(12)
NOTE_CHECKED = 12                                       # + k: CHECKED_RANGES[k], one value
NOTE_CHECKED_SPAN = NOTE_CHECKED + len(CHECKED_RANGES)  # + k: a span
NOTE_DEFAULT = NOTE_CHECKED_SPAN + len(CHECKED_RANGES)  # + j: CHECKED_AT_DEFAULT[j]


def notes(W):
    """[(code, level, text)] of the notes W holds, each worded alone."""
    out = []
    for n in range(int(W[W_NOTES])):
        at = W_NOTES + 1 + n * (1 + NOTE_ARGS)
        code = int(W[at])
        level, fmt = NOTE_TEXT[code]
        args = tuple(float(W[at + 1 + i]) for i in range(fmt.count("%")))
        out.append((code, level, fmt % args))
    return out


def notes_text(W):
    """[(level, message)] of the notes W holds, a note starting with "; " joined to the one
    before (as the FMU's binary words them: cfuncs.worded_notes)."""
    return worded_notes(W, W_NOTES, NOTE_TEXT)


def note(W, code, a0, a1, a2, a3):
    """Leave a note (code, four numbers) for the FMU's log; beyond MAX_NOTES it is dropped."""
    leave_note(W, W_NOTES, MAX_NOTES, code, a0, a1, a2, a3)


# --- the checked range ------------------------------------------------------------------------
def inertia_ratio(m, r, omega, load):
    """The roller's inertia force over the pressing load, m r (2 omega)^2 / |load| (the traverse
    slide runs at twice the whirl): m [kg], r [m], omega [rad/s], load [N]; inf without load."""
    F = abs(load)
    a = m * r * ((2.0 * omega) * (2.0 * omega))
    return a / F if F > 0 else (math.inf if a > 0 else 0.0)


def hertz_ratio(O, F):
    """The Hertz approach (F / K)^(2/3) under the load F [N] over the groove clearance [1]."""
    return (F / O[O_K]) ** (2.0 / 3.0) / O[O_CLEAR] if F > 0 else 0.0


def checked_value(T, O, k):
    """CHECKED_RANGES[k]'s quantity for the scene the reduced model runs at O, in its unit."""
    if k == C_THETA:
        return O[O_TH] * (180.0 / math.pi)
    if k == C_MU:
        return T[MU_GROOVE]
    if k == C_INERTIA:
        return inertia_ratio(T[M_ROLLER], T[R_ROLLER], O[O_W], O[O_F])
    if k == C_CLEARANCE:
        return (T[R_GROOVE] - T[R_ROLLER]) / T[R_ROLLER]
    if k == C_ROLLER:
        return T[R_ROLLER] / T[S]
    if k == C_BORE:
        return T[R_BORE] / T[R_ROLLER]
    if k == C_HERTZ:
        return hertz_ratio(O, O[O_F])
    return O[O_VP]


def inside(k, v0, v1):
    """Whether the values v0..v1 of CHECKED_RANGES[k]'s quantity lie in its checked range."""
    lo, hi = CHECKED_RANGES[k][2], CHECKED_RANGES[k][3]
    return lo - 1e-9 * abs(lo) <= v0 and v1 <= hi + 1e-9 * abs(hi)


def note_outside(T, O, W):
    """Notes naming what of the scene at O lies outside the checked range (none inside it)."""
    head = False
    for k in range(len(CHECKED_RANGES)):
        v = checked_value(T, O, k)
        if not inside(k, v, v):
            if not head:
                note(W, NOTE_OUTSIDE, 0.0, 0.0, 0.0, 0.0)
                head = True
            note(W, NOTE_CHECKED + k, v, 0.0, 0.0, 0.0)
    for j in range(len(DEFAULT_SLOTS)):
        v = T[DEFAULT_SLOTS[j]]
        if v != DEFAULT_VALUES[j]:
            if not head:
                note(W, NOTE_OUTSIDE, 0.0, 0.0, 0.0, 0.0)
                head = True
            note(W, NOTE_DEFAULT + j, v, 0.0, 0.0, 0.0)


def note_run_outside(T, X, W):
    """Notes naming where the run's inputs (their span) left the checked range."""
    O = X[X_OP:X_OP + O_LEN]
    t0, w0, f0 = X[X_SPAN], X[X_SPAN + 1], X[X_SPAN + 2]
    t1, w1, f1 = X[X_SPAN + 3], X[X_SPAN + 4], X[X_SPAN + 5]
    # the roller's inertia at its worst: the highest whirl on the lowest load
    worst = inertia_ratio(T[M_ROLLER], T[R_ROLLER], w1, f0)
    d = 180.0 / math.pi
    spans = ((C_THETA, t0 * d, t1 * d), (C_INERTIA, worst, worst),
             (C_HERTZ, hertz_ratio(O, f0), hertz_ratio(O, f1)))
    head = False
    for k, v0, v1 in spans:
        if not inside(k, v0, v1):
            if not head:
                note(W, NOTE_RUN_OUTSIDE, 0.0, 0.0, 0.0, 0.0)
                head = True
            if v0 == v1:
                note(W, NOTE_CHECKED + k, v0, 0.0, 0.0, 0.0)
            else:
                note(W, NOTE_CHECKED_SPAN + k, v0, v1, 0.0, 0.0)


# --- the analytic FMU's lifecycle -------------------------------------------------------------
def mirrored(X, x):
    """The reduced model's whirl angle for a roller's angle x [rad] (coast: turned)."""
    return -x if X[X_OP + O_MIRROR] != 0.0 else x


def take_inputs(T, IN, X):
    """IN's operating-point inputs as the key, the operating point at them, the span widened."""
    for q in range(N_KEY):
        X[X_KEY + q] = IN[q]
    X[X_HAS_KEY] = 1.0
    operating_point(T, IN[THETA], IN[OMEGA], IN[F_PRESS], IN[TORQUE], IN[PLUNGE_SPEED],
                    X[X_OP:X_OP + O_LEN])
    now = (IN[THETA], abs(IN[OMEGA]), abs(X[X_OP + O_LOAD]))
    first = X[X_HAS_SPAN] == 0.0
    X[X_HAS_SPAN] = 1.0
    for q in range(3):
        if first:
            X[X_SPAN + q] = now[q]
            X[X_SPAN + 3 + q] = now[q]
        else:
            X[X_SPAN + q] = min(X[X_SPAN + q], now[q])
            X[X_SPAN + 3 + q] = max(X[X_SPAN + 3 + q], now[q])


def prepare(T, IN, X, W):
    """The operating point at IN's inputs, unless they moved only by rounding from its key (a
    master interpolating a constant stretch of an input table).  At the start the settled table
    (where the traverse model applies), reverse whirl from rest the march; once the inputs
    moved the slide is stepped in time from where the table had it (AnalyticModel's modes)."""
    start = X[X_HAS_KEY] == 0.0
    if not start:
        moved = False
        for q in range(N_KEY):
            if not same_value(IN[q], X[X_KEY + q]):
                moved = True
        if not moved:
            return
    O = X[X_OP:X_OP + O_LEN]
    take_inputs(T, IN, X)
    loaded = O[O_MU] > 0 and O[O_F] > 0
    if T[TRAVERSE] == 0.0:
        X[X_MODE] = MODE_THRUST
        X[X_REGIME] = 0.0
    elif start and O[O_W] < 0 and loaded:
        # reverse whirl (or coast at forward whirl) from the start: no periodic table in that
        # sense; the slide is stepped in time from rest
        X[X_MODE] = MODE_MARCH
        X[X_REGIME] = 0.0
        for i in range(3):
            r = X_MARCH + R_LEN * i
            X[r + R_HAS_S] = 0.0
            X[r + R_P] = 0.0
            X[r + R_HAS_OUT] = 0.0
    elif start:
        X[X_MODE] = MODE_THRUST
        X[X_REGIME] = 0.0
        if O[O_W] > 0 and loaded:
            TAB = X[X_TABLE:X_TABLE + 5 * TABLE_ROWS]
            cycles, mismatch, g_max = traverse_table(
                O, W[:W_NOTES], N_PER_CYCLE, TAB, X[X_TABLE_SS:X_TABLE_SS + TABLE_ROWS],
                X[X_TABLE_PS:X_TABLE_PS + TABLE_ROWS], X[X_TABLE_BS:X_TABLE_BS + TABLE_ROWS])
            X[X_CYCLES] = cycles
            X[X_MISMATCH] = mismatch
            X[X_SETTLED] = 1.0 if mismatch <= SETTLED_TOL * O[O_VST] else 0.0
            X[X_GMAX] = g_max
            X[X_MODE] = MODE_TABLE
            X[X_REGIME] = regime(g_max, TAB, N_PER_CYCLE, O)
            X[X_TABLES] += 1.0
            note_outside(T, O, W)
            if X[X_SETTLED] == 0.0:
                note(W, NOTE_UNSETTLED, O[O_TH], O[O_W], X[X_MISMATCH], X[X_CYCLES])
    else:
        # the inputs moved: the slide is stepped in time from where the table had it
        if X[X_MODE] != MODE_MARCH:
            for i in range(3):
                r = X_MARCH + R_LEN * i
                X[r + R_HAS_OUT] = 0.0
                if X[X_MODE] == MODE_TABLE:
                    # (the table's whirl angle: the roller's, as the operating point it was
                    # derived at had it)
                    s, p = table_state_at(X[X_TABLE_SS:X_TABLE_SS + TABLE_ROWS],
                                          X[X_TABLE_PS:X_TABLE_PS + TABLE_ROWS], N_PER_CYCLE,
                                          mirrored(X, X[X_WHIRL + i]))
                    X[r + R_S] = s
                    X[r + R_P] = p
                    X[r + R_B2] = table_state_at(X[X_TABLE_BS:X_TABLE_BS + TABLE_ROWS],
                                                 X[X_TABLE_BS:X_TABLE_BS + TABLE_ROWS],
                                                 N_PER_CYCLE, mirrored(X, X[X_WHIRL + i]))[0]
                    X[r + R_B2D] = 0.0
                    X[r + R_T] = 0.0
                    X[r + R_B1D] = 0.0
                    X[r + R_SD] = 0.0
                    X[r + R_HAS_S] = 1.0
                else:
                    X[r + R_HAS_S] = 0.0
                    X[r + R_P] = 0.0
            if X[X_TOLD] == 0.0:   # (once: a rollback may start it again)
                note(W, NOTE_MARCH, 0.0, 0.0, 0.0, 0.0)
                X[X_TOLD] = 1.0
        X[X_MODE] = MODE_MARCH


def roller_row(T, X, i, x):
    """Roller i's (Fz, Fz_mod, Fx, Fy [N], slip speed [m/s]) at its whirl angle x [rad] now, as
    the joint's (coast: turned back): the march's, the table's, or Eqs. (18)-(27) (where Fx is
    the pressing load)."""
    O = X[X_OP:X_OP + O_LEN]
    sign = -1.0 if O[O_MIRROR] != 0.0 else 1.0
    r = X_MARCH + R_LEN * i
    if X[X_MODE] == MODE_MARCH and X[X_MARCH + R_HAS_OUT] != 0.0:
        Fz, Fzm, Fx, Fy, slip = X[r + R_FZ], X[r + R_FZ_MOD], X[r + R_FX], X[r + R_FY], \
            X[r + R_SLIP]
    elif X[X_MODE] == MODE_TABLE:
        TAB = X[X_TABLE:X_TABLE + 5 * TABLE_ROWS]
        y = mirrored(X, x)
        Fz, Fzm, Fx, Fy, slip = (table_at(TAB, N_PER_CYCLE, y, 0),
                                 table_at(TAB, N_PER_CYCLE, y, 1),
                                 table_at(TAB, N_PER_CYCLE, y, 2),
                                 table_at(TAB, N_PER_CYCLE, y, 3),
                                 table_at(TAB, N_PER_CYCLE, y, 4))
    else:
        Fz, ft, V, phi = thrust_at(O, mirrored(X, x))
        return sign * Fz, sign * Fz, O[O_LOAD], ft * math.cos(phi), abs(V)
    if sign < 0:
        return -Fz, -Fzm, -Fx, Fy, slip
    return Fz, Fzm, Fx, Fy, slip


def outputs(T, X, OUT):
    """Every output at the state X into OUT when each is finite.  Returns 1, or 2 (OUT
    untouched)."""
    n = int(T[N_ROLLERS])
    F = X[X_OP + O_LOAD]
    Fz1, Fzm1, Fx1, Fy1, slip1 = roller_row(T, X, 0, X[X_WHIRL])
    total = 0.0 + Fz1
    fz2 = fx2 = fy2 = fz3 = fx3 = fy3 = 0.0      # (scalars: nothing allocated when compiled)
    if n > 1:
        fz2, _, fx2, fy2, _ = roller_row(T, X, 1, X[X_WHIRL + 1])
        total += fz2
        fz3, _, fx3, fy3, _ = roller_row(T, X, 2, X[X_WHIRL + 2])
        total += fz3
    sp = T[S]
    hx, hy, ht = housing_forces(Fx1, Fy1, sp, fx2, fy2, sp, fx3, fy3, sp)
    return finite_into((Fx1, Fy1, Fz1, Fzm1, Fx1 - F, slip1, total, fz2, fz3, X[X_WHIRL], fx2,
                        fy2, fx3, fy3, hx, hy, ht, F, X[X_PLUNGE], X[X_REGIME]), OUT)


def check_scene(T, W):
    """The relations between parameters the table's ranges cannot state (scene.validate): a note
    naming them and False where one fails."""
    if T[R_GROOVE] <= T[R_ROLLER]:
        note(W, NOTE_GROOVE, T[R_GROOVE], T[R_ROLLER], 0.0, 0.0)
        return False
    if T[N_ROLLERS] != 1.0 and T[N_ROLLERS] != 3.0:
        note(W, NOTE_ROLLERS, T[N_ROLLERS], 0.0, 0.0, 0.0)
        return False
    if T[TRAVERSE] != 0.0 and T[MU_GROOVE] >= 1.0:
        note(W, NOTE_MU, T[MU_GROOVE], 0.0, 0.0, 0.0)
        return False
    if T[TRAVERSE] != 0.0 and T[NEEDLE_ROW] != 0.0 and T[MU_GROOVE] + ROW_MU * T[MU_NEEDLE] >= 1.0:
        note(W, NOTE_ROW_MU, T[MU_GROOVE] + ROW_MU * T[MU_NEEDLE], 0.0, 0.0, 0.0)
        return False
    if T[R_BORE] >= T[R_ROLLER]:
        note(W, NOTE_BORE, T[R_BORE], T[R_ROLLER], 0.0, 0.0)
        return False
    return True


def init(T, IN, X, OUT, W):
    """The start: the rollers at whirl angles 0, 120, 240 deg, the operating point at IN (the
    settled table where the traverse model applies), the outputs at the start.  Returns 1; 2 for
    a non-finite output; 3 for a scene refused (its note says why)."""
    W[W_NOTES] = 0.0
    if not check_scene(T, W):
        return 3
    for j in range(X_LEN):
        X[j] = 0.0
    for i in range(3):
        X[X_WHIRL + i] = 2.0 * math.pi * i / 3.0 if i < int(T[N_ROLLERS]) else 0.0
    prepare(T, IN, X, W)
    return outputs(T, X, OUT)


def step(T, IN, X, OUT, W, t, h):
    """From t to t + h [s] at IN's inputs (driven by angle: omega from the shaft angle).
    Returns 1; 2 for a non-finite output (OUT untouched); 3 for a step refused before it starts
    (its note says why); 5 for an omega derived from the shaft angle out of its range (written
    into IN; nothing stepped)."""
    W[W_NOTES] = 0.0
    if T[DRIVE_BY_ANGLE] != 0.0:   # the whirl reaches the master's angle at the step's end
        w = (IN[SHAFT_ANGLE] - X[X_WHIRL]) / h
        IN[OMEGA] = w
        if not (IN_LO[OMEGA] <= w <= IN_HI[OMEGA]):
            return 5
    prepare(T, IN, X, W)
    # a step that differs from the last one by the rounding of the master's times is that step
    dt = h if (X[X_HAS_DT] == 0.0 or not same_step(h, X[X_DT], t)) else X[X_DT]
    O = X[X_OP:X_OP + O_LEN]
    n = int(T[N_ROLLERS])
    if X[X_MODE] == MODE_MARCH and substeps(O, dt) > MAX_SUBSTEPS:
        # refused before it starts (a host's huge step): the slide and the step as they were
        note(W, NOTE_TOO_LONG, dt, 2.0 * math.pi / (abs(O[O_W]) * N_PER_CYCLE), 0.0, 0.0)
        return 3
    X[X_DT] = dt
    X[X_HAS_DT] = 1.0
    if X[X_MODE] == MODE_MARCH:
        for i in range(n):
            x = march(O, X, X_MARCH + R_LEN * i, mirrored(X, X[X_WHIRL + i]), dt)
            X[X_WHIRL + i] = mirrored(X, x)
    else:
        w = X[X_KEY + OMEGA] * dt
        for i in range(n):
            X[X_WHIRL + i] += w
    X[X_PLUNGE] = X[X_PLUNGE] + X[X_KEY + PLUNGE_SPEED] * dt   # the held speed
    X[X_STEPS] += 1.0
    return outputs(T, X, OUT)


def end(T, IN, X, OUT, W):
    """The run's end: notes on where its inputs left the checked range (once the slide was
    stepped in time) and on how the steps ran.  Returns 1."""
    W[W_NOTES] = 0.0
    if X[X_MODE] == MODE_MARCH and T[TRAVERSE] != 0.0:
        note_run_outside(T, X, W)
    note(W, NOTE_STEPS, X[X_STEPS], X[X_TABLES], 0.0, 0.0)
    if X[X_MODE] == MODE_MARCH:
        note(W, NOTE_STEPS_MARCH, 0.0, 0.0, 0.0, 0.0)
    return 1


def state_problem(T, X):
    """0 when the state X is one the model can step (every value finite is the layer's
    check), else a code: 1 its mode, flags or counts are none the model writes; 2 an input of
    its operating point outside its range; 3 a march row's p outside [-mu_groove, mu_groove];
    4 its step not above 0.  (p's range: mu_groove, and with the needle row mu_needle q / F
    beside it.)"""
    for j in (X_HAS_DT, X_HAS_KEY, X_TOLD, X_SETTLED, X_HAS_SPAN):
        if X[j] != 0.0 and X[j] != 1.0:
            return 1
    if X[X_MODE] != MODE_THRUST and X[X_MODE] != MODE_TABLE and X[X_MODE] != MODE_MARCH:
        return 1
    if X[X_REGIME] != 0.0 and X[X_REGIME] != 1.0 and X[X_REGIME] != 2.0:
        return 1
    if X[X_STEPS] < 0.0 or X[X_TABLES] < 0.0 or X[X_HAS_KEY] == 0.0:
        return 1
    for q in range(N_KEY):
        if not (IN_LO[q] <= X[X_KEY + q] <= IN_HI[q]):
            return 2
    for i in range(3):
        r = X_MARCH + R_LEN * i
        if X[r + R_HAS_S] != 0.0 and X[r + R_HAS_S] != 1.0:
            return 1
        if X[r + R_HAS_OUT] != 0.0 and X[r + R_HAS_OUT] != 1.0:
            return 1
        # p = fa - row / f_n with |fa| <= mu_groove, |row| <= mu_needle q and f_n >= F
        # (T5 at p = 0): the needle row widens the range by mu_needle q / F
        F = X[X_OP + O_F]
        row = X[X_OP + O_MQ] / F if (X[X_OP + O_ROW] != 0.0 and F > 0.0) else 0.0
        if not abs(X[r + R_P]) <= T[MU_GROOVE] + row:
            return 3
    if X[X_HAS_DT] != 0.0 and not X[X_DT] > 0.0:
        return 4
    # the needle row's constants and offset kept in the operating point (row_point) are used
    # as they are where they name these needles: then they must be theirs, the offset the one
    # at its load (a state's offset far above it would cost Newton its iterations)
    O = X[X_OP:X_OP + O_LEN]
    if O[O_RN] == T[N_NEEDLES] and O[O_RL] == T[L_NEEDLE]:
        c1, k_row, _q = row_constants(int(T[N_NEEDLES]), T[L_NEEDLE])
        if O[O_RC1] != c1 or O[O_RKR] != k_row:
            return 5
        if O[O_RAF] != 0.0 or O[O_RA] != 0.0:
            f = sum_row(T[NEEDLE_CLEARANCE], int(T[N_NEEDLES]), c1, O[O_RA])[0]
            if not (O[O_RAF] > 0.0 and abs(f - O[O_RAF]) <= 1e-9 * O[O_RAF]):
                return 5
    return 0


STATE_PROBLEMS = ("", "its mode, flags or counts are none the model writes",
                  "an input of its operating point is outside its range",
                  "a march row's p is outside [-mu_groove, mu_groove] (the needle row: widened "
                  "by mu_needle q / F)",
                  "its step is not above 0",
                  "its needle row's kept constants or offset are not those of its parameters "
                  "and load")

# the functions the FMU's binary compiles (c_functions) besides equations.py's and table.py's,
# callees first
COMPILED = ("finite_into", "leave_note", "note", "inertia_ratio", "hertz_ratio", "checked_value",
            "inside", "note_outside", "note_run_outside", "mirrored", "take_inputs", "prepare",
            "roller_row", "outputs", "check_scene", "init", "step", "end", "state_problem")


def compiled_namespace():
    """equations.py's, table.py's and this module's COMPILED functions as numba njit copies
    calling each other (IEEE arithmetic: error_model numpy), with the reduced model's functions
    they call; the modules themselves stay plain Python."""
    import types

    import numba as nb

    from . import hertz

    def jit(f):
        return nb.njit(error_model="numpy")(f)

    h = dict(vars(hertz))
    h["groove_curvature_radii"] = jit(groove_curvature_radii)
    g = {**vars(equations), **vars(table), **globals()}
    g["needle_line_stiffness"] = needle_row.needle_line_stiffness
    g["hertz_point"] = jit(types.FunctionType(hertz_point.__code__, h, "hertz_point"))
    for f in (spin_moment, housing_forces, fz_mod, pressing_load, same_step, same_value,
              tanh_clipped):
        g[f.__name__] = jit(f)
    return compile_over(g, needle_row.COMPILED + equations.COMPILED + table.COMPILED + COMPILED,
                        jit)


def c_functions():
    """init, step, end and check_state as the native layer's C functions (cfuncs.py), for
    fmu_src/aot.py."""
    from .cfuncs import c_functions as wrap
    return wrap(compiled_namespace(), (T_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN))


def native_layout() -> dict:
    """Where each of the analytic FMU's variables lives in this module's arrays, the arrays'
    sizes, the order the variables are checked in at initialisation (the table's, as
    scene.validate checks them) and the notes' wording: for the FMU whose binary runs this
    module compiled (fmu_src/native_fmu.py)."""
    from .cfuncs import native_layout as layout
    return layout(BY_NAME, PARAM_NAMES, INPUT_NAMES, OUTPUT_NAMES,
                  [p.name for p in params_for("analytic")],
                  (T_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN), W_NOTES, MAX_NOTES, NOTE_TEXT,
                  STATE_PROBLEMS)
