"""A roller's set-up as scalar functions over arrays: its parameter vector P from the parameter
table's values, the needle row's parameters and static offset, and its start state.  One source
for the model (model.ContactModel, plain Python) and the contact FMU's binary (lifecycle.py
compiles the same functions).

T: the contact FMU's parameters in PARAM_NAMES' order (the table's; flags and integers as
floats).  SI units throughout.
"""
import math

from reduced_model.hertz import hertz_point
from reduced_model.scene import params_for
from reduced_model.table import table_state_at
from reduced_model.thrust import spin_inertia
from . import layout as K
from reduced_model.needle_row import needle_line_stiffness, row_constants
from .oppoint import groove_offset, lumped_offset

PARAM_NAMES = tuple(p.name for p in params_for("contact") if p.causality != "input")


def _slot(name):
    return PARAM_NAMES.index(name)


def params_array(p: dict) -> list:
    """The table's values T (PARAM_NAMES' order, floats) of the scene p."""
    return [float(p[n]) for n in PARAM_NAMES]


# P's slots copied from the table as they are, and the flags (1.0 or 0.0)
COPIED = tuple((slot, _slot(name)) for slot, name in (
    (K.P_S, "s"), (K.P_R_ROLLER, "r_roller"), (K.P_R_GROOVE, "r_groove"),
    (K.P_M_ROLLER, "m_roller"), (K.P_MU_GROOVE, "mu_groove"), (K.P_BEARING, "bearing"),
    (K.P_MU_NEEDLE, "mu_needle"), (K.P_MU_ROLLING, "mu_rolling"), (K.P_R_BORE, "r_bore"),
    (K.P_NEEDLE_CLEARANCE, "needle_clearance"), (K.P_INTEGRATOR, "integrator"),
    (K.P_V_ST, "v_st"), (K.P_MAX_SUBSTEP, "max_substep"), (K.P_NEWTON_PASSES, "newton_passes"),
    (K.P_NEWTON_TOL, "newton_tol"), (K.P_CONTACT_DAMPING, "contact_damping"),
    (K.P_ROW_DAMPING, "row_damping"), (K.P_SPIDER, "spider"), (K.P_SPIDER_MASS, "spider_mass"),
    (K.P_SPIDER_INERTIA, "spider_inertia"), (K.P_TOLERANCE, "tolerance"),
    (K.P_NEEDLE_AXIAL_CLEARANCE, "needle_axial_clearance")))
FLAGS = tuple((slot, _slot(name)) for slot, name in (
    (K.P_PITCH, "pitch"), (K.P_YAW, "yaw"), (K.P_ROLL, "roll"), (K.P_AXIAL, "axial"),
    (K.P_TRAVERSE, "traverse"), (K.P_FRICTION_GROOVE, "friction_groove"),
    (K.P_SPIN_MOMENT, "spin_moment"), (K.P_FRICTION_NEEDLE, "friction_needle"),
    (K.P_ROLLING_RESISTANCE, "rolling_resistance")))
# the parameters the set-up reads beside those (kernel_params; needle_params), and those the
# roller's set-up does not read, with where they go
DERIVED_FROM = ("E", "nu", "l_needle", "n_needles", "roller_width", "step_tolerance",
                "running_clearance")
NEEDLE_ROW = ("n_spheres", "d_needle", "r_trunnion", "needle_circ_clearance", "rho_needle")
ELSEWHERE = {"n_rollers": "the joint (model.JointModel, lifecycle.py)",
             "drive_by_angle": "the step (lifecycle.step)",
             "spin_inertia": "the analytic model only: the contact model's roller always has "
                             "its spin inertia"}
