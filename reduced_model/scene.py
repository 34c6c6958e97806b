"""The parameter table: every scene and model parameter declared once.

Each entry gives name, default, SI unit, allowed range, description, type, FMI causality and
which models use it.  The CLI options, the FMU variables and the docs are generated from
``PARAMS``; ``validate`` checks a scene against it and names the offending parameter.
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field

DEG = math.pi / 180.0


@dataclass(frozen=True)
class Param:
    name: str
    default: float | int | bool
    unit: str                   # SI unit, "1" for dimensionless
    lo: float | None            # lower bound (None = unbounded)
    hi: float | None            # upper bound (None = unbounded)
    description: str
    kind: str = "real"          # real | int | bool
    causality: str = "parameter"  # parameter | input (FMI)
    models: frozenset = field(default_factory=lambda: frozenset({"analytic", "contact"}))
    hi_open: bool = False       # True: hi itself is excluded
    lo_open: bool = False
    display_unit: str | None = None  # FMI displayUnit, e.g. "deg"
    # 0 means "automatic"; any other value must be at least this (below it the model would
    # step for hours: a bound FMI's min/max cannot state, checked here)
    auto_or_min: float | None = None

    def range_text(self) -> str:
        if self.kind == "bool":
            return "true or false"
        if self.auto_or_min is not None:
            u = "" if self.unit == "1" else f" {self.unit}"
            return f"0 (automatic) or [{_fmt(self.auto_or_min, self)}, {_fmt(self.hi, self)}]{u}"
        lo = "-inf" if self.lo is None else _fmt(self.lo, self)
        hi = "inf" if self.hi is None else _fmt(self.hi, self)
        lb = "(" if (self.lo_open or self.lo is None) else "["
        rb = ")" if (self.hi_open or self.hi is None) else "]"
        u = "" if self.unit == "1" else f" {self.unit}"
        return f"{lb}{lo}, {hi}{rb}{u}"


def _fmt(v: float, p: Param) -> str:
    if p.unit == "rad" and v != 0:
        return f"{v:.6g} ({v / DEG:.6g} deg)"
    return f"{v:.6g}"


_A = frozenset({"analytic", "contact"})
_C = frozenset({"contact"})
_R = frozenset({"analytic"})

# the values `bearing` and `integrator` take, named once (tripod_model/layout.py hands them to
# the kernel as BEAR_* and INT_*; everything else compares against these names)
BEARING_IDEAL, BEARING_LUMPED, BEARING_RESOLVED = 0, 1, 2
(INTEGRATOR_EULER, INTEGRATOR_EXTRAPOLATED, INTEGRATOR_EXPLICIT, INTEGRATOR_ADAPTIVE,
 INTEGRATOR_DEFAULT) = range(5)
SPIDER_PRESCRIBED, SPIDER_FREE = range(2)

PARAMS: tuple[Param, ...] = (
    # --- scene: the paper's test conditions (section 3.1) ---
    Param("theta", 10 * DEG, "rad", 0.0, 45 * DEG, "joint angle", causality="input",
          hi_open=True, display_unit="deg"),
    Param("omega", 20 * math.pi, "rad/s", -1.0e4, 1.0e4,
          "whirl angular speed of the output shaft (< 0: reverse)", causality="input"),
    # (upper bounds: twice a launch's 50 kN per roller; above, the lumped bearing's stiff
    # contact needs ever smaller substeps: 0.45 s a 1e-4 s step at 1 MN with three rollers)
    Param("F_press", 1000.0, "N", -1.0e5, 1.0e5,
          "pressing load of the roller on the groove (< 0: coast, on the other flank)",
          causality="input"),
    Param("torque", 0.0, "N.m", -6.0e3, 6.0e3,
          "transmitted torque (< 0: coast); when not 0 it sets the pressing load per roller, "
          "torque/(3 s), instead of F_press", causality="input"),
    Param("plunge_speed", 0.0, "m/s", -1.0, 1.0,
          "speed of the spider along the housing axis (the groove direction z; > 0 along +z): "
          "the trunnions' travel along the groove gets it, so the thrust includes the "
          "plunging resistance", causality="input"),
    Param("shaft_angle", 0.0, "rad", -1.0e9, 1.0e9,
          "with drive_by_angle: the whirl (shaft) angle the master wants at the end of this "
          "step; omega over the step is then (shaft_angle - whirl_angle) / dt",
          causality="input"),
    Param("drive_by_angle", False, "1", None, None,
          "drive the whirl by the input shaft_angle instead of omega (a master that "
          "integrates the shaft angle itself)", kind="bool"),
    Param("n_rollers", 1, "1", 1, 3, "rollers simulated: 1, or 3 at whirl phases 0/120/240 deg",
          kind="int"),
    Param("mu_groove", 0.055, "1", 0.0, 1.0, "sliding friction coefficient roller-groove "
          "(the analytic traverse model needs it below 1)"),
    Param("v_st", 0.0, "m/s", 0.0, 10.0,
          "transition velocity of the tanh friction law; 0 = automatic, sqrt(A^2+B^2)/4",
          auto_or_min=1e-5),
    Param("pitch", True, "1", None, None, "pitching motion acts, Eq. (1)", kind="bool"),
    Param("yaw", True, "1", None, None, "yawing motion acts, Eq. (3)", kind="bool"),
    Param("roll", True, "1", None, None, "rolling motion acts, Eq. (5)", kind="bool"),
    Param("axial", True, "1", None, None, "axial trunnion displacement acts, Eq. (7)", kind="bool"),
    # --- geometry (model.md, assumed: the paper publishes none) ---
    Param("s", 0.022, "m", 0.0, 1.0, "spider centre to roller centre (pitch circle radius)",
          lo_open=True),
    Param("r_roller", 0.019, "m", 0.0, 1.0, "roller outer sphere radius", lo_open=True),
    Param("r_groove", 0.0192, "m", 0.0, 1.0, "groove radius (must exceed r_roller)", lo_open=True),
    Param("r_bore", 0.0125, "m", 0.0, 1.0, "roller bore radius (must be below r_roller)",
          lo_open=True),
    Param("m_roller", 0.060, "kg", 0.0, 100.0, "roller mass", lo_open=True),
    Param("spin_inertia", True, "1", None, None,
          "add the roller spin-inertia thrust (I_spin/r^2) d2z/dt2", kind="bool", models=_A),
    # --- contact model only ---
    Param("mu_needle", 0.050, "1", 0.0, 1.0, "sliding friction coefficient needle-roller/trunnion",
          models=_A),
    Param("mu_rolling", 0.002, "1", 0.0, 0.1, "rolling friction coefficient of the needles, Eq. (12)",
          models=_A),
    Param("bearing", BEARING_IDEAL, "1", BEARING_IDEAL, BEARING_RESOLVED,
          "needle bearing: 0 ideal, 1 lumped, 2 every needle resolved", kind="int", models=_C),
    Param("traverse", True, "1", None, None,
          "roller free along the trunnion axis (contact point traverses the groove); in the "
          "analytic model: the reduced traverse model (false: Eqs. 18-27 alone)",
          kind="bool", models=_A),
    Param("needle_row", True, "1", None, None,
          "traverse model: the needle row's friction (the needles' sliding friction and rolling "
          "resistance) and the roller's rocking on the row (docs/model.md); false: an ideal "
          "bearing, the roller free along the trunnion", kind="bool", models=_R),
    Param("friction_groove", True, "1", None, None, "roller-groove sliding friction on",
          kind="bool", models=_C),
    Param("spin_moment", True, "1", None, None, "roller-groove spin moment Eq. (16) on",
          kind="bool", models=_A),
    Param("friction_needle", True, "1", None, None,
          "needle sliding friction on (lumped and resolved bearing, the analytic model's row)",
          kind="bool", models=_A),
    Param("rolling_resistance", True, "1", None, None, "needle rolling resistance Eq. (12) on",
          kind="bool", models=_A),
    Param("max_substep", 0.0, "s", 0.0, 1.0e-2,
          "largest internal integration substep; 0 = automatic from a stability estimate",
          models=_C, auto_or_min=1e-7),
    Param("integrator", INTEGRATOR_DEFAULT, "1", INTEGRATOR_EULER, INTEGRATOR_DEFAULT,
          "4 (default) generalized-alpha (implicit, Newton) with the ideal and lumped "
          "bearings, linearly implicit BDF2 with the roller and the needle row in one "
          "system with the needle-resolved bearing, 3 linearly implicit Euler extrapolated to 2nd "
          "order (Richardson) with the substep set by its own error estimate "
          "(step_tolerance), 1 the same at the fixed "
          "automatic substep, 0 linearly implicit Euler, 2 explicit (symplectic) Euler for "
          "comparison", kind="int", models=_C),
    Param("newton_passes", 2, "1", 1, 4,
          "needle-resolved bearing, integrator 4: the most linear solves of each BDF2 substep, "
          "each after the first linearized at the state the one before reached (Newton) and "
          "made only where the one before moved the velocities by more than newton_tol (a "
          "pass that would move them more than the one before is refused); 1 = linearly "
          "implicit, at a 27 % shorter substep (docs/integrators.md)",
          kind="int", models=_C),
    Param("newton_tol", 3e-4, "m/s", 0.0, 1.0,
          "needle-resolved bearing with newton_passes > 1: a Newton pass is the last where its "
          "correction (root sum of squares over the roller's and the needles' velocities, "
          "rotations times their radius) is at most this; 0 = every pass",
          models=_C),
    Param("step_tolerance", 0.0, "1", 0.0, 1.0,
          "integrator 3: largest error of one substep in the roller's slip velocities, as a "
          "fraction of v_st; 0 = automatic: 1e-3, or 3e-3 with bearing 2 (the split step's "
          "needle row moves order 3 by about 1 % anyway)", models=_C, auto_or_min=1e-6),
    Param("E", 206e9, "Pa", 1e9, 1e12, "Young's modulus of roller and groove", models=_A),
    Param("nu", 0.3, "1", 0.0, 0.5, "Poisson's ratio", hi_open=True, models=_A),
    Param("r_trunnion", 0.0109, "m", 0.0, 1.0, "trunnion radius", lo_open=True, models=_C),
    Param("d_needle", 0.0016, "m", 0.0, 0.1, "needle diameter", lo_open=True, models=_C),
    Param("l_needle", 0.012, "m", 0.0, 0.1, "needle length", lo_open=True, models=_A),
    Param("n_spheres", 7, "1", 1, 50, "spheres per needle (contact discretisation, Fig. 10)",
          kind="int", models=_C),
    Param("needle_clearance", 1e-5, "m", 0.0, 1e-3, "radial clearance of the needle row",
          models=_A),
    Param("n_needles", 46, "1", 3, 200, "number of needles in the row", kind="int", models=_A),
    Param("needle_circ_clearance", 5e-5, "m", 0.0, 1e-2,
          "circumferential play of the needle row, summed over the row (resolved bearing)",
          models=_C),
    Param("needle_axial_clearance", 1e-4, "m", 0.0, 1e-2,
          "axial play of each needle between trunnion flange and retainer, either way "
          "(resolved bearing; the lumped row's and the analytic row's needles lag the "
          "trunnion's stroke within it)", models=_A),
    Param("rho_needle", 7850.0, "kg/m3", 0.0, 1e5, "density of the needles (steel)",
          lo_open=True, models=_C),
    Param("roller_width", 0.013, "m", 0.0, 0.1, "roller width", lo_open=True, models=_C),
    Param("row_damping", 0.2, "1", 0.0, 1.0,
          "lumped bearing: damping ratio of the roller's modes on the needle row (radial, "
          "across the load, tilt), the lumped form of the resolved row's needle-contact "
          "damping", models=_C),
    Param("contact_damping", 0.0, "s/m", 0.0, 10.0,
          "Hunt-Crossley damping of the roller-groove contact: f_n = K delta^1.5 (1 + 1.5 "
          "contact_damping d delta/dt), never pulling; 0 = the paper's law (no damping)",
          models=_C),
    Param("running_clearance", 0.0, "m", 0.0, 0.01,
          "flank-to-flank play of the track with the roller centred: the flanks are two arcs "
          "of radius r_groove, running_clearance / 2 - (r_groove - r_roller) off the track's "
          "mid-plane; 0 = from the geometry, 2 (r_groove - r_roller) (one cylinder, the "
          "paper's groove); below that the roller would touch both flanks (refused)",
          models=_C),
    # --- the whole joint (docs/model.md, "The floating spider") ---
    Param("spider", SPIDER_PRESCRIBED, "1", SPIDER_PRESCRIBED, SPIDER_FREE,
          "0 prescribed: each trunnion moves on Eqs. (1)-(8) and each roller is pressed by "
          "torque / (3 s) (the paper's); 1 free: the spider's centre and twist come from the "
          "three rollers' forces and the input torque (n_rollers = 3, bearing 0 or 1)",
          kind="int", models=_C),
    Param("spider_mass", 0.32, "kg", 0.0, 100.0,
          "spider = 1: mass moving with the spider's centre across the shaft (the spider with "
          "its trunnions, and any share of the intermediate shaft)", lo_open=True, models=_C),
    Param("spider_inertia", 8.5e-5, "kg.m2", 0.0, 10.0,
          "spider = 1: moment of inertia of the spider about the shaft axis", lo_open=True,
          models=_C),
    Param("tolerance", 0.0, "1", 0.0, 0.1,
          "the relative error of the thrust's orders the generalized-alpha substep (integrator "
          "4, ideal and lumped bearing) is set for: the automatic substep times "
          "sqrt(tolerance / 7.5e-3), at most 4 times it; 0 = the host's tolerance "
          "(fmi2SetupExperiment) where it gives one, else the automatic substep",
          models=_C, auto_or_min=1e-6),
)

BY_NAME = {p.name: p for p in PARAMS}

# Outputs of the FMUs: name, SI unit, description (same names in both FMUs where they exist).
OUTPUTS = (
    ("Fx", "N", "pressing force of the roller on the groove"),
    ("Fy", "N", "lateral force on the groove, along the trunnion axis"),
    ("Fz", "N", "thrust: force on the groove along the groove (shaft) axis"),
    ("Fz_mod", "N", "modified thrust Fz' = Fz F_press / Fx (section 3.2)"),
    ("dFx", "N", "pressing force change Fx - F_press"),
    ("contact_y", "m", "contact point on the groove across the groove (trunnion-axis direction)"),
    ("contact_z", "m", "contact point on the groove along the groove"),
    ("slip_speed", "m/s", "sliding speed of the roller on the groove at the contact"),
    ("roller_spin", "rad/s", "absolute spin rate of the roller about the trunnion axis"),
    ("Fz_joint", "N", "housing axial force: sum of Fz over the rollers (= Fz with n_rollers = 1)"),
    ("Fz_2", "N", "thrust of roller 2 (whirl phase 120 deg; 0 with n_rollers = 1)"),
    ("Fz_3", "N", "thrust of roller 3 (whirl phase 240 deg; 0 with n_rollers = 1)"),
    ("whirl_angle", "rad", "whirl angle of roller 1 the trunnion motions use: the integral of "
     "omega as held over each communication step, 0 at the start (for order tracking)"),
    # the other rollers and the joint on the housing (housing.py gives the housing frame)
    ("Fx_2", "N", "pressing force of roller 2 on its groove (0 with n_rollers = 1)"),
    ("Fy_2", "N", "lateral force of roller 2 on its groove, along its trunnion axis"),
    ("contact_y_2", "m", "contact point of roller 2 across its groove"),
    ("contact_z_2", "m", "contact point of roller 2 along its groove"),
    ("Fx_3", "N", "pressing force of roller 3 on its groove (0 with n_rollers = 1)"),
    ("Fy_3", "N", "lateral force of roller 3 on its groove, along its trunnion axis"),
    ("contact_y_3", "m", "contact point of roller 3 across its groove"),
    ("contact_z_3", "m", "contact point of roller 3 along its groove"),
    ("F_housing_x", "N", "radial force of the joint on the housing along X, the housing frame's "
     "axis through groove 1 (fixed to the housing; grooves 2, 3 at 120, 240 deg)"),
    ("F_housing_y", "N", "radial force of the joint on the housing along Y = Z x X"),
    ("T_housing", "N.m", "torque of the rollers on the housing about the shaft axis, positive "
     "in the drive sense: sum of each roller's pressing force times its contact radius"),
    ("F_roller", "N", "pressing load per roller in use: torque / (3 s) when torque is not 0, else "
     "F_press"),
    ("plunge", "m", "the spider's travel along the housing axis: the integral of plunge_speed "
     "as held over each communication step, 0 at the start"),
    ("spider_x", "m", "the spider centre's position along the housing's X (spider = 0: Eq. "
     "(5)'s orbit, e (cos 2x, sin 2x) at roller 1's whirl angle x; 1: from the forces)"),
    ("spider_y", "m", "the spider centre's position along the housing's Y"),
    ("F_roller_1", "N", "pressing load roller 1's trunnion carries (spider = 0: F_roller; 1: "
     "from the spider's balance)"),
    ("F_roller_2", "N", "pressing load roller 2's trunnion carries (0 with n_rollers = 1)"),
    ("F_roller_3", "N", "pressing load roller 3's trunnion carries (0 with n_rollers = 1)"),
)
# the outputs the contact model has and the analytic model does not (no contact point there)
CONTACT_ONLY_OUTPUTS = ("contact_y", "contact_z", "roller_spin", "contact_y_2", "contact_z_2",
                        "contact_y_3", "contact_z_3",
                        "spider_x", "spider_y", "F_roller_1", "F_roller_2", "F_roller_3")


# Integer outputs: name, description, the FMU that has it.
REGIME_CODES = ("full slip", "traverse", "micro-slip")
INT_OUTPUTS = (
    ("regime", "which theory holds at the start's operating point (reduced traverse model): "
               "0 full slip (Eqs. 18-27 within 5 %), 1 traverse, 2 micro-slip", "analytic"),
)


def params_for(model: str) -> tuple[Param, ...]:
    """The parameters a model ('analytic' or 'contact') uses, in table order."""
    return tuple(p for p in PARAMS if model in p.models)


def defaults(model: str = "analytic") -> dict:
    return {p.name: p.default for p in params_for(model)}


def pressing_load(F_press: float, torque: float, s: float) -> float:
    """Pressing load per roller [N]: torque / (3 s) when a torque [N m] is given (not 0: it
    wins; < 0 coast), else F_press (< 0 coast).  s [m] is the pitch-circle radius."""
    return torque / (3.0 * s) if torque != 0 else F_press


def load_text(scene: dict) -> str:
    """The pressing load in use, for headers and titles: from the torque when one is given
    (F_press is then unused), else F_press."""
    tq = scene.get("torque", 0.0)
    if tq != 0:
        F = pressing_load(scene["F_press"], tq, scene["s"])
        return f"pressing load = {F:.6g} N per roller (torque {tq:.6g} N m / (3 s); F_press unused)"
    return f"F_press = {scene['F_press']:.6g} N"


STEP_ROUNDING = 64 * sys.float_info.epsilon


class StepRefused(RuntimeError):
    """A step the model cannot finish within its budget (its message says what ran out and
    where): the FMU refuses it (fmi2Discard) with that message."""


# The most substeps one communication step may take, in either FMU (about a second of work):
# a longer step is refused before it starts (too_long); both kernels compile this number
# (tests/test_budget.py checks it)
MAX_SUBSTEPS = float(2 ** 20)


# The refusal of a communication step of dt [s] in substeps of h [s] above MAX_SUBSTEPS: a
# printf format (the FMUs' binaries word it alike)
TOO_LONG = ("the communication step of %.4g s in substeps of %.3g s needs more than "
            f"the {MAX_SUBSTEPS:.0f} substeps one step may take: take shorter communication "
            "steps")


def too_long(dt, h) -> str:
    """The refusal of a communication step of dt [s] in substeps of h [s] (TOO_LONG)."""
    return TOO_LONG % (dt, h)


def same_step(dt, dt0, t):
    """Whether a communication step of dt [s] at time t [s] is the step dt0 up to the rounding
    a master's t_{k+1} - t_k carries (FMPy: a few ulps of t): within 64 ulps of max(|t|, dt0).
    Both FMUs then take the step dt0 (the contact model reuses dt0's operating point; the
    analytic FMU's kernel and the contact FMU's lifecycle compile this function), so the
    compiled FMUs and their functions run as Python take the same steps."""
    return abs(dt - dt0) <= STEP_ROUNDING * max(abs(t), dt0)


def same_value(a, b):
    """Whether input values a and b differ only by rounding (within 64 ulps of the larger): a
    master's interpolation of a constant stretch of an input table moves its last bits.  Never
    for a non-finite value (inf - inf is no rounding: such an input is refused, not kept)."""
    return math.isfinite(a) and math.isfinite(b) and \
        abs(a - b) <= STEP_ROUNDING * max(abs(a), abs(b))


_TRUE = {"1", "true", "yes", "on"}
_FALSE = {"0", "false", "no", "off"}


def parse_value(name: str, text: str):
    """Parse a textual value (as given by ``--set NAME=VALUE``) for parameter ``name``."""
    return parse_param(_param(name), text)


def parse_param(p: Param, text: str):
    """Parse a textual value for the parameter ``p`` (any table's)."""
    name = p.name
    t = str(text).strip().lower()
    if p.kind == "bool":
        if t in _TRUE:
            return True
        if t in _FALSE:
            return False
        raise ValueError(f"{name}: '{text}' is not a boolean; allowed: true or false (1/0)")
    try:
        v = float(t)
    except ValueError:
        raise ValueError(f"{name}: '{text}' is not a number; allowed range {p.range_text()}") from None
    if p.kind == "int":
        if not math.isfinite(v) or v != int(v):
            raise ValueError(f"{name}: '{text}' is not an integer; allowed range {p.range_text()}")
        return int(v)
    return v


def _param(name: str) -> Param:
    try:
        return BY_NAME[name]
    except KeyError:
        raise ValueError(f"unknown parameter '{name}'; known: {', '.join(BY_NAME)}") from None


def check_value(name: str, value) -> None:
    """Raise ValueError naming ``name`` and its allowed range if ``value`` is outside it."""
    check_param(_param(name), value)


def check_param(p: Param, value) -> None:
    """Raise ValueError naming the parameter ``p`` and its allowed range if ``value`` is
    outside it (any table's Param: the joint's here, the powertrain's in driveline/)."""
    name = p.name
    if p.kind == "bool":
        if not isinstance(value, (bool, int)) or int(value) not in (0, 1):
            raise ValueError(f"{name} = {value!r}: allowed {p.range_text()}")
        return
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} is not a number; allowed range {p.range_text()}") from None
    bad = not math.isfinite(v)
    if not bad and p.lo is not None:
        bad = v <= p.lo if p.lo_open else v < p.lo
    if not bad and p.hi is not None:
        bad = v >= p.hi if p.hi_open else v > p.hi
    if not bad and p.auto_or_min is not None:
        bad = 0.0 < v < p.auto_or_min
    if not bad and v != 0.0 and abs(v) < sys.float_info.min:   # no physical value: refused
        raise ValueError(f"{name} = {v!r} is subnormal (below {sys.float_info.min:.4g} in "
                         f"magnitude): give 0 or a value in {p.range_text()}")
    if bad:
        raise ValueError(f"{name} = {value!r} is outside the allowed range {p.range_text()}"
                         + _thousandth_hint(p, v))


