"""The powertrain's equations as scalar functions over flat arrays: one source for the Python
model (powertrain.PowertrainModel) and the Powertrain FMU's binary, which compiles `init` and
`step` ahead of time (c_functions, fmu_src/aot.py) and runs them without Python.

Arrays (float64): T the parameters in powertrain.PARAMS' order (integers as floats), IN the
inputs in INPUTS' order, X the mounts' state (q = u_x, u_y, u_z [m], rho [rad]; then their
rates), OUT the outputs in OUTPUTS' order, W the step's transition for the step size W[0]
(per degree of freedom Phi, 2 x 2 row by row, and Gamma, 2), TH (t, h) [s].  Equations:
docs/driveline-example.md.  Both run with IEEE arithmetic (a division by zero or a negative
root gives inf or NaN, which the step reports as a non-finite output).
"""
import math

from reduced_model.cfuncs import finite_into

# slots of T: powertrain.PARAMS' order (tests/test_example.py checks it)
(MASS, J_ROLL, K_X, K_Y, K_Z, K_ROLL, C_X, C_Y, C_Z, C_ROLL, JOINT_X, JOINT_Y, JOINT_Z,
 SHAFT_LENGTH, THETA0, N_SHAFTS, VEHICLE_MASS, WHEEL_RADIUS, TORQUE_CREEP, TORQUE_LAUNCH,
 TORQUE_RISE_TIME, T_LEN) = range(22)
# of IN (INPUTS' order) and OUT (OUTPUTS' order)
(FZ_JOINT, F_HOUSING_X, F_HOUSING_Y, WHIRL_ANGLE, IN_LEN) = range(5)
(THETA, PLUNGE_SPEED, OMEGA, TORQUE, PLUNGE, ACC_X, ACC_Y, ACC_Z, DISP_Y, ROLL,
 OUT_LEN) = range(11)
X_LEN = 8
W_LEN = 1 + 4 * 6
# parameters divided by: each must square above this (init's refusal)
DIVISORS = (MASS, J_ROLL, VEHICLE_MASS, WHEEL_RADIUS)
TAYLOR_TERMS = 18


def launch_torque(T, t):
    """Half-shaft torque [N m] at time t [s]: creep, rising linearly to the launch level."""
    T0, T1, tr = T[TORQUE_CREEP], T[TORQUE_LAUNCH], T[TORQUE_RISE_TIME]
    return T1 if t >= tr else T0 + (T1 - T0) * t / tr


def wheel_speed(T, t):
    """Wheel speed [rad/s] at time t [s] from standstill: n_shafts T(t) accelerates the vehicle
    through its wheels, (m r^2) dw/dt = n T (no slip, no resistance), integrated exactly."""
    T0, T1, tr = T[TORQUE_CREEP], T[TORQUE_LAUNCH], T[TORQUE_RISE_TIME]
    if t < tr:
        impulse = T0 * t + (T1 - T0) * t * t / (2 * tr)
    else:
        impulse = T0 * tr + (T1 - T0) * tr / 2 + T1 * (t - tr)
    r = T[WHEEL_RADIUS]
    return T[N_SHAFTS] * impulse / (T[VEHICLE_MASS] * (r * r))


def housing_force(Fz, Fhx, Fhy, psi):
    """The joint's force on its housing in the vehicle frame [N] (x, y, z).  Housing Z = +y;
    its X, fixed to the housing, turns about +y with the whirl angle psi [rad] from +z:
    X = (sin psi, 0, cos psi), Y = Z x X = (cos psi, 0, -sin psi)."""
    s, c = math.sin(psi), math.cos(psi)
    return Fhx * s + Fhy * c, Fz, Fhx * c - Fhy * s


def generalised_force(T, F, torque):
    """Forces on (u_x, u_y, u_z) [N] and the moment on the roll [N m] of the joint's force F at
    the joint centre r = (joint_x, joint_y, joint_z) and of the launch torque's reaction
    -n_shafts torque about +y (the case takes the reaction of what it drives)."""
    rx, rz = T[JOINT_X], T[JOINT_Z]
    return F[0], F[1], F[2], rz * F[0] - rx * F[2] - T[N_SHAFTS] * torque