(T_S, T_R_ROLLER, T_R_GROOVE, T_R_BORE, T_M_ROLLER, T_E, T_NU, T_MU_GROOVE, T_BEARING,
 T_N_NEEDLES, T_N_SPHERES, T_L_NEEDLE, T_D_NEEDLE, T_R_TRUNNION, T_NEEDLE_CLEARANCE,
 T_NEEDLE_CIRC_CLEARANCE, T_NEEDLE_AXIAL_CLEARANCE, T_RHO_NEEDLE, T_ROLLER_WIDTH, T_MU_NEEDLE, T_MU_ROLLING,
 T_FRICTION_NEEDLE, T_ROLLING_RESISTANCE, T_STEP_TOLERANCE, T_RUNNING_CLEARANCE, T_TRAVERSE,
 T_FRICTION_GROOVE, T_N_ROLLERS, T_DRIVE_BY_ANGLE, T_AXIAL, T_SPIDER) = map(_slot, (
    "s", "r_roller", "r_groove", "r_bore", "m_roller", "E", "nu", "mu_groove", "bearing",
    "n_needles", "n_spheres", "l_needle", "d_needle", "r_trunnion", "needle_clearance",
    "needle_circ_clearance", "needle_axial_clearance", "rho_needle", "roller_width", "mu_needle",
    "mu_rolling", "friction_needle", "rolling_resistance", "step_tolerance", "running_clearance",
    "traverse", "friction_groove", "n_rollers", "drive_by_angle", "axial", "spider"))


def kernel_params(T, P):
    """The roller's parameter vector P (layout.py) from the table's values T: the copies, the
    flags, and what the geometry derives (Hertz, Eqs. 13-15; the lumped needle row, Eq. 17 per
    needle summed over the loaded half of the row; the spin and tilt inertias).  The slots the
    operating point derives (oppoint.derive) are left at 0."""
    for j in range(K.P_LEN):
        P[j] = 0.0
    for slot, t in COPIED:
        P[slot] = T[t]
    for slot, t in FLAGS:
        P[slot] = 1.0 if T[t] != 0.0 else 0.0
    m, r, rb, l_n = T[T_M_ROLLER], T[T_R_ROLLER], T[T_R_BORE], T[T_L_NEEDLE]
    Kh, a1, _ = hertz_point(r, T[T_R_GROOVE], T[T_E], T[T_NU])
    P[K.P_K] = Kh
    P[K.P_A1] = a1
    P[K.P_IS] = spin_inertia(m, r, rb)   # thick ring
    # the row's load over the pressing offset with no clearance: needles at 2 pi j / n from the
    # pressing direction, the loaded half summed (two line contacts in series a needle): the
    # resolved row's substep and its slide's rate (oppoint.substep); the lumped row's law is
    # oppoint.row_sums, with the clearance
    n = int(T[T_N_NEEDLES])
    c1, k_row, q_sum = row_constants(n, l_n)
    P[K.P_KN] = k_row                        # F_r = K_row g^(10/9)
    P[K.P_QSUM] = q_sum                      # sum of needle loads / F_r
    P[K.P_NROW] = n
    P[K.P_KN1] = c1
    P[K.P_LT] = l_n * l_n / 12.0             # tilt = radial x l^2 / 12
    P[K.P_IT] = m * (3.0 * (r * r + rb * rb) + T[T_ROLLER_WIDTH] * T[T_ROLLER_WIDTH]) / 12.0
    tol = T[T_STEP_TOLERANCE]
    P[K.P_STEP_TOLERANCE] = tol if tol != 0.0 else (
        3e-3 if T[T_BEARING] == K.BEAR_RESOLVED else 1e-3)
    # each flank's arc centre off the track's mid-plane (0: one cylinder, the default)
    c = T[T_RUNNING_CLEARANCE]
    P[K.P_FLANK] = 0.5 * c - (T[T_R_GROOVE] - T[T_R_ROLLER]) if c > 0.0 else 0.0


# --- the needle-resolved row -------------------------------------------------------------------
def row_bore_radius(T):
    """Radius of the needles' outer race [m]: trunnion + needle diameter + the row's radial
    clearance (r_bore sets the roller's inertia; model.md's 12.5 mm leaves no clearance)."""
    return T[T_R_TRUNNION] + T[T_D_NEEDLE] + T[T_NEEDLE_CLEARANCE]