# (the unit a value given a thousand times too large was likely meant in)
_SMALLER_UNIT = {"m": "millimetres", "kg": "grams"}


def _thousandth_hint(p: Param, v: float) -> str:
    """For a length or mass refused as too large where a thousandth of it is allowed: the
    likely unit mistake, named (empty otherwise)."""
    if p.unit not in _SMALLER_UNIT or p.hi is None or not math.isfinite(v) or v <= p.hi:
        return ""
    try:
        check_param(p, v / 1000.0)
    except ValueError:
        return ""
    return f": {_SMALLER_UNIT[p.unit]}? the unit is {p.unit} ({p.name} = {v / 1000.0:g} {p.unit})"


# A roller's density [kg/m3] from its mass and its ring (r_roller, r_bore, roller_width): a
# value outside this is a unit mistake more likely than a material (magnesium 1740 kg/m3 to
# tungsten carbide 15600, with room for a ring that is not a plain cylinder)
ROLLER_DENSITY = (1000.0, 30000.0)


def roller_density(scene: dict) -> float:
    """The roller's mean density [kg/m3]: m_roller over the ring between r_bore and r_roller,
    roller_width wide (the contact model's; the analytic model's scene has none: the paper's
    width scaled with r_roller)."""
    w = scene.get("roller_width")
    if w is None:
        d = defaults("contact")
        w = d["roller_width"] * scene["r_roller"] / d["r_roller"]
    return scene["m_roller"] / (math.pi * (scene["r_roller"] ** 2 - scene["r_bore"] ** 2) * w)