def load(T, IN, t):
    """The generalised force at time t [s] of the joint's forces IN and the launch torque's
    reaction."""
    F = housing_force(IN[FZ_JOINT], IN[F_HOUSING_X], IN[F_HOUSING_Y], IN[WHIRL_ANGLE])
    return generalised_force(T, F, launch_torque(T, t))


def joint_kinematics(T, X):
    """(theta [rad], plunge [m], plunge speed [m/s]) of the joint from the powertrain's motion
    X.  The half-shaft is a rigid link of length L from the spider to the wheel-side joint W,
    fixed to the body at L (0, cos theta0, -sin theta0) from the joint centre at rest.  The
    joint centre moves with the powertrain, d_J = u + rho e_y x r; the spider stays on the
    housing axis at plunge p from it: |W - J - p e_y| = L gives p = d_y - sqrt(L^2 - d_x^2 -
    d_z^2) and theta = asin(sqrt(d_x^2 + d_z^2) / L), d = W - J."""
    L, th0 = T[SHAFT_LENGTH], T[THETA0]
    rx, rz = T[JOINT_X], T[JOINT_Z]
    djx, djy, djz = X[0] + X[3] * rz, X[1], X[2] - X[3] * rx
    vjx, vjy, vjz = X[4] + X[7] * rz, X[5], X[6] - X[7] * rx
    dx, dy, dz = -djx, L * math.cos(th0) - djy, -L * math.sin(th0) - djz
    S2 = L * L - dx * dx - dz * dz
    S = math.sqrt(S2) if S2 >= 0.0 else math.nan
    plunge_speed = -vjy + (dx * -vjx + dz * -vjz) / S
    sin_theta = math.sqrt(dx * dx + dz * dz) / L
    theta = math.asin(sin_theta) if sin_theta <= 1.0 else math.nan
    return theta, dy - S, plunge_speed


def dof(T, i):
    """(a, b, minv) of degree of freedom i (u_x, u_y, u_z, roll): q'' = -a q - b q' + minv Q,
    the mount's rate and damping over the mass (the roll's over the roll inertia)."""
    minv = 1.0 / (T[J_ROLL] if i == 3 else T[MASS])
    return minv * T[K_X + i], minv * T[C_X + i], minv


def transition(a, b, minv, h):
    """The exact step over h [s] of q'' = -a q - b q' + minv Q with Q held (zero-order hold):
    (Phi row by row, Gamma) = the blocks of exp(h [[0, 1, 0], [-a, -b, minv], [0, 0, 0]]),
    by scaling and squaring (the matrix over 2^s down to a norm of 1/2) and its Taylor series
    to TAYLOR_TERMS terms (the rest below 1e-21)."""
    s = 0
    hs = h
    norm = h * max(1.0, a + b + minv)
    while norm > 0.5:
        norm *= 0.5
        hs *= 0.5
        s += 1
    f01, f10, f11, g1 = hs, -a * hs, -b * hs, minv * hs   # F = [[0, f01], [f10, f11]], g = (0, g1)
    t00, t01, t10, t11 = 1.0, 0.0, 0.0, 1.0               # F^(k-1) / (k-1)!
    p00, p01, p10, p11 = 1.0, 0.0, 0.0, 1.0
    g0 = gg1 = 0.0
    for k in range(1, TAYLOR_TERMS + 1):
        g0 += t01 * g1 / k                                 # Gamma += F^(k-1) g / k!
        gg1 += t11 * g1 / k
        t00, t01, t10, t11 = (t01 * f10 / k, (t00 * f01 + t01 * f11) / k,
                              t11 * f10 / k, (t10 * f01 + t11 * f11) / k)
        p00 += t00
        p01 += t01
        p10 += t10
        p11 += t11
    for _ in range(s):     # [[Phi, Gamma], [0, 1]]^2 = [[Phi Phi, Phi Gamma + Gamma], [0, 1]]
        g0, gg1 = p00 * g0 + p01 * gg1 + g0, p10 * g0 + p11 * gg1 + gg1
        p00, p01, p10, p11 = (p00 * p00 + p01 * p10, p00 * p01 + p01 * p11,
                              p10 * p00 + p11 * p10, p10 * p01 + p11 * p11)
    return p00, p01, p10, p11, g0, gg1