def neighbour_distance(T):
    """Centre distance [m] at which two neighbouring needles touch: the needle diameter, or
    less where n_needles of that diameter would over-fill the pitch circle without the row's
    circumferential play (model.md's 46 x 1.6 mm on 11.705 mm over-fill it by 0.11 mm); then
    the chord of equal spacing less the play shared out."""
    n = T[T_N_NEEDLES]
    Rp = T[T_R_TRUNNION] + 0.5 * T[T_D_NEEDLE] + 0.5 * T[T_NEEDLE_CLEARANCE]
    return min(T[T_D_NEEDLE], 2.0 * Rp * math.sin(math.pi / n) - T[T_NEEDLE_CIRC_CLEARANCE] / n)


def needle_params(T, NP):
    """The needle row's parameter vector NP (layout.py's N_ slots; needles.py)."""
    for j in range(K.N_LEN):
        NP[j] = 0.0
    ns = T[T_N_SPHERES]
    rn = 0.5 * T[T_D_NEEDLE]
    l_n = T[T_L_NEEDLE]
    NP[K.N_N] = T[T_N_NEEDLES]
    NP[K.N_NS] = ns
    NP[K.N_RN] = rn
    NP[K.N_RT] = T[T_R_TRUNNION]
    NP[K.N_RBR] = row_bore_radius(T)
    NP[K.N_LN] = l_n
    mn = T[T_RHO_NEEDLE] * math.pi * (rn * rn) * l_n
    NP[K.N_MN] = mn
    NP[K.N_I1] = mn * (3.0 * (rn * rn) + l_n * l_n) / 12.0   # cylinder, transverse
    NP[K.N_I3] = 0.5 * mn * (rn * rn)                        # about its axis
    NP[K.N_CS] = needle_line_stiffness(l_n) / ns   # Table 1: C = 8.15e4 l^(8/9) / N_s per sphere
    NP[K.N_DC] = neighbour_distance(T)
    NP[K.N_ZAX] = T[T_NEEDLE_AXIAL_CLEARANCE]
    NP[K.N_HW] = 0.5 * T[T_ROLLER_WIDTH]
    NP[K.N_MU] = T[T_MU_NEEDLE]
    NP[K.N_MUR] = T[T_MU_ROLLING]
    NP[K.N_FRIC] = 1.0 if T[T_FRICTION_NEEDLE] != 0.0 else 0.0
    NP[K.N_ROLLR] = 1.0 if T[T_ROLLING_RESISTANCE] != 0.0 else 0.0


def row_load(n, C_line, clearance, g):
    """The row's load [N] along the pressing direction with the roller g [m] off the trunnion
    axis against it: needle j at psi_j = 2 pi j / n squeezed by g cos(psi_j) - clearance
    across its two races in series, Eq. (17) on each."""
    total = 0.0
    for j in range(n):
        c = math.cos(2.0 * math.pi * j / n)
        ap = g * c - clearance
        if ap > 0.0:
            total += C_line * (0.5 * ap) ** (10.0 / 9.0) * c
    return total


def needle_radial_offset(n, l_needle, clearance, F):
    """Static x offset of the roller from the trunnion axis [m] under a radial load F [N] with
    the needles resolved: row_load(g) = |F| solved by bisection (it grows with g), against
    the load (negative in drive)."""
    C_line = needle_line_stiffness(l_needle)
    lo, hi = 0.0, clearance + 1e-3
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if row_load(n, C_line, clearance, mid) < abs(F):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi) if F < 0 else -0.5 * (lo + hi)


def radial_offset(P, T, F):
    """Static x offset of the roller from the trunnion axis [m] under a radial load F [N]:
    0 (ideal bearing), the lumped row's law, or the resolved row's (the same estimate starts
    it)."""
    if P[K.P_BEARING] == K.BEAR_IDEAL:
        return 0.0
    if P[K.P_BEARING] == K.BEAR_LUMPED:
        return lumped_offset(P, F)
    return needle_radial_offset(int(T[T_N_NEEDLES]), T[T_L_NEEDLE], T[T_NEEDLE_CLEARANCE], F)


def pressing_offset(P, T, F):
    """x position of the trunnion axis [m] that gives the pressing load F [N] with the roller at
    the groove bottom: the Hertz approach, less the needle row's static offset."""
    return groove_offset(P, F) - radial_offset(P, T, F)