def check_roller_mass(scene: dict) -> None:
    """Raise ValueError where m_roller, against the roller's size, is no metal's (a density
    outside ROLLER_DENSITY), naming the likely unit mistake."""
    rho, (lo, hi) = roller_density(scene), ROLLER_DENSITY
    if lo <= rho <= hi:
        return
    hint = " grams?" if lo <= rho / 1000.0 <= hi else ""
    width = (f", roller_width {scene['roller_width']:g} m" if "roller_width" in scene else "")
    raise ValueError(f"m_roller = {scene['m_roller']:g} kg is a density of {rho:.2g} kg/m3 for "
                     f"this roller (r_roller {scene['r_roller']:g} m, r_bore "
                     f"{scene['r_bore']:g} m{width}; steel is about 7800 kg/m3):{hint} allowed "
                     f"{lo:g}-{hi:g} kg/m3 for its size")


def check_drive(scene: dict, what: str) -> None:
    """Raise ValueError naming the input when ``what`` (a report of the closed forms over
    whirl cycles) is asked for coast (a negative pressing load) or reverse whirl (a negative
    omega): both FMUs take those, the reports cover drive at forward whirl."""
    F = pressing_load(scene["F_press"], scene.get("torque", 0.0), scene["s"])
    for name, bad in (("omega", scene["omega"] < 0), ("torque", scene.get("torque", 0.0) < 0),
                      ("F_press", F < 0)):
        if bad:
            raise ValueError(f"{name} = {scene[name]:g}: {what} covers drive at forward whirl "
                             "(omega, torque, F_press >= 0); coast and reverse whirl: run the "
                             "FMUs or tripod-thrust compare, which take them")


