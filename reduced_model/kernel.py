"""The reduced model's equations as scalar functions over flat arrays: one source for the reduced
traverse model (traverse.Traverse), the analytic FMU's model as Python (analytic_model) and the
analytic FMU's binary, which compiles ``init``, ``step``, ``end`` and ``check_state`` ahead of
time (c_functions, fmu_src/aot.py) and runs them without Python.

Arrays (float64; flags and counts as 0.0 / 1.0, integers as floats; Python lists or numpy
arrays on the Python path):
- P: the analytic FMU's parameters in PARAM_NAMES' order (the table's, inputs left out);
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

from .friction import V_ST_FLOOR, spin_moment
from .hertz import groove_curvature_radii, hertz_point
from .housing import housing_forces
from .scene import BY_NAME, CONTACT_ONLY_OUTPUTS, MAX_SUBSTEPS, OUTPUTS, STEP_ROUNDING, \
    params_for
from .thrust import fz_mod

TWO_PI = 6.283185307179586   # math.tau

# --- the FMU's variables ----------------------------------------------------------------------
PARAM_NAMES = tuple(p.name for p in params_for("analytic") if p.causality != "input")
INPUT_NAMES = tuple(p.name for p in params_for("analytic") if p.causality == "input")
OUTPUT_NAMES = tuple(n for n, _, _ in OUTPUTS if n not in CONTACT_ONLY_OUTPUTS) + ("regime",)
(DRIVE_BY_ANGLE, N_ROLLERS, MU_GROOVE, V_ST, PITCH, YAW, ROLL, AXIAL, S, R_ROLLER, R_GROOVE,
 R_BORE, M_ROLLER, SPIN_INERTIA, TRAVERSE, SPIN_MOMENT, E, NU) = map(PARAM_NAMES.index, (
    "drive_by_angle", "n_rollers", "mu_groove", "v_st", "pitch", "yaw", "roll", "axial", "s",
    "r_roller", "r_groove", "r_bore", "m_roller", "spin_inertia", "traverse", "spin_moment",
    "E", "nu"))
P_LEN = len(PARAM_NAMES)
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

# --- the reduced traverse model's table -------------------------------------------------------
N_PER_CYCLE = 360          # table points a whirl cycle (24 scenes: order 3 within 0.02 % of 1440)
PERIODIC_TOL = 1e-7        # the secant's target: |s(2 pi) - s(0)| <= PERIODIC_TOL x v_st
SETTLED_TOL = 1e-5         # periodic enough: the tanh friction moves by <= 3 SETTLED_TOL of
                           # mu f_n over the mismatch, far below compare's 0.1 % settling
STALL = 3                  # cycles without a better one: the secant is in the map's noise
MAX_CYCLES = 60            # cycles of the cycle map the secant may run
MICRO_SLIP_G = 0.95        # friction never above 95 % of mu_s f_n: the roller never slides across
FULL_SLIP_REL = 0.05       # order 3 within 5 % (complex) of Eq. (27): Eqs. 18-27 hold
REGIME_FULL_SLIP, REGIME_TRAVERSE, REGIME_MICRO_SLIP = 0, 1, 2   # scene.REGIME_CODES

# the operating point: the scene's constants at the inputs of its key, for the scene the reduced
# model runs (coast: drive at the opposite whirl, turned about the trunnion axis)
(O_W, O_TH, O_T, O_KR, O_S, O_R, O_F, O_MU, O_VST, O_K, O_A1, O_CLEAR, O_RHO, O_VP, O_SM, O_I,
 O_HELD, O_MIRROR, O_A, O_B, O_KT, O_MUF, O_THP, O_VPP, O_KSPIN, O_LOAD, O_LEN) = range(27)

# --- the state X ------------------------------------------------------------------------------
MODE_THRUST, MODE_TABLE, MODE_MARCH = 0, 1, 2
# a roller's march row: slide slip s [m/s], p [1], the outputs (Fz, Fz_mod, Fx, Fy [N], slip
# speed [m/s]), whether s and the outputs exist yet (the march starts at rest)
R_S, R_P, R_FZ, R_FZ_MOD, R_FX, R_FY, R_SLIP, R_HAS_S, R_HAS_OUT, R_LEN = range(10)
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
X_TABLE_PS = X_TABLE_SS + TABLE_ROWS    # the table's points (where a march starts)
X_LEN = X_TABLE_PS + TABLE_ROWS

# --- the work W: the table's derivation, then the notes ---------------------------------------
# per table point: driven slip V, T2's inertia part bi, dphi, spin, phi, xi; the cycle run and
# the best one (slip s, p)
(D_V, D_BI, D_DPHI, D_SPIN, D_PHI, D_XI, D_SS, D_PS, D_BEST_SS, D_BEST_PS,
 D_COUNT) = range(11)
W_NOTES = D_COUNT * TABLE_ROWS
NOTE_ARGS = 4
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
# held at their defaults in that check (yaw and axial are not here: the analytic model does not
# use them, so they cannot move its result)
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
    (ERROR, "the communication step of %.4g s in substeps of %.3g s "
            f"needs more than the {MAX_SUBSTEPS:.0f} substeps one step may take: take shorter "
            "communication steps"),
    (ERROR, "r_groove = %g m must exceed r_roller = %g m (range (r_roller, 1] m)"),
    (ERROR, "r_bore = %g m must be below r_roller = %g m (range (0, r_roller) m)"),
    (ERROR, "n_rollers = %.0f is not allowed; allowed: 1 or 3"),
    (ERROR, "mu_groove = %g: the traverse model needs mu_groove < 1 (the friction it balances "
            "tilts the contact normal by asin(mu_groove)); allowed range [0, 1) (or traverse = "
            "false)"),
) + tuple((WARNING, "; " + phrase(k, False)) for k in range(len(CHECKED_RANGES))) \
  + tuple((WARNING, "; " + phrase(k, True)) for k in range(len(CHECKED_RANGES))) \
  + tuple((WARNING, "; " + default_phrase(j)) for j in range(len(CHECKED_AT_DEFAULT)))
(NOTE_OUTSIDE, NOTE_UNSETTLED, NOTE_MARCH, NOTE_RUN_OUTSIDE, NOTE_STEPS, NOTE_STEPS_MARCH,
 NOTE_TOO_LONG, NOTE_GROOVE, NOTE_BORE, NOTE_ROLLERS, NOTE_MU) = range(11)
NOTE_CHECKED = 11                                       # + k: CHECKED_RANGES[k], one value
NOTE_CHECKED_SPAN = NOTE_CHECKED + len(CHECKED_RANGES)  # + k: a span
NOTE_DEFAULT = NOTE_CHECKED_SPAN + len(CHECKED_RANGES)  # + j: CHECKED_AT_DEFAULT[j]


def notes_text(W):
    """[(level, message)] of the notes W holds, a note starting with "; " joined to the one
    before (as the FMU's binary words them: fmu_src/native/fmi2_native.c)."""
    out = []
    for n in range(int(W[W_NOTES])):
        at = W_NOTES + 1 + n * (1 + NOTE_ARGS)
        level, fmt = NOTE_TEXT[int(W[at])]
        args = tuple(float(W[at + 1 + i]) for i in range(fmt.count("%")))
        text = fmt % args
        if text.startswith("; ") and out:
            prev_level, prev = out[-1]
            out[-1] = (prev_level, prev + (text[2:] if prev.endswith(": ") else text))
        else:
            out.append((level, text))
    return out


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


# --- the scene's constants --------------------------------------------------------------------
def pressing_load(F_press, torque, s):
    """Pressing load per roller [N]: torque / (3 s) when a torque [N m] is given (not 0; < 0
    coast), else F_press (< 0 coast); s [m] the pitch-circle radius (scene.pressing_load)."""
    return torque / (3.0 * s) if torque != 0 else F_press


def transition_velocity(v_st, s, r, w, th, vp, pitch, roll):
    """v_st [m/s] in use: the scene's, or the automatic sqrt(A^2 + B^2 + Vp^2) / 4, at least
    V_ST_FLOOR (friction.v_st_auto), with A = s w th^2 / 2 (Eq. 19), B = -r w (1 - cos th) /
    cos th (Eq. 20), Vp = |v_p| sin th (the plunge's sliding); pitch and roll switch A, Vp and
    B."""
    if v_st > 0:
        return v_st
    A = 0.5 * s * w * (th * th) if pitch else 0.0
    B = 0.0
    if roll:
        c = math.cos(th)
        B = -r * w * (1.0 - c) / c
    h = math.sqrt(A * A + B * B)
    Vp = abs(vp) * math.sin(th) if pitch else 0.0
    if Vp != 0.0:
        h = math.sqrt(h * h + Vp * Vp)
    return max(h / 4.0, V_ST_FLOOR)


def operating_point(P, theta, omega, F_press, torque, vp, O):
    """O: the constants of the scene the reduced model runs at these inputs (theta [rad], omega
    [rad/s], F_press [N], torque [N m], plunge speed vp [m/s]): Traverse's (T1-T6) and Eqs.
    (18)-(27)'s.  Coast (a negative pressing load) runs as drive at the opposite whirl and
    plunge speed, turned 180 deg about the trunnion axis (docs/model.md): O_MIRROR."""
    s, r = P[S], P[R_ROLLER]
    load = pressing_load(F_press, torque, s)
    mirror = load < 0
    if mirror:    # (-tq) / (3 s) is -(tq / (3 s)) to the bit
        omega, F_press, torque, vp = -omega, -F_press, -torque, -vp
    F = pressing_load(F_press, torque, s)
    pitch, roll = P[PITCH] != 0.0, P[ROLL] != 0.0
    O[O_W] = omega
    O[O_TH] = theta
    O[O_T] = math.tan(theta) if pitch else 0.0
    O[O_KR] = (1.0 - math.cos(theta)) / (2.0 * math.cos(theta)) if roll else 0.0   # e / s
    O[O_S] = s
    O[O_R] = r
    O[O_F] = F
    O[O_LOAD] = load
    O[O_MIRROR] = 1.0 if mirror else 0.0
    mu = P[MU_GROOVE]
    O[O_MU] = mu
    vst = transition_velocity(P[V_ST], s, r, omega, theta, vp, pitch, roll)
    O[O_VST] = vst
    K, a1, _ = hertz_point(r, P[R_GROOVE], P[E], P[NU])
    O[O_K] = K
    O[O_A1] = a1
    clear = P[R_GROOVE] - r
    O[O_CLEAR] = clear
    O[O_RHO] = clear + (F / K) ** (2.0 / 3.0) if F > 0 else clear
    O[O_VP] = vp
    O[O_SM] = 1.0 if P[SPIN_MOMENT] != 0.0 else 0.0
    # the roller's spin inertia as a thick ring, m (r^2 + r_bore^2) / 2 (0: the spin-inertia
    # thrust switched off)
    inertia = 0.5 * P[M_ROLLER] * (r * r + P[R_BORE] * P[R_BORE])
    O[O_I] = inertia if P[SPIN_INERTIA] != 0.0 else 0.0
    O[O_HELD] = 1.0 if (F > 0 and mu > 0 and vst > 0) else 0.0   # else nothing holds the roller
    # Eqs. (18)-(27): V = A sin 2x + B cos 2x (Eq. 24), ft = mu F tanh(3 V / v_st)
    O[O_A] = 0.5 * s * omega * (theta * theta) if pitch else 0.0
    if roll:
        c = math.cos(theta)
        O[O_B] = -r * omega * (1.0 - c) / c
    else:
        O[O_B] = 0.0
    O[O_KT] = 3.0 / vst if vst > 0 else 1e300         # Coulomb at v_st = 0
    O[O_MUF] = mu * F                                  # Eq. (11)
    th = theta if pitch else 0.0
    O[O_THP] = th                                      # Eq. (2): phi = theta sin x
    O[O_VPP] = vp if pitch else 0.0                    # the plunge's part of dz/dt in v1
    # the spin inertia's thrust (I / r^2) d2z/dt2, d2z/dt2 = -w^2 s theta sin x
    O[O_KSPIN] = -inertia / (r * r) * omega * omega * (s * th) \
        if (P[SPIN_INERTIA] != 0.0 and pitch) else 0.0


# --- Eqs. (18)-(27) ---------------------------------------------------------------------------
def thrust_at(O, x):
    """(Fz, ft, V, phi) at whirl angle x [rad]: Eqs. (2), (18)-(26) and the spin inertia's
    thrust; N, N, m/s, rad."""
    sx = math.sin(x)
    V = O[O_A] * math.sin(2.0 * x) + O[O_B] * math.cos(2.0 * x)   # Eq. (24)
    phi = O[O_THP] * sx                                            # Eq. (2)
    if O[O_VPP] != 0.0:                                            # plunging: v_p sin(phi)
        V = V + O[O_VPP] * math.sin(phi)
    ft = O[O_MUF] * math.tanh(O[O_KT] * V)                         # Eqs. (11), (25), Fig. 8
    return ft * math.sin(phi) + O[O_KSPIN] * sx, ft, V, phi       # Eq. (26)


# --- the traverse model, T1-T6 (traverse.py's header) -----------------------------------------
def drive_at(O, x):
    """The driving motion at whirl angle x [rad], exact Eqs. (1), (5) (z = s tan(phi), Eq. 18):
    phi, xi [rad], V [m/s] (T4's driven slip), dphi [rad/s], spin [rad/s] (rolling along the
    groove), bi [N] (T2's inertia part of f_b)."""
    w, T, k, r = O[O_W], O[O_T], O[O_KR], O[O_R]
    tz = T * math.sin(x)
    phi = math.atan(tz)
    dphi = T * w * math.cos(x) / (1.0 + tz * tz)
    q = k * math.sin(2.0 * x)
    xi = math.asin(q)
    dxi = 2.0 * w * k * math.cos(2.0 * x) / math.sqrt(1.0 - q * q)
    zd = O[O_S] * T * w * math.cos(x)
    if O[O_VP] != 0.0:                                  # the plunge: travel along z
        zd = zd + O[O_VP]
    zdd = -O[O_S] * T * w * w * math.sin(x)
    v1 = zd * math.sin(phi)                             # Eq. (19), exact
    v2 = -r * dxi                                       # Eq. (20), exact
    V = v1 + v2 * (1.0 + O[O_RHO] / r)                  # T4
    return phi, xi, V, dphi, zd / r, -O[O_I] * zdd / (r * r)


def normal_force(O, p):
    """T5: f_n [N] at p [1]."""
    d = O[O_RHO] / math.sqrt(1.0 - p * p) - O[O_CLEAR]
    return O[O_K] * d ** 1.5 if d > 0 else 0.0


def beta_at(O, p, fn, bi, dphi, spin):
    """T2: f_b / f_n where the drive gives bi [N], dphi and spin [rad/s]; with the spin moment,
    Eqs. (14)-(16), against the spin w_n = dphi + spin p [rad/s]."""
    b = bi
    if O[O_SM] != 0.0:
        b -= spin_moment(O[O_MU], fn, O[O_A1], dphi + spin * p, O[O_VST]) * p / O[O_R]
    return b / fn


def share(O, s, B):
    """T3 inverted: p >= 0 [1] for the slide slip |s| [m/s] when the spin needs |f_b| / f_n = B:
    the slip vector (s, t) at angle a from the slide, mu tanh(3 |s| / (v_st cos a)) sin a = B,
    solved by bisection and Newton on a in [0, pi/2) (its left side rises from 0 to mu); then
    p = mu tanh(3 |v| / v_st) cos a."""
    mu, k = O[O_MU], 3.0 / O[O_VST]
    B = min(B, mu * (1.0 - 1e-9))
    s = abs(s)
    if B <= 0.0:
        return mu * math.tanh(k * s)
    if s == 0.0:
        return 0.0
    lo, hi = 0.0, 0.5 * math.pi
    a = min(math.asin(min(B / (mu * math.tanh(k * s) + 1e-300), 1.0)), 1.5)
    for _ in range(60):
        c, sn = math.cos(a), math.sin(a)
        th = math.tanh(k * s / c)
        f = mu * th * sn - B
        if f > 0:
            hi = a
        else:
            lo = a
        df = mu * (th * c + sn * (1.0 - th * th) * k * s * sn / (c * c))
        an = a - f / df if df > 0 else 0.5 * (lo + hi)
        if not lo < an < hi:
            an = 0.5 * (lo + hi)
        if abs(an - a) < 1e-10:
            a = an
            break
        a = an
    return mu * math.tanh(k * s / math.cos(a)) * math.cos(a)


def p_at(O, s, bi, dphi, spin, p0, guess):
    """T2, T3, T5: p for the slide slip s [m/s] where the drive gives bi, dphi, spin (beta
    depends weakly on p through f_n and the spin moment: fixed point), from p0 when guess and
    of p's sign (the march: a nearby point's p), else from beta = 0."""
    mu = O[O_MU]
    sign = -1.0 if s > 0 else 1.0
    p = sign * mu * math.tanh(3.0 * abs(s) / O[O_VST])
    if guess and p0 * sign > 0.0:
        p = p0
    for _ in range(6):
        q = sign * share(O, s, abs(beta_at(O, p, normal_force(O, p), bi, dphi, spin)))
        if abs(q - p) < 1e-11 * mu:
            return q
        p = q
    return p


def trapezoid_step(O, rhs0, s, h, bi, dphi, spin, p0, guess):
    """s1 [m/s] of one trapezoidal step of T4 from slip s over h [s]: the root of f(z) = rho_c
    p(z) - h/2 z - rhs0, p at the step's end point.  Newton: f falls with slope <= -h/2 and
    |p| <= mu, so its root lies in [lo, hi]; a Newton step that leaves the bracket (it
    overshoots on the tanh's knee and can cycle there) is a bisection instead.  guess (the
    march): p's fixed point starts from p0, then from the last p found."""
    rho, mu, vst = O[O_RHO], O[O_MU], O[O_VST]
    e = 1e-6 * vst              # finite-difference step of the Newton slope
    lo, hi = -2.0 * (rho * mu + rhs0) / h, 2.0 * (rho * mu - rhs0) / h
    z = min(max(s, lo), hi)
    g = p0
    for _ in range(200):
        p1 = p_at(O, z, bi, dphi, spin, g, guess)
        g = p1
        res = rho * p1 - 0.5 * h * z - rhs0
        if res > 0.0:
            lo = z
        elif res < 0.0:
            hi = z
        else:
            break
        d = (rho * (p_at(O, z + e, bi, dphi, spin, p1, guess) - p1)) / e - 0.5 * h
        dz = -res / d
        if not lo < z + dz < hi:
            dz = 0.5 * (lo + hi) - z
        z += dz
        if abs(dz) < 1e-9 * vst:
            break
    return z


def slip_step(O, rhs0, s, h, bi, dphi, spin, p0):
    """(settled, s1 [m/s], p1 [1]) of one trapezoidal step of T4 from slip s and p0 over h [s],
    the march's first choice: T3 and T4 together as Newton on the slip vector (s, t), t >= 0
    across the slide, where trapezoid_step nests T3's inversion (and T2's fixed point) inside
    its Newton and costs three to four times as much.  The friction mu tanh(k |v|) v / |v| (k =
    3 / v_st) gives p = -mu g s / |v| and |f_b| / f_n = mu g t / |v|; the residuals are T4,
    rho_c p - h/2 s - rhs0, and T2's demand, mu g t / |v| - |beta(p)| (capped as share caps
    it), with the friction's Jacobian exact and beta's weak dependence on p left out of it.
    Not settled within 30 iterations to 1e-9 v_st (the start from rest, some steps after a
    jump: about one step in 200 over random scenes): the caller takes trapezoid_step.  Where T3
    determines the slip the two agree within 2e-6 of v_st, mu and the thrust over 2000 steps
    (tests/test_traverse.py; measured 1e-11 to 2e-8)."""
    rho, mu, k = O[O_RHO], O[O_MU], 3.0 / O[O_VST]
    kt = 0.5 * h
    cap = mu * (1.0 - 1e-9)
    tol = 1e-9 * O[O_VST]
    t = 0.0
    if p0 != 0.0:   # the last step's slip angle
        t = abs(s * min(abs(beta_at(O, p0, normal_force(O, p0), bi, dphi, spin)), cap) / p0)
    for _ in range(30):
        v = math.sqrt(s * s + t * t)
        gv, dg, us, ut = k, k, 0.0, 0.0      # the friction's slope at v = 0
        if v > 0.0:
            g = math.tanh(k * v)
            gv, dg, us, ut = g / v, k * (1.0 - g * g), s / v, t / v
        p = -mu * gv * s
        B = min(abs(beta_at(O, p, normal_force(O, p), bi, dphi, spin)), cap)
        a11 = mu * (gv * (1.0 - us * us) + dg * us * us)
        a22 = mu * (gv * (1.0 - ut * ut) + dg * ut * ut)
        a12 = mu * (dg - gv) * us * ut
        r1 = rho * p - kt * s - rhs0
        r2 = mu * gv * t - B
        j11 = -rho * a11 - kt
        j12 = -rho * a12
        det = j11 * a22 - j12 * a12          # < 0: the friction's Jacobian is semi-definite
        if not det < 0.0:
            return False, s, 0.0
        ds = (j12 * r2 - a22 * r1) / det
        dt = (a12 * r1 - j11 * r2) / det
        s += ds
        t = abs(t + dt)
        if abs(ds) < tol and abs(dt) < tol:
            v = math.sqrt(s * s + t * t)
            return True, s, -mu * (math.tanh(k * v) / v if v > 0.0 else k) * s
    return False, s, 0.0


def groove_forces(fn, p, beta, phi, xi, F):
    """T6: (Fz, Fx, Fy, Fz_mod) [N] on the groove from the normal force fn [N], p, beta [1], the
    pitch phi and roll tilt xi [rad], F the pressing load [N].  T1 on the groove: the ideal
    bearing takes no force along the trunnion axis a = (sin xi, cos xi cos phi, cos xi sin phi),
    so F . a = 0 gives Fy."""
    Fz = -fn * (p * math.sin(phi) + beta * math.cos(phi))
    Fx = fn * (math.sqrt(1.0 - p * p) + p * p - p * xi)
    Fy = -(Fx * math.sin(xi) + Fz * math.cos(xi) * math.sin(phi)) / (math.cos(xi) * math.cos(phi))
    return Fz, Fx, Fy, fz_mod(Fx, Fz, F)


# --- the periodic solution: the settled table -------------------------------------------------
# D (work, n + 1 values a row, rows D_*): the driving motion at the table's n + 1 points, the
# cycle run and the best one; T: the table (n + 1 rows of Fz, Fz_mod, Fx, Fy [N], slip speed
# [m/s]); SS, PS: the settled cycle's slide slip s [m/s] and p [1] at the table's points
def drive_table(O, D, n):
    """The driving motion at the table's points (whirl angles 2 pi i / n) into D."""
    m = n + 1
    for i in range(m):
        phi, xi, V, dphi, spin, bi = drive_at(O, 2.0 * math.pi * i / n)
        D[D_V * m + i] = V
        D[D_BI * m + i] = bi
        D[D_DPHI * m + i] = dphi
        D[D_SPIN * m + i] = spin
        D[D_PHI * m + i] = phi
        D[D_XI * m + i] = xi


def table_p(O, D, n, i, s):
    """p at table point i for the slide slip s [m/s]."""
    m = n + 1
    return p_at(O, s, D[D_BI * m + i], D[D_DPHI * m + i], D[D_SPIN * m + i], 0.0, False)


def cycle(O, D, n, s0):
    """One whirl cycle of T4, rho_c dp/dt = s - V', by the trapezoidal rule in s (never
    singular: d(rho_c p - h s / 2)/ds <= -h / 2) from slide slip s0 [m/s]: s and p at every
    table point into D (D_SS, D_PS).  Returns s at the cycle's end."""
    m = n + 1
    h = 2.0 * math.pi / O[O_W] / n
    rho, v, ss, ps = O[O_RHO], D_V * m, D_SS * m, D_PS * m
    s = s0
    p0 = table_p(O, D, n, 0, s)
    D[ss] = s
    D[ps] = p0
    for i in range(n):
        rhs0 = rho * p0 + 0.5 * h * (s - D[v + i] - D[v + i + 1])
        j = i + 1
        s = trapezoid_step(O, rhs0, s, h, D[D_BI * m + j], D[D_DPHI * m + j],
                           D[D_SPIN * m + j], 0.0, False)
        p0 = table_p(O, D, n, j, s)
        D[ss + j] = s
        D[ps + j] = p0
    return s


def keep_best(D, n):
    """The cycle just run (D_SS, D_PS) as the best one."""
    m = n + 1
    for i in range(m):
        D[D_BEST_SS * m + i] = D[D_SS * m + i]
        D[D_BEST_PS * m + i] = D[D_PS * m + i]


def periodic(O, D, n):
    """The slide slip over one cycle with s(2 pi) = s(0): secant on the cycle map; the best
    cycle run into D (D_BEST_SS, D_BEST_PS).  Returns (cycles run, |s(2 pi) - s(0)| [m/s]).
    The cycle map carries the rounding of n inner solves, amplified where the slip crosses the
    tanh's knee (up to about 1e-5 v_st, measured): where the secant wanders in that noise (no
    better cycle in STALL tries) and the best cycle is within SETTLED_TOL, it stops there."""
    vst = O[O_VST]
    tol = PERIODIC_TOL * vst
    a = 0.0
    ga = cycle(O, D, n, a) - a
    b = a + ga
    gb = cycle(O, D, n, b) - b
    best = abs(gb)
    keep_best(D, n)
    stall = 0
    used = 2
    while abs(gb) > tol and gb != ga and used < MAX_CYCLES:
        a, ga, b = b, gb, b - gb * (b - a) / (gb - ga)
        gb = cycle(O, D, n, b) - b
        used += 1
        if abs(gb) < best:
            best, stall = abs(gb), 0
            keep_best(D, n)
        else:
            stall += 1
            if stall >= STALL and best <= SETTLED_TOL * vst:
                break
    return used, best


def traverse_table(O, D, n, T, SS, PS):
    """The settled table at O (O_W > 0) into T, SS, PS.  Returns (cycles of the cycle map run,
    mismatch |s(2 pi) - s(0)| [m/s], g_max: the largest friction over mu_s f_n [1])."""
    drive_table(O, D, n)
    m = n + 1
    bss, bps = D_BEST_SS * m, D_BEST_PS * m
    if O[O_HELD] == 0.0:            # no friction, or no slip to drive it: the roller slips by V
        for i in range(m):
            D[bss + i] = D[D_V * m + i]
            D[bps + i] = 0.0
        cycles, mismatch = 0, 0.0
    else:
        cycles, mismatch = periodic(O, D, n)
    g_max = 0.0
    for i in range(m):
        p = D[bps + i]
        fn = normal_force(O, p) if O[O_F] > 0 else 0.0
        beta = beta_at(O, p, fn, D[D_BI * m + i], D[D_DPHI * m + i],
                       D[D_SPIN * m + i]) if fn > 0 else 0.0
        Fz, Fx, Fy, Fzm = groove_forces(fn, p, beta, D[D_PHI * m + i], D[D_XI * m + i], O[O_F])
        g = math.sqrt(p * p + beta * beta)
        if g > g_max:
            g_max = g
        T[5 * i] = Fz
        T[5 * i + 1] = Fzm
        T[5 * i + 2] = Fx
        T[5 * i + 3] = Fy
        T[5 * i + 4] = abs(D[bss + i])
        SS[i] = D[bss + i]
        PS[i] = p
    return cycles, mismatch, (g_max / O[O_MU] if O[O_MU] > 0 else 0.0)


def table_index(n, x):
    """(i, f): the table's interval and the fraction into it at whirl angle x [rad]."""
    u = (x % TWO_PI) * (n / TWO_PI)
    i = int(u)
    if i >= n:
        i = n - 1
    return i, u - i


def table_at(T, n, x, k):
    """Column k (0 Fz, 1 Fz_mod, 2 Fx, 3 Fy [N], 4 slip speed [m/s]) of the table at whirl
    angle x [rad]: linear interpolation."""
    i, f = table_index(n, x)
    a = T[5 * i + k]
    return a + f * (T[5 * (i + 1) + k] - a)


def table_state_at(SS, PS, n, x):
    """(slide slip s [m/s], p [1]) of the settled cycle at whirl angle x [rad]: linear
    interpolation, where the march starts when the inputs begin to move."""
    i, f = table_index(n, x)
    return SS[i] + f * (SS[i + 1] - SS[i]), PS[i] + f * (PS[i + 1] - PS[i])


def order3(T, n, O):
    """Whether the table's order 3 of Fz_mod lies within FULL_SLIP_REL (complex) of Eq.
    (27)'s at O: the sums of y_i exp(-3 j x_i) over the table's points, compared."""
    re_t = im_t = re_e = im_e = 0.0
    for i in range(n):
        x = 2.0 * math.pi * i / n
        c, sn = math.cos(3.0 * x), math.sin(3.0 * x)
        y = T[5 * i + 1]
        e = thrust_at(O, x)[0]
        re_t += y * c
        im_t -= y * sn
        re_e += e * c
        im_e -= e * sn
    d = math.sqrt((re_t - re_e) * (re_t - re_e) + (im_t - im_e) * (im_t - im_e))
    m = math.sqrt(re_e * re_e + im_e * im_e)
    return m > 0 and d <= FULL_SLIP_REL * m


def regime(g_max, T, n, O):
    """REGIME_MICRO_SLIP where the friction never reaches MICRO_SLIP_G of mu_s f_n (g_max [1]),
    else REGIME_FULL_SLIP where the table's order 3 is Eq. (27)'s within FULL_SLIP_REL, else
    REGIME_TRAVERSE."""
    if g_max < MICRO_SLIP_G:
        return REGIME_MICRO_SLIP
    return REGIME_FULL_SLIP if order3(T, n, O) else REGIME_TRAVERSE


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


def checked_value(P, O, k):
    """CHECKED_RANGES[k]'s quantity for the scene the reduced model runs at O, in its unit."""
    if k == C_THETA:
        return O[O_TH] * (180.0 / math.pi)
    if k == C_MU:
        return P[MU_GROOVE]
    if k == C_INERTIA:
        return inertia_ratio(P[M_ROLLER], P[R_ROLLER], O[O_W], O[O_F])
    if k == C_CLEARANCE:
        return (P[R_GROOVE] - P[R_ROLLER]) / P[R_ROLLER]
    if k == C_ROLLER:
        return P[R_ROLLER] / P[S]
    if k == C_BORE:
        return P[R_BORE] / P[R_ROLLER]
    if k == C_HERTZ:
        return hertz_ratio(O, O[O_F])
    return O[O_VP]


def inside(k, v0, v1):
    """Whether the values v0..v1 of CHECKED_RANGES[k]'s quantity lie in its checked range."""
    lo, hi = CHECKED_RANGES[k][2], CHECKED_RANGES[k][3]
    return lo - 1e-9 * abs(lo) <= v0 and v1 <= hi + 1e-9 * abs(hi)


def note_outside(P, O, W):
    """Notes naming what of the scene at O lies outside the checked range (none inside it)."""
    head = False
    for k in range(len(CHECKED_RANGES)):
        v = checked_value(P, O, k)
        if not inside(k, v, v):
            if not head:
                note(W, NOTE_OUTSIDE, 0.0, 0.0, 0.0, 0.0)
                head = True
            note(W, NOTE_CHECKED + k, v, 0.0, 0.0, 0.0)
    for j in range(len(DEFAULT_SLOTS)):
        v = P[DEFAULT_SLOTS[j]]
        if v != DEFAULT_VALUES[j]:
            if not head:
                note(W, NOTE_OUTSIDE, 0.0, 0.0, 0.0, 0.0)
                head = True
            note(W, NOTE_DEFAULT + j, v, 0.0, 0.0, 0.0)


def note_run_outside(P, X, W):
    """Notes naming where the run's inputs (their span) left the checked range."""
    O = X[X_OP:X_OP + O_LEN]
    t0, w0, f0 = X[X_SPAN], X[X_SPAN + 1], X[X_SPAN + 2]
    t1, w1, f1 = X[X_SPAN + 3], X[X_SPAN + 4], X[X_SPAN + 5]
    # the roller's inertia at its worst: the highest whirl on the lowest load
    worst = inertia_ratio(P[M_ROLLER], P[R_ROLLER], w1, f0)
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


# --- the slide stepped in time (inputs that move) ---------------------------------------------
def march(O, X, r, x, dt):
    """The slide of the roller whose march row starts at X[r] stepped in time at O from whirl
    angle x [rad] over dt [s] (T4 is an ODE in time; the table is its periodic solution), by the
    table's trapezoidal rule in substeps of at most the table's spacing (each by slip_step, or
    trapezoid_step where that does not settle); the row's outputs at the end (T5, T2, T6).  From
    rest (no slip yet): on the groove bottom, p = 0.  Returns x at the end.  The caller checks
    the substeps' count (steps_of)."""
    n, h = steps_of(O, dt)
    wh = O[O_W] * h
    V0 = drive_at(O, x)[2]
    s, p = X[r + R_S], X[r + R_P]
    if X[r + R_HAS_S] == 0.0:
        s, p = V0, 0.0
    phi = xi = bi = dphi = spin = 0.0
    for i in range(n):
        phi, xi, V1, dphi, spin, bi = drive_at(O, x + wh * (i + 1))
        if O[O_HELD] != 0.0:
            rhs0 = O[O_RHO] * p + 0.5 * h * (s - V0 - V1)
            ok, s1, p1 = slip_step(O, rhs0, s, h, bi, dphi, spin, p)
            if ok:
                s, p = s1, p1
            else:
                s = trapezoid_step(O, rhs0, s, h, bi, dphi, spin, p, True)
                p = p_at(O, s, bi, dphi, spin, p, True)
        V0 = V1
    if O[O_HELD] == 0.0:
        s, p = V0, 0.0
    fn = normal_force(O, p) if O[O_F] > 0 else 0.0
    beta = beta_at(O, p, fn, bi, dphi, spin) if fn > 0 else 0.0
    Fz, Fx, Fy, Fzm = groove_forces(fn, p, beta, phi, xi, O[O_F])
    X[r + R_S] = s
    X[r + R_P] = p
    X[r + R_FZ] = Fz
    X[r + R_FZ_MOD] = Fzm
    X[r + R_FX] = Fx
    X[r + R_FY] = Fy
    X[r + R_SLIP] = abs(s)
    X[r + R_HAS_S] = 1.0
    X[r + R_HAS_OUT] = 1.0
    return x + wh * n


def substeps(O, dt):
    """The march's substeps over dt [s] (at most the table's spacing), before rounding up."""
    return abs(O[O_W]) * dt * N_PER_CYCLE / (2.0 * math.pi) - 1e-9


def steps_of(O, dt):
    """(n, h [s]): the march's substeps over dt [s]."""
    n = max(1, int(math.ceil(substeps(O, dt))))
    return n, dt / n


# --- the analytic FMU's lifecycle -------------------------------------------------------------
def same_value(a, b):
    """Whether a and b differ only by rounding (scene.same_value)."""
    return math.isfinite(a) and math.isfinite(b) and \
        abs(a - b) <= STEP_ROUNDING * max(abs(a), abs(b))


def same_step(dt, dt0, t):
    """Whether a step of dt [s] at t [s] is the step dt0 up to a master's rounding
    (scene.same_step)."""
    return abs(dt - dt0) <= STEP_ROUNDING * max(abs(t), dt0)


def mirrored(X, x):
    """The reduced model's whirl angle for a roller's angle x [rad] (coast: turned)."""
    return -x if X[X_OP + O_MIRROR] != 0.0 else x


def take_inputs(P, IN, X):
    """IN's operating-point inputs as the key, the operating point at them, the span widened."""
    for q in range(N_KEY):
        X[X_KEY + q] = IN[q]
    X[X_HAS_KEY] = 1.0
    operating_point(P, IN[THETA], IN[OMEGA], IN[F_PRESS], IN[TORQUE], IN[PLUNGE_SPEED],
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


def prepare(P, IN, X, W):
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
    take_inputs(P, IN, X)
    loaded = O[O_MU] > 0 and O[O_F] > 0
    if P[TRAVERSE] == 0.0:
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
            T = X[X_TABLE:X_TABLE + 5 * TABLE_ROWS]
            cycles, mismatch, g_max = traverse_table(
                O, W[:W_NOTES], N_PER_CYCLE, T, X[X_TABLE_SS:X_TABLE_SS + TABLE_ROWS],
                X[X_TABLE_PS:X_TABLE_PS + TABLE_ROWS])
            X[X_CYCLES] = cycles
            X[X_MISMATCH] = mismatch
            X[X_SETTLED] = 1.0 if mismatch <= SETTLED_TOL * O[O_VST] else 0.0
            X[X_GMAX] = g_max
            X[X_MODE] = MODE_TABLE
            X[X_REGIME] = regime(g_max, T, N_PER_CYCLE, O)
            X[X_TABLES] += 1.0
            note_outside(P, O, W)
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
                    X[r + R_HAS_S] = 1.0
                else:
                    X[r + R_HAS_S] = 0.0
                    X[r + R_P] = 0.0
            if X[X_TOLD] == 0.0:   # (once: a rollback may start it again)
                note(W, NOTE_MARCH, 0.0, 0.0, 0.0, 0.0)
                X[X_TOLD] = 1.0
        X[X_MODE] = MODE_MARCH


def roller_row(P, X, i, x):
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
        T = X[X_TABLE:X_TABLE + 5 * TABLE_ROWS]
        y = mirrored(X, x)
        Fz, Fzm, Fx, Fy, slip = table_at(T, N_PER_CYCLE, y, 0), table_at(T, N_PER_CYCLE, y, 1), \
            table_at(T, N_PER_CYCLE, y, 2), table_at(T, N_PER_CYCLE, y, 3), \
            table_at(T, N_PER_CYCLE, y, 4)
    else:
        Fz, ft, V, phi = thrust_at(O, mirrored(X, x))
        return sign * Fz, sign * Fz, O[O_LOAD], ft * math.cos(phi), abs(V)
    if sign < 0:
        return -Fz, -Fzm, -Fx, Fy, slip
    return Fz, Fzm, Fx, Fy, slip


def outputs(P, X, OUT):
    """Every output at the state X into OUT when each is finite.  Returns 1, or 2 (OUT
    untouched)."""
    n = int(P[N_ROLLERS])
    F = X[X_OP + O_LOAD]
    Fz1, Fzm1, Fx1, Fy1, slip1 = roller_row(P, X, 0, X[X_WHIRL])
    total = 0.0 + Fz1
    fz2 = fx2 = fy2 = fz3 = fx3 = fy3 = 0.0      # (scalars: nothing allocated when compiled)
    if n > 1:
        fz2, _, fx2, fy2, _ = roller_row(P, X, 1, X[X_WHIRL + 1])
        total += fz2
        fz3, _, fx3, fy3, _ = roller_row(P, X, 2, X[X_WHIRL + 2])
        total += fz3
    sp = P[S]
    hx, hy, ht = housing_forces(Fx1, Fy1, sp, fx2, fy2, sp, fx3, fy3, sp)
    vals = (Fx1, Fy1, Fz1, Fzm1, Fx1 - F, slip1, total, fz2, fz3, X[X_WHIRL], fx2, fy2, fx3, fy3,
            hx, hy, ht, F, X[X_PLUNGE], X[X_REGIME])
    for v in vals:
        if not math.isfinite(v):
            return 2
    for j in range(OUT_LEN):
        OUT[j] = vals[j]
    return 1


def check_scene(P, W):
    """The relations between parameters the table's ranges cannot state (scene.validate): a note
    naming them and False where one fails."""
    if P[R_GROOVE] <= P[R_ROLLER]:
        note(W, NOTE_GROOVE, P[R_GROOVE], P[R_ROLLER], 0.0, 0.0)
        return False
    if P[N_ROLLERS] != 1.0 and P[N_ROLLERS] != 3.0:
        note(W, NOTE_ROLLERS, P[N_ROLLERS], 0.0, 0.0, 0.0)
        return False
    if P[TRAVERSE] != 0.0 and P[MU_GROOVE] >= 1.0:
        note(W, NOTE_MU, P[MU_GROOVE], 0.0, 0.0, 0.0)
        return False
    if P[R_BORE] >= P[R_ROLLER]:
        note(W, NOTE_BORE, P[R_BORE], P[R_ROLLER], 0.0, 0.0)
        return False
    return True


def init(P, IN, X, OUT, W):
    """The start: the rollers at whirl angles 0, 120, 240 deg, the operating point at IN (the
    settled table where the traverse model applies), the outputs at the start.  Returns 1; 2 for
    a non-finite output; 3 for a scene refused (its note says why)."""
    W[W_NOTES] = 0.0
    if not check_scene(P, W):
        return 3
    for j in range(X_LEN):
        X[j] = 0.0
    for i in range(3):
        X[X_WHIRL + i] = 2.0 * math.pi * i / 3.0 if i < int(P[N_ROLLERS]) else 0.0
    prepare(P, IN, X, W)
    return outputs(P, X, OUT)


def step(P, IN, X, OUT, W, t, h):
    """From t to t + h [s] at IN's inputs (driven by angle: omega from the shaft angle).
    Returns 1; 2 for a non-finite output (OUT untouched); 3 for a step refused before it starts
    (its note says why); 5 for an omega derived from the shaft angle out of its range (written
    into IN; nothing stepped)."""
    W[W_NOTES] = 0.0
    if P[DRIVE_BY_ANGLE] != 0.0:   # the whirl reaches the master's angle at the step's end
        w = (IN[SHAFT_ANGLE] - X[X_WHIRL]) / h
        IN[OMEGA] = w
        if not (IN_LO[OMEGA] <= w <= IN_HI[OMEGA]):
            return 5
    prepare(P, IN, X, W)
    # a step that differs from the last one by the rounding of the master's times is that step
    dt = h if (X[X_HAS_DT] == 0.0 or not same_step(h, X[X_DT], t)) else X[X_DT]
    O = X[X_OP:X_OP + O_LEN]
    n = int(P[N_ROLLERS])
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
    return outputs(P, X, OUT)


def end(P, IN, X, OUT, W):
    """The run's end: notes on where its inputs left the checked range (once the slide was
    stepped in time) and on how the steps ran.  Returns 1."""
    W[W_NOTES] = 0.0
    if X[X_MODE] == MODE_MARCH and P[TRAVERSE] != 0.0:
        note_run_outside(P, X, W)
    note(W, NOTE_STEPS, X[X_STEPS], X[X_TABLES], 0.0, 0.0)
    if X[X_MODE] == MODE_MARCH:
        note(W, NOTE_STEPS_MARCH, 0.0, 0.0, 0.0, 0.0)
    return 1


def state_problem(P, X):
    """0 when the state X is one the model can step (every value finite is the layer's
    check), else a code: 1 its mode, flags or counts are none the model writes; 2 an input of
    its operating point outside its range; 3 a march row's p outside [-mu_groove, mu_groove];
    4 its step not above 0."""
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
        if not abs(X[r + R_P]) <= P[MU_GROOVE]:
            return 3
    if X[X_HAS_DT] != 0.0 and not X[X_DT] > 0.0:
        return 4
    return 0


STATE_PROBLEMS = ("", "its mode, flags or counts are none the model writes",
                  "an input of its operating point is outside its range",
                  "a march row's p is outside [-mu_groove, mu_groove]",
                  "its step is not above 0")

# the functions the FMU's binary compiles (c_functions), callees first
COMPILED = ("note", "pressing_load", "transition_velocity", "operating_point", "thrust_at",
            "drive_at", "normal_force", "beta_at", "share", "p_at", "trapezoid_step",
            "slip_step", "groove_forces", "drive_table", "table_p", "cycle", "keep_best",
            "periodic", "traverse_table", "table_index", "table_at", "table_state_at", "order3",
            "regime",
            "inertia_ratio", "hertz_ratio", "checked_value", "inside", "note_outside",
            "note_run_outside",
            "substeps", "steps_of", "march", "same_value", "same_step", "mirrored",
            "take_inputs", "prepare", "roller_row", "outputs", "check_scene", "init", "step",
            "end", "state_problem")


def compiled_namespace():
    """This module's COMPILED functions as numba njit copies calling each other (IEEE
    arithmetic: error_model numpy), with the reduced model's functions they call; the module
    itself stays plain Python."""
    import types

    import numba as nb

    from . import hertz

    def jit(f):
        return nb.njit(error_model="numpy")(f)

    h = dict(vars(hertz))
    h["groove_curvature_radii"] = jit(groove_curvature_radii)
    g = dict(globals())
    g["hertz_point"] = jit(types.FunctionType(hertz_point.__code__, h, "hertz_point"))
    for f in (spin_moment, housing_forces, fz_mod):
        g[f.__name__] = jit(f)
    for name in COMPILED:
        f = g[name]
        g[name] = jit(types.FunctionType(f.__code__, g, f.__name__, f.__defaults__,
                                         f.__closure__))
    return g


def c_functions():
    """init, step, end and check_state as the native layer's C functions (cfuncs.py), for
    fmu_src/aot.py."""
    from .cfuncs import c_functions as wrap
    return wrap(compiled_namespace(), (P_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN))


def native_layout() -> dict:
    """Where each of the analytic FMU's variables lives in this module's arrays, the arrays'
    sizes, the order the variables are checked in at initialisation (the table's, as
    scene.validate checks them) and the notes' wording: for the FMU whose binary runs this
    module compiled (fmu_src/native_fmu.py)."""
    arrays = {n: ("IN_P", i) for i, n in enumerate(PARAM_NAMES)}
    arrays.update({n: ("IN_IN", i) for i, n in enumerate(INPUT_NAMES)})
    arrays.update({n: ("IN_OUT", i) for i, n in enumerate(OUTPUT_NAMES)})
    return {"by_name": BY_NAME, "arrays": arrays,
            "check_order": [p.name for p in params_for("analytic")],
            "sizes": {"P": P_LEN, "IN": IN_LEN, "X": X_LEN, "OUT": OUT_LEN, "W": W_LEN, "TH": 2},
            "notes": {"at": W_NOTES, "args": NOTE_ARGS, "max": MAX_NOTES, "text": NOTE_TEXT,
                      "state_problems": STATE_PROBLEMS}}
