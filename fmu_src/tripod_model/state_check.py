"""The bounds a contact model's state must keep to be stepped: checked when a host sets a state
(the FMU's fmi2SetFMUstate: host_state.state_problem calls these functions), beyond its
format.  Scalar Python.

The bounds come from the scene, each far outside what a run reaches (benchmarks/step_budget.py
and tests/test_budget.py measure both):
- every value finite (the inputs' key may be NaN: no step taken yet);
- the roller on its trunnion: its slide u within half the needle length of the row's middle
  (beyond it the roller is off its needles; runs reach about 1e-4 m of the default's 6 mm);
- with the lumped bearing, the roller's radial offsets within the needle diameter (the row's
  thickness: beyond it the trunnion would pass through the needles; runs reach 5e-5 m of
  1.6 mm) and its tilts within the angle that takes half a needle across the row's thickness;
- speeds within SPEED_MARGIN x the fastest the driven motion makes at the state's inputs:
  (s + r_roller) |omega| (1 + tan theta) + |plunge speed|, at least 1 m/s (runs reach a tenth
  of it), the spin and tilt rates within that over the bore radius;
- the whirl angle within the shaft angle's range; the history's substep within 0-1 s, the
  transition velocity within its parameter's range.
"""
import math


from reduced_model.scene import BY_NAME
from . import layout as K

SPEED_MARGIN = 10.0
WHIRL_HI = BY_NAME["shaft_angle"].hi + 2.0 * math.pi   # a state's whirl angle [rad]
VST_HI = BY_NAME["v_st"].hi                             # a state's transition velocity [m/s]
def speed_limit(s, r_roller, theta, omega, vp):
    """The fastest a roller's point may move [m/s] at joint angle theta [rad] (at most pi/4
    counted), whirl omega [rad/s] and plunge speed vp [m/s] on a joint of trunnion offset s and
    roller radius r_roller [m] (module docstring).  Scalar: the compiled state check
    (host_state.roller_problem) compiles it."""
    kin = ((s + r_roller) * abs(omega) * (1.0 + abs(math.tan(min(abs(theta), math.pi / 4.0))))
           + abs(vp))
    return SPEED_MARGIN * max(kin, 1.0)


def speed_bound(p: dict, theta: float, omega: float, vp: float) -> float:
    """speed_limit [m/s] for the parameters p."""
    return speed_limit(p["s"], p["r_roller"], theta, omega, vp)


def history_bound(vst, hs):
    """0 when a roller's transition velocity vst [m/s] and its integrators' history hs can be
    stepped, else the first that cannot: 1 vst outside (0, VST_HI], 2 the carried substep
    hs[H_SUB] outside [0, 1] s, 3 the restart's weight hs[H_JUMPW] outside [0, 1], 4 a negative
    count of substeps taken.  NaN is outside.  Scalar: the compiled state check
    (host_state.roller_problem) compiles it."""
    if not 0.0 < vst <= VST_HI:
        return 1
    if not 0.0 <= hs[K.H_SUB] <= 1.0:
        return 2
    if not 0.0 <= hs[K.H_JUMPW] <= 1.0:
        return 3
    if not hs[K.H_TAKEN] >= 0.0:
        return 4
    return 0


def roller_bound(Y, row, l_needle, d_needle, r_roller, r_bore, v):
    """The first value of a roller's state Y beyond its bound (module docstring): (code of
    fmu_arrays.STATE_PROBLEMS, its index in Y, the bound), (0, -1, 0.0) when
    every one is within.  row: the bearing has a row (not the ideal one); l_needle, d_needle,
    r_roller, r_bore [m]; v: speed_limit [m/s].  NaN is beyond.  Scalar: the compiled state
    check (host_state.roller_problem) compiles it."""
    if not abs(Y[K.Y_X]) <= WHIRL_HI:
        return 5, K.Y_X, WHIRL_HI
    if not abs(Y[K.Y_U]) <= 0.5 * l_needle:
        return 6, K.Y_U, 0.5 * l_needle
    if not abs(Y[K.Y_UD]) <= v:
        return 7, K.Y_UD, v
    if not abs(Y[K.Y_OM]) <= v / r_roller:
        return 7, K.Y_OM, v / r_roller
    if row:
        tilt = math.atan(d_needle / (0.5 * l_needle))
        for i in (K.Y_E, K.Y_W):
            if not abs(Y[i]) <= d_needle:
                return 8, i, d_needle
        for i in (K.Y_B1, K.Y_B2):
            if not abs(Y[i]) <= tilt:
                return 8, i, tilt
        for i in (K.Y_ED, K.Y_WD):
            if not abs(Y[i]) <= v:
                return 7, i, v
        for i in (K.Y_B1D, K.Y_B2D):
            if not abs(Y[i]) <= v / r_bore:
                return 7, i, v / r_bore
    return 0, -1, 0.0


def spider_bounds(qx, qy, psi, vx, vy, vpsi, s, r_groove, kin):
    """0 when a free spider's coordinates (layout.OP_SP_*) can be stepped, 9 otherwise
    (fmu_arrays.STATE_PROBLEMS): its centre within r_groove [m] of its kinematic pose (beyond,
    a trunnion would pass through its groove's flank), its twist within r_groove / s [rad], its
    speeds within SPEED_MARGIN times max(kin, 1 m/s), kin = s |omega| [m/s] (the twist's over
    s).  Runs reach micrometres and the clearance's twist (about 1e-2 rad).  Scalar: the
    compiled FMU's state check (host_state.spider_problem) compiles it."""
    vb = SPEED_MARGIN * max(kin, 1.0)
    if not (abs(qx) <= r_groove and abs(qy) <= r_groove and abs(psi) <= r_groove / s):
        return 9
    if not (abs(vx) <= vb and abs(vy) <= vb and abs(vpsi) <= vb / s):
        return 9
    return 0
