"""A powertrain on its mounts, driving one tripod joint through a vehicle launch.

Vehicle frame (ISO 8855): x forward, y left, z up.  The powertrain is transverse; its
crankshaft and the left half-shaft's inboard (tripod) joint run along y.  Its rigid-body
motion about the static equilibrium, small: u = (u_x, u_y, u_z) [m] of the centre of gravity
and the roll rho [rad] about the crankshaft axis (+y) through it; each on a linear mount
(rate k, damping c, expressed at the centre of gravity, uncoupled).  The launch is the
vehicle's: a half-shaft torque rising from creep to a launch level, the wheels accelerating
the vehicle's mass.  Equations in docs/driveline-example.md, written once in mounts.py (the
Python model here and the FMU's compiled binary run them).  SI units throughout.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from reduced_model.scene import DEG, Param

from . import mounts as M



def _param(*args, **kw) -> Param:
    return Param(*args, models=frozenset({"powertrain"}), **kw)


PARAMS: tuple[Param, ...] = (
    _param("mass", 180.0, "kg", 0.0, 5000.0, "powertrain mass (engine and gearbox)", lo_open=True),
    _param("J_roll", 8.0, "kg.m2", 0.0, 1000.0,
           "powertrain roll inertia about the crankshaft axis (+y) through its centre of gravity",
           lo_open=True),
    _param("k_x", 4.5e5, "N/m", 0.0, 1e9, "mount rate fore-aft (x): 8.0 Hz with the default mass",
           lo_open=True),
    _param("k_y", 1.0e6, "N/m", 0.0, 1e9, "mount rate lateral (y, along the crankshaft and the "
           "joint's axis): 11.9 Hz", lo_open=True),
    _param("k_z", 7.0e5, "N/m", 0.0, 1e9, "mount rate vertical (z): 9.9 Hz", lo_open=True),
    _param("k_roll", 5.0e4, "N.m/rad", 0.0, 1e8, "mount rate in roll: 12.6 Hz", lo_open=True),
    _param("c_x", 1250.0, "N.s/m", 0.0, 1e7, "mount damping fore-aft (7 % of critical)"),
    _param("c_y", 1900.0, "N.s/m", 0.0, 1e7, "mount damping lateral (7 % of critical)"),
    _param("c_z", 1570.0, "N.s/m", 0.0, 1e7, "mount damping vertical (7 % of critical)"),
    _param("c_roll", 90.0, "N.m.s/rad", 0.0, 1e6, "mount damping in roll (7 % of critical)"),
    _param("joint_x", 0.0, "m", -2.0, 2.0, "joint centre relative to the centre of gravity, x"),
    _param("joint_y", 0.30, "m", -2.0, 2.0, "joint centre relative to the centre of gravity, y"),
    _param("joint_z", -0.15, "m", -2.0, 2.0, "joint centre relative to the centre of gravity, z"),
    _param("shaft_length", 0.6, "m", 0.05, 5.0,
           "half-shaft: joint centre to the wheel-side joint's centre (fixed to the body)"),
    _param("theta0", 10 * DEG, "rad", 0.0, 40 * DEG,
           "joint angle at rest: the shaft falls from the joint to the wheel in the y-z plane",
           display_unit="deg"),
    _param("n_shafts", 2, "1", 1, 4, "driven half-shafts, each carrying the launch torque",
           kind="int"),
    _param("vehicle_mass", 1500.0, "kg", 0.0, 1e5, "vehicle mass the launch accelerates",
           lo_open=True),
    _param("wheel_radius", 0.30, "m", 0.0, 2.0, "rolling radius of the driven wheels",
           lo_open=True),
    _param("torque_creep", 100.0, "N.m", 0.0, 6000.0, "half-shaft torque at the start (creep)"),
    _param("torque_launch", 1200.0, "N.m", 0.0, 6000.0, "half-shaft torque at launch"),
    _param("torque_rise_time", 0.5, "s", 0.0, 100.0,
           "time the half-shaft torque takes from creep to launch (a linear rise)"),
)
# inputs: the joint's forces on its housing (the joint FMU's outputs of the same names)
_F = 1e7     # far above any joint's force: a bound that refuses nonsense, not physics
INPUTS: tuple[Param, ...] = (
    _param("Fz_joint", 0.0, "N", -_F, _F, "axial force of the joint on its housing (along +y, "
           "the housing axis)", causality="input"),
    _param("F_housing_x", 0.0, "N", -_F, _F, "radial force of the joint on its housing along "
           "the housing's X", causality="input"),
    _param("F_housing_y", 0.0, "N", -_F, _F, "radial force of the joint on its housing along "
           "the housing's Y", causality="input"),
    _param("whirl_angle", 0.0, "rad", -1e9, 1e9, "the joint's whirl angle: the housing's X is "
           "at this angle from +z about +y", causality="input"),
)
TABLE = INPUTS + PARAMS
BY_NAME = {p.name: p for p in TABLE}
# outputs: what the joint takes (theta, omega, torque, plunge_speed: its inputs' names)
OUTPUTS = (
    ("theta", "rad", "joint angle: between the housing axis (+y) and the half-shaft"),
    ("plunge_speed", "m/s", "speed of the spider along the housing axis, > 0 toward the wheel"),
    ("omega", "rad/s", "wheel (whirl) speed"),
    ("torque", "N.m", "half-shaft torque"),
    ("plunge", "m", "the spider's travel along the housing axis from rest (geometric)"),
    ("acc_x", "m/s2", "powertrain acceleration fore-aft at its centre of gravity"),
    ("acc_y", "m/s2", "powertrain lateral acceleration at its centre of gravity (along the "
     "crankshaft and the joint's axis)"),
    ("acc_z", "m/s2", "powertrain vertical acceleration at its centre of gravity"),
    ("disp_y", "m", "powertrain lateral displacement at its centre of gravity"),
    ("roll", "rad", "powertrain roll about the crankshaft axis"),
)


def defaults() -> dict:
    return {p.name: p.default for p in TABLE}


def params_array(values: dict) -> np.ndarray:
    """The parameters (PARAMS' names) as mounts.py's T."""
    return np.array([float(values[p.name]) for p in PARAMS])


def launch_torque(t, p) -> float:
    """Half-shaft torque [N m] at time t [s] (mounts.launch_torque); p: the parameters."""
    return M.launch_torque(params_array(p), t)


def wheel_speed(t, p) -> float:
    """Wheel speed [rad/s] at time t [s] from standstill (mounts.wheel_speed)."""
    return M.wheel_speed(params_array(p), t)


housing_force = M.housing_force


@dataclass(frozen=True)
class JointKinematics:
    """The joint's angle [rad], plunge [m] and plunge speed [m/s] from the powertrain's motion."""
    theta: float
    plunge: float
    plunge_speed: float


def joint_kinematics(q, v, p) -> JointKinematics:
    """mounts.joint_kinematics at q = (u, rho) [m, rad] and v = dq/dt."""
    return JointKinematics(*M.joint_kinematics(params_array(p), np.concatenate([q, v])))


class Mounts:
    """The powertrain on its mounts, M q'' + C q' + K q = Q, stepped exactly for a force Q held
    over the step (mounts.mounts_step: the transition computed once per step size)."""

    def __init__(self, p):
        self.T = params_array(p)
        self.W = np.zeros(M.W_LEN)

    def step(self, x, Q, h):
        """The state x = (q, v) [m, rad, m/s, rad/s] after h [s] under Q held."""
        x = np.array(x, dtype=float)
        M.mounts_step(self.T, x, [float(f) for f in Q], self.W, h)
        return x


class PowertrainModel:
    """The powertrain FMU's model (mounts.init, mounts.step): the mounts' state x = (q, v), 8
    floats, and the outputs at time t [s] from the joint's forces held over each step."""

    def __init__(self, values: dict):
        """values: every parameter and the inputs at the start (TABLE's names)."""
        self.p = dict(values)
        self.T = params_array(values)
        self.IN = np.array([float(values[p.name]) for p in INPUTS])
        self.x = np.zeros(M.X_LEN)
        self.OUT = np.zeros(M.OUT_LEN)
        self.W = np.zeros(M.W_LEN)
        rc = M.init(self.T, self.IN, self.x, self.OUT, self.W)
        if rc < 0:
            name = PARAMS[-rc - 1].name
            raise ValueError(f"{name} = {self.p[name]!r} is too small to compute with; "
                             f"allowed range {BY_NAME[name].range_text()}")
        if rc != 1:
            raise ValueError("the start's outputs are not finite")

    def outputs(self) -> dict:
        return {name: float(v) for (name, _, _), v in zip(OUTPUTS, self.OUT)}

    def step(self, t, h, joint: dict) -> dict:
        """Advance from t to t + h [s] with the joint's forces held; the outputs at t + h (NaN
        where the step's are not finite: the slave refuses it)."""
        for i, p in enumerate(INPUTS):
            self.IN[i] = joint[p.name]
        if M.step(self.T, self.IN, self.x, self.OUT, self.W, t, h) != 1:
            return {name: math.nan for name, _, _ in OUTPUTS}
        return self.outputs()


def native_layout() -> dict:
    """Where each variable lives in mounts.py's arrays, the arrays' sizes and the order the
    variables are checked in at initialisation (TABLE's, as the slave checks them): for the FMU
    whose binary runs mounts.py compiled (fmu_src/native_fmu.py)."""
    arrays = {p.name: ("IN_IN", i) for i, p in enumerate(INPUTS)}
    arrays.update({p.name: ("IN_T", i) for i, p in enumerate(PARAMS)})
    arrays.update({name: ("IN_OUT", i) for i, (name, _, _) in enumerate(OUTPUTS)})
    return {"by_name": BY_NAME, "arrays": arrays, "check_order": [p.name for p in TABLE],
            "sizes": {"T": M.T_LEN, "IN": M.IN_LEN, "X": M.X_LEN, "OUT": M.OUT_LEN,
                      "W": M.W_LEN, "TH": 2}}