def start_needles(Y, T, phase, theta, n, d0):
    """The n needles' state in Y: equally spaced from the pressing direction, each midway
    between trunnion and bore (equal approach on both races), rolling without slip on both
    races; the roller's offset Y[Y_E] and spin Y[Y_OM] already set, whirl angle phase [rad],
    d0 the trunnion's axial travel there [m] (contact.trunnion_axial)."""
    Rt, Rb = T[T_R_TRUNNION], row_bore_radius(T)
    rn = 0.5 * T[T_D_NEEDLE]
    E = Y[K.Y_E]
    om = Y[K.Y_OM]
    for j in range(n):
        psi = 2.0 * math.pi * j / n
        c, s = math.cos(psi), math.sin(psi)
        rho_b = E * c + math.sqrt(Rb * Rb - (E * s) * (E * s))   # bore surface along psi
        rho = 0.5 * (Rt + rho_b)
        vc = 0.5 * om * Rb
        q = K.Y_LEN + K.N_F * j
        for i in range(K.N_F):
            Y[q + i] = 0.0
        Y[q] = rho * c
        Y[q + 1] = rho * s
        Y[q + 2] = d0
        Y[q + 5] = -vc * s
        Y[q + 6] = vc * c
        Y[q + 10] = om * Rb / (2.0 * rn)


# --- the start ---------------------------------------------------------------------------------
def start_state(Y, P, T, phase, theta, omega, F):
    """The roller at whirl angle phase [rad] (0, 2 pi/3, 4 pi/3 in a joint) at the groove
    bottom, rolling without slip, its row loaded in equilibrium under F [N]: Y from zero."""
    for j in range(len(Y)):
        Y[j] = 0.0
    Y[K.Y_X] = phase
    T_ = math.tan(theta) if P[K.P_PITCH] != 0.0 else 0.0
    # dz/dt / r with z = s tan(phi), tan(phi) = T sin(x)
    c = math.cos(phase)
    sec2 = 1.0 + (T_ * math.sin(phase)) ** 2
    Y[K.Y_OM] = P[K.P_S] * T_ * c * omega / P[K.P_R_ROLLER] / math.sqrt(sec2)
    if F < 0:   # coast: the contact on the other side of the roller rolls it back
        Y[K.Y_OM] = -Y[K.Y_OM]
    Y[K.Y_E] = radial_offset(P, T, F)


def uses_table(T, omega, F):
    """Whether the traverse model's settled cycle places the roller at the start: ideal or
    lumped bearing, drive at forward whirl (F > 0, omega > 0), the slide free, groove friction
    with 0 < mu_groove < 1 (elsewhere it starts at the groove bottom, at rest along the
    trunnion)."""
    return (T[T_BEARING] != K.BEAR_RESOLVED and F > 0.0 and omega > 0.0
            and T[T_TRAVERSE] != 0.0 and T[T_FRICTION_GROOVE] != 0.0
            and 0.0 < T[T_MU_GROOVE] < 1.0)


DX = 1e-4   # whirl-angle step of p's slope [rad]: within one of the table's intervals


def tilt_and_rate(SS, PS, n, x, omega):
    """p [1] of the settled cycle (its table SS, PS of n intervals: reduced_model.table) at
    whirl angle x [rad], and its rate dp/dt [1/s]."""
    p = table_state_at(SS, PS, n, x)[1]
    slope = (table_state_at(SS, PS, n, x + DX)[1] - table_state_at(SS, PS, n, x - DX)[1]) / (
        2.0 * DX)
    return p, slope * omega