def transitions(T, W, h):
    """W holds each degree of freedom's transition for the step h [s] (computed when h is not
    the one it holds)."""
    if W[0] == h:
        return
    for i in range(4):
        a, b, minv = dof(T, i)
        E = transition(a, b, minv, h)
        for j in range(6):
            W[1 + 6 * i + j] = E[j]
    W[0] = h


def mounts_step(T, X, Q, W, h):
    """The mounts' state X after h [s] under the generalised force Q held: M q'' + C q' + K q
    = Q, stepped exactly, each degree of freedom on its own (the mounts are uncoupled)."""
    transitions(T, W, h)
    for i in range(4):
        o = 1 + 6 * i
        q, v = X[i], X[4 + i]
        X[i] = W[o] * q + W[o + 1] * v + W[o + 4] * Q[i]
        X[4 + i] = W[o + 2] * q + W[o + 3] * v + W[o + 5] * Q[i]


def acceleration(T, X, Q, i):
    """q''_i [m/s2, rad/s2] at the state X under Q."""
    a, b, minv = dof(T, i)
    return minv * (Q[i] - T[C_X + i] * X[4 + i] - T[K_X + i] * X[i])


def outputs(T, X, Q, t, OUT):
    """The outputs at time t [s] with the mounts at X under Q, into OUT when every one is
    finite.  Returns 1, or 2 (a non-finite output; OUT untouched)."""
    theta, plunge, plunge_speed = joint_kinematics(T, X)
    return finite_into((theta, plunge_speed, wheel_speed(T, t), launch_torque(T, t), plunge,
                        acceleration(T, X, Q, 0), acceleration(T, X, Q, 1),
                        acceleration(T, X, Q, 2), X[1], X[3]), OUT)


def init(T, IN, X, OUT, W):
    """The start: the mounts at rest, W empty, the outputs at t = 0.  Returns 1; 2 for a
    non-finite output; -(1 + slot) for a parameter of DIVISORS too small to divide by."""
    for i in DIVISORS:
        if not T[i] * T[i] > 1e-300:
            return -(1 + i)
    for i in range(X_LEN):
        X[i] = 0.0
    for i in range(W_LEN):
        W[i] = 0.0
    return outputs(T, X, load(T, IN, 0.0), 0.0, OUT)


def step(T, IN, X, OUT, W, t, h):
    """From t to t + h [s] with the joint's forces IN held; the outputs at t + h.  Returns 1, or
    2 for a non-finite output (the state has moved; OUT untouched)."""
    Q = load(T, IN, t)
    mounts_step(T, X, Q, W, h)
    return outputs(T, X, Q, t + h, OUT)


# the functions the FMU's binary compiles (c_functions), callees first
COMPILED = ("finite_into", "launch_torque", "wheel_speed", "housing_force", "generalised_force",
            "load", "joint_kinematics", "dof", "transition", "transitions", "mounts_step",
            "acceleration", "outputs", "init", "step")


def c_functions():
    """init and step as the native layer's C functions (reduced_model/cfuncs.py; numba, IEEE
    arithmetic: error_model numpy), for fmu_src/aot.py."""
    import types

    import numba as nb

    from reduced_model.cfuncs import c_functions as wrap

    g = dict(globals())     # compiled copies: this module's functions stay plain Python
    for name in COMPILED:
        f = g[name]
        g[name] = nb.njit(error_model="numpy")(
            types.FunctionType(f.__code__, g, f.__name__, f.__defaults__, f.__closure__))
    return wrap(g, (T_LEN, IN_LEN, X_LEN, OUT_LEN, W_LEN))