def check_traverse_mu(mu: float) -> None:
    """The reduced traverse model needs mu_groove < 1: the friction it balances tilts the
    contact normal by asin(mu_groove), 90 deg at 1.  Raise ValueError naming the range."""
    if mu >= 1.0:
        raise ValueError(f"mu_groove = {mu:g}: the traverse model needs mu_groove < 1 (the "
                         "friction it balances tilts the contact normal by asin(mu_groove)); "
                         "allowed range [0, 1) (or traverse = false)")


# The relations between parameters the table's ranges cannot state (validate), as printf
# formats of the values they name (the FMUs' binaries word them alike)
RELATIONS = {
    "groove": "r_groove = %g m must exceed r_roller = %g m (range (r_roller, 1] m)",
    "running_clearance": "running_clearance = %g m is below 2 (r_groove - r_roller) = %g m, "
                         "where the roller would touch both flanks (range 0 (from the "
                         "geometry) or [%g, 0.01] m)",
    "n_rollers": "n_rollers = %.0f is not allowed; allowed: 1 or 3",
    "bore": "r_bore = %g m must be below r_roller = %g m (range (0, r_roller) m)",
    "spider": "spider = 1 (free) needs n_rollers = 3 and bearing 0 or 1 (the needle-resolved "
              "row is not coupled to a floating spider); got n_rollers = %.0f, bearing = %.0f",
    "row_mu": "mu_groove + 1.5 mu_needle = %g: the traverse model with the needle row needs it "
              "below 1 (the groove's and the row's friction tilt the contact normal by their "
              "sum, the row's at most 1.5 mu_needle F); lower mu_groove or mu_needle (or "
              "needle_row = false)",
}
# the needle row's friction over the pressing load is at most mu_needle q / F, q / F at most 1.3
# (Eq. 17 over the row: 1.27 without clearance, less with it): with this margin the normal's
# tilt p in the traverse model stays below mu_groove + ROW_MU mu_needle
ROW_MU = 1.5