def slide_for_tilt(tilt, rate, D, ax, ay, adx, ady):
    """Slide u [m] of the roller centre along the trunnion axis a = (ax, ay) (its x and y
    components; adx, ady their rates [1/s]) that tilts the contact normal towards a by n.a =
    tilt [1], and u' [m/s] that keeps n.a on tilt's rate [1/s].  The centre is at (D + u ax,
    u ay) [m] from the facing flank's arc centre in the groove's cross-section
    (contact.groove_contact), so that u q = tilt rho - D ax with q = ax^2 + ay^2 and rho the
    centre's distance; a fixed point on rho, which the slide changes by its square only
    (|ax| << 1: 8 sweeps reach rounding), and that relation's time derivative, linear in u'."""
    q = ax * ax + ay * ay
    u = 0.0
    for _ in range(8):
        rho = math.hypot(D + u * ax, u * ay)
        u = (tilt * rho - D * ax) / q
    cx, cy = D + u * ax, u * ay
    rho = math.hypot(cx, cy)
    # d/dt: u' q + u q' = rate rho + tilt rho' - D ax', rho' = (cx cx' + cy cy') / rho
    # with cx' = u' ax + u ax', cy' = u' ay + u ay'
    qd = 2.0 * (ax * adx + ay * ady)
    coef = q - tilt * (cx * ax + cy * ay) / rho
    rhs = rate * rho + tilt * (cx * u * adx + cy * u * ady) / rho - D * adx - u * qd
    return u, rhs / coef


def slip_across(L, res):
    """The contact point's slip [m/s] across the trunnion axis: along b = a x n / |a x n|, the
    direction in which the spin about a moves the contact point (a the trunnion axis in L, n
    the contact normal and v_t the slip in res: contact.groove_contact).  The slip along a is
    the slide's."""
    ax, ay, az = L[K.L_AX], L[K.L_AY], L[K.L_AZ]
    nx, ny = res[K.R_NX], res[K.R_NY]
    bx, by, bz = -az * ny, az * nx, ax * ny - ay * nx
    return (res[K.R_VTX] * bx + res[K.R_VTY] * by + res[K.R_VTZ] * bz) / math.sqrt(
        bx * bx + by * by + bz * bz)


def rolling_spin(om0, v0, v1):
    """Spin [rad/s] at which the roller rolls without slip across the trunnion axis, from that
    slip v0 at spin om0 and v1 at om0 + 1 [m/s] (slip_across; linear in the spin); om0 where
    the spin moves no slip (the roller off its flank: a load too light to press it on)."""
    d = v1 - v0
    return om0 - v0 / d if d != 0.0 else om0


def place_on_cycle(Y, P, F, omega, SS, PS, n, probe, ctx):
    """Put the roller (its state Y at the start, at the groove bottom) where the settled cycle
    of the traverse model (SS, PS: reduced_model.table, n intervals) has it: the slide and its
    rate, and the spin at which it then rolls without slip across the trunnion axis, from the
    kernel's trunnion line and contact at that state.  probe(ctx) gives them, (L, res), at the
    state now without a step (the model's probe, or the compiled one: lifecycle.py).  F [N],
    omega [rad/s]: the start's."""
    L = probe(ctx)[0]
    tilt, rate = tilt_and_rate(SS, PS, n, Y[K.Y_X], omega)
    u, ud = slide_for_tilt(tilt, rate, groove_offset(P, F) - P[K.P_FLANK], L[K.L_AX],
                           L[K.L_AY], L[K.L_ADX], L[K.L_ADY])
    Y[K.Y_U] = u
    Y[K.Y_UD] = ud
    om0 = Y[K.Y_OM]
    L, res = probe(ctx)
    v0 = slip_across(L, res)
    Y[K.Y_OM] = om0 + 1.0
    L, res = probe(ctx)
    v1 = slip_across(L, res)
    Y[K.Y_OM] = rolling_spin(om0, v0, v1)
    if not (math.isfinite(Y[K.Y_U]) and math.isfinite(Y[K.Y_UD]) and math.isfinite(Y[K.Y_OM])):
        Y[K.Y_U] = 0.0   # the groove bottom, at rest
        Y[K.Y_UD] = 0.0
        Y[K.Y_OM] = om0


# what lifecycle.py compiles of this module, callees first
COMPILED = ("kernel_params", "row_bore_radius", "neighbour_distance", "needle_params",
            "row_load", "needle_radial_offset", "radial_offset", "pressing_offset",
            "start_needles", "start_state", "uses_table", "tilt_and_rate", "slide_for_tilt",
            "slip_across", "rolling_spin", "place_on_cycle")
