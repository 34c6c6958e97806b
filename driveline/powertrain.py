"""A powertrain on its mounts, driving one tripod joint through a vehicle launch.

Vehicle frame (ISO 8855): x forward, y left, z up.  The powertrain is transverse; its
crankshaft and the left half-shaft's inboard (tripod) joint run along y.  Its rigid-body
motion about the static equilibrium, small: u = (u_x, u_y, u_z) [m] of the centre of gravity
and the roll rho [rad] about the crankshaft axis (+y) through it; each on a linear mount
(rate k, damping c, expressed at the centre of gravity, uncoupled).  The launch is the
vehicle's: a half-shaft torque rising from creep to a launch level, the wheels accelerating
the vehicle's mass.  Equations in docs/driveline-example.md.  SI units throughout.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from reduced_model.scene import DEG, Param



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


def launch_torque(t, p) -> float:
    """Half-shaft torque [N m] at time t [s]: creep, rising linearly to the launch level."""
    T0, T1, tr = p["torque_creep"], p["torque_launch"], p["torque_rise_time"]
    return T1 if t >= tr else T0 + (T1 - T0) * t / tr


def wheel_speed(t, p) -> float:
    """Wheel speed [rad/s] at time t [s] from standstill: n_shafts T(t) accelerates the vehicle
    through its wheels, (m r^2) dw/dt = n T (no slip, no resistance), integrated exactly."""
    T0, T1, tr = p["torque_creep"], p["torque_launch"], p["torque_rise_time"]
    if t < tr:
        impulse = T0 * t + (T1 - T0) * t * t / (2 * tr)
    else:
        impulse = T0 * tr + (T1 - T0) * tr / 2 + T1 * (t - tr)
    return p["n_shafts"] * impulse / (p["vehicle_mass"] * p["wheel_radius"] ** 2)


def housing_force(Fz, Fhx, Fhy, psi):
    """The joint's force on its housing in the vehicle frame [N] (x, y, z).  Housing Z = +y;
    its X, fixed to the housing, turns about +y with the whirl angle psi [rad] from +z:
    X = (sin psi, 0, cos psi), Y = Z x X = (cos psi, 0, -sin psi)."""
    s, c = math.sin(psi), math.cos(psi)
    return (Fhx * s + Fhy * c, Fz, Fhx * c - Fhy * s)


def generalised_force(F, p, torque):
    """Forces on (u_x, u_y, u_z) [N] and the moment on the roll [N m] of the joint's force F at
    the joint centre r = (joint_x, joint_y, joint_z) and of the launch torque's reaction
    -n_shafts torque about +y (the case takes the reaction of what it drives)."""
    rx, rz = p["joint_x"], p["joint_z"]
    return np.array([F[0], F[1], F[2], rz * F[0] - rx * F[2] - p["n_shafts"] * torque])


@dataclass(frozen=True)
class JointKinematics:
    """The joint's angle [rad], plunge [m] and plunge speed [m/s] from the powertrain's motion."""
    theta: float
    plunge: float
    plunge_speed: float


def joint_kinematics(q, v, p) -> JointKinematics:
    """The half-shaft is a rigid link of length L from the spider to the wheel-side joint W,
    fixed to the body at L (0, cos theta0, -sin theta0) from the joint centre at rest.  The
    joint centre moves with the powertrain, d_J = u + rho e_y x r; the spider stays on the
    housing axis at plunge p from it: |W - J - p e_y| = L gives p = d_y - sqrt(L^2 - d_x^2 -
    d_z^2) and theta = asin(sqrt(d_x^2 + d_z^2) / L), d = W - J.  q = (u, rho), v = dq/dt."""
    L, th0 = p["shaft_length"], p["theta0"]
    rx, rz = p["joint_x"], p["joint_z"]
    dj = (q[0] + q[3] * rz, q[1], q[2] - q[3] * rx)
    vj = (v[0] + v[3] * rz, v[1], v[2] - v[3] * rx)
    dx, dy, dz = -dj[0], L * math.cos(th0) - dj[1], -L * math.sin(th0) - dj[2]
    S = math.sqrt(L * L - dx * dx - dz * dz)
    plunge_speed = -vj[1] + (dx * -vj[0] + dz * -vj[2]) / S
    return JointKinematics(math.asin(math.hypot(dx, dz) / L), dy - S, plunge_speed)


class Mounts:
    """The powertrain on its mounts, M q'' + C q' + K q = Q, stepped exactly for a force Q held
    over the step (zero-order hold: state transition from the matrix exponential, computed
    once per step size)."""

    def __init__(self, p):
        m, J = p["mass"], p["J_roll"]
        self.minv = np.array([1 / m, 1 / m, 1 / m, 1 / J])
        self.k = np.array([p["k_x"], p["k_y"], p["k_z"], p["k_roll"]])
        self.c = np.array([p["c_x"], p["c_y"], p["c_z"], p["c_roll"]])
        self._steps = {}

    def _matrices(self, h):
        if h not in self._steps:
            from scipy.linalg import expm
            A = np.zeros((12, 12))      # [[A, B], [0, 0]] for the state (q, v) and Q
            A[0:4, 4:8] = np.eye(4)
            A[4:8, 0:4] = -np.diag(self.minv * self.k)
            A[4:8, 4:8] = -np.diag(self.minv * self.c)
            A[4:8, 8:12] = np.diag(self.minv)
            E = expm(A * h)
            self._steps = {h: (E[0:8, 0:8].copy(), E[0:8, 8:12].copy())}   # one step size kept
        return self._steps[h]

    def step(self, x, Q, h):
        """The state x = (q, v) [m, rad, m/s, rad/s] after h [s] under Q held."""
        Phi, Gamma = self._matrices(h)
        return Phi @ x + Gamma @ Q

    def acceleration(self, x, Q):
        """q'' [m/s2, rad/s2] at the state x under Q."""
        return self.minv * (Q - self.c * x[4:8] - self.k * x[0:4])


class PowertrainModel:
    """The powertrain FMU's model: the mounts' state x = (q, v), 8 floats, and the outputs at
    time t [s] from the joint's forces held over each step."""

    def __init__(self, values: dict):
        self.p = dict(values)
        for name in ("mass", "J_roll", "vehicle_mass", "wheel_radius"):   # divided by
            if not self.p[name] ** 2 > 1e-300:
                raise ValueError(f"{name} = {self.p[name]!r} is too small to compute with; "
                                 f"allowed range {BY_NAME[name].range_text()}")
        self.mounts = Mounts(self.p)
        self.x = np.zeros(8)

    def outputs(self, t, Q) -> dict:
        """Every output at time t with the mounts at x under the generalised force Q."""
        q, v = self.x[0:4], self.x[4:8]
        kin = joint_kinematics(q, v, self.p)
        a = self.mounts.acceleration(self.x, Q)
        return {"theta": kin.theta, "plunge_speed": kin.plunge_speed,
                "omega": wheel_speed(t, self.p), "torque": launch_torque(t, self.p),
                "plunge": kin.plunge, "acc_x": float(a[0]), "acc_y": float(a[1]),
                "acc_z": float(a[2]), "disp_y": float(q[1]), "roll": float(q[3])}

    def load(self, t, joint: dict):
        """The generalised force at time t of the joint's forces (INPUTS' names) and the launch
        torque's reaction."""
        F = housing_force(joint["Fz_joint"], joint["F_housing_x"], joint["F_housing_y"],
                          joint["whirl_angle"])
        return generalised_force(F, self.p, launch_torque(t, self.p))

    def step(self, t, h, joint: dict) -> dict:
        """Advance from t to t + h [s] with the joint's forces held; the outputs at t + h."""
        with np.errstate(all="ignore"):     # a non-finite result is refused by the slave
            Q = self.load(t, joint)
            self.x = self.mounts.step(self.x, Q, h)
            return self.outputs(t + h, Q)