def analytic_counterpart(contact: dict) -> dict:
    """The analytic model's values for a contact scene (its overrides or a validated scene):
    the names both models take, and the analytic model's needle row where the contact model
    has one (needle_row = true with the lumped or the needle-resolved row, false with the ideal
    bearing, unless the values name needle_row themselves): what the cross-check runs the
    analytic model with."""
    out = {k: v for k, v in contact.items() if "analytic" in BY_NAME[k].models}
    out.setdefault("needle_row",
                   int(contact.get("bearing", BY_NAME["bearing"].default)) != BEARING_IDEAL)
    return out


def validate(overrides: dict | None = None, model: str = "analytic") -> dict:
    """A complete scene for ``model``: defaults updated by ``overrides``, every value checked.

    Raises ValueError that names the parameter and its allowed range.
    """
    scene = defaults(model)
    for name, value in (overrides or {}).items():
        p = _param(name)
        if model not in p.models:
            raise ValueError(f"parameter '{name}' does not apply to the {model} model")
        scene[name] = value
    for name, value in scene.items():
        check_value(name, value)
        p = BY_NAME[name]
        scene[name] = bool(value) if p.kind == "bool" else int(value) if p.kind == "int" else float(value)
    if scene["r_groove"] <= scene["r_roller"]:
        raise ValueError(RELATIONS["groove"] % (scene["r_groove"], scene["r_roller"]))
    c, c0 = scene.get("running_clearance", 0.0), 2.0 * (scene["r_groove"] - scene["r_roller"])
    if c != 0.0 and c < c0:
        raise ValueError(RELATIONS["running_clearance"] % (c, c0, c0))
    if scene.get("n_rollers", 1) not in (1, 3):
        raise ValueError(RELATIONS["n_rollers"] % scene["n_rollers"])
    if model == "analytic" and scene["traverse"]:
        check_traverse_mu(scene["mu_groove"])
        if scene["needle_row"] and scene["mu_groove"] + ROW_MU * scene["mu_needle"] >= 1.0:
            raise ValueError(RELATIONS["row_mu"] % (scene["mu_groove"]
                                                    + ROW_MU * scene["mu_needle"]))
    if scene["r_bore"] >= scene["r_roller"]:
        raise ValueError(RELATIONS["bore"] % (scene["r_bore"], scene["r_roller"]))
    check_roller_mass(scene)
    if scene.get("spider", SPIDER_PRESCRIBED) == SPIDER_FREE and (
            scene["n_rollers"] != 3 or scene["bearing"] == BEARING_RESOLVED):
        raise ValueError(RELATIONS["spider"] % (scene["n_rollers"], scene["bearing"]))
    return scene
