"""Peers of the contact FMU on the same roller, for `tripod-thrust bench --peer`.

scipy's solve_ivp is what a Python user writes first: the roller's equations of the ideal
bearing with traverse (slide u along the trunnion axis, its rate, the spin rate; the whirl
angle w t drives the trunnion), the right-hand side the kernel's own compiled force evaluation
(genalpha.ga_forces: Hertz contact, tanh friction, spin moment, driving accelerations), so the
two differ only in how they integrate.  Outputs Fz' at the communication instants from the
dense solution, like the FMU's.

Exudyn (optional extra `peer`) is a general multibody engine: it builds the roller's equations
itself from rigid bodies and joints, so only the contact law is shared (exudyn_run).
"""
from __future__ import annotations

import math
import time

import numpy as np

from reduced_model.thrust import fz_mod
from tripod_model import contact, genalpha, layout as LY
from tripod_model.model import ContactModel


def solve_ivp_run(method: str = "LSODA", rtol: float = 1e-6, params=None, cycles: float = 2.0,
                  dt_out: float = 1e-4):
    """``cycles`` whirl cycles of the scene (ideal bearing, traverse) by scipy.integrate.solve_ivp.

    rtol: solve_ivp's relative tolerance; atol is rtol x v_st [m/s] on the slide's rate and
    rtol x v_st / r [rad/s] on the spin (the friction's velocity scale) and rtol x 1 um on the
    slide.  Returns (t [s], Fz' [N], {"nfev", "status"}, wall time of solve_ivp [s]).
    """
    from scipy.integrate import solve_ivp
    m = ContactModel(dict(params or {}, bearing=0))
    p = m.p
    theta, w, F = float(p["theta"]), float(p["omega"]), float(p["F_press"])
    m.start(theta, w, F)
    vst = m.v_st(theta, w)
    m.P[LY.P_VST_OP] = vst
    x0 = m.pressing_offset(F)
    Y, P, L, res, Q, M = m.Y.copy(), m.P, m._L, m._res, m._b, m._GW[LY.W_M]
    xs = Y[LY.Y_X]
    drive = LY.Drive(theta, w, x0, 0.0)

    def rhs(t, y):
        Y[LY.Y_X] = xs + w * t
        Y[LY.Y_U], Y[LY.Y_UD], Y[LY.Y_OM] = y
        genalpha.ga_forces(Y, P, drive, L, res, Q, M)
        return (y[1], Q[0] / M[0], Q[1] / M[1])

    n_out = int(round(cycles * 2 * math.pi / w / dt_out))
    t_eval = dt_out * np.arange(1, n_out + 1)
    y0 = (Y[LY.Y_U], Y[LY.Y_UD], Y[LY.Y_OM])
    atol = rtol * np.array([1e-6, vst, vst / p["r_roller"]])
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, t_eval[-1]), y0, method=method, t_eval=t_eval, rtol=rtol,
                    atol=atol)
    wall = time.perf_counter() - t0
    out = np.full(n_out, np.nan)
    for k in range(sol.y.shape[1]):
        Y[LY.Y_X] = xs + w * sol.t[k]
        Y[LY.Y_U], Y[LY.Y_UD], Y[LY.Y_OM] = sol.y[:, k]
        genalpha.ga_forces(Y, P, drive, L, res, Q, M)
        out[k] = fz_mod(-res[LY.R_FX], -res[LY.R_FZ], F)
    return t_eval, out, {"nfev": sol.nfev, "status": sol.status}, wall


def exudyn_run(h: float, params=None, cycles: float = 2.0, dt_out: float = 1e-4,
               spectral_radius: float = 0.9):
    """``cycles`` whirl cycles of the scene (ideal bearing) in Exudyn, at a fixed step h [s].

    The engine's own multibody model, not the kernel's equations of motion: the trunnion is a
    rigid body driven along the kernel's trunnion motion (trunnion_line: Eqs. 1, 5, 18; its
    axis a through Q) by a generic joint with time offsets; the roller a rigid body (mass m,
    inertia I_t, I_t, I_s) on it by a cylindrical joint (slide along a free with traverse, spin
    about a free): the ideal needle bearing.  The groove's Hertz force, tanh friction and spin
    moment (contact.groove_contact) act on the roller as user loads, Python callbacks at each
    evaluation.  Exudyn's generalized-alpha (index 3, spectral radius 0.9), Newton with a
    numerical system Jacobian; a step whose Newton iteration fails is cut by the engine.
    Returns (t [s], Fz' [N], {"steps", "extra_steps"}, wall time of the solve [s]).
    """
    import exudyn as exu

    m = ContactModel(dict(params or {}, bearing=0))
    p = m.p
    theta, w, F = float(p["theta"]), float(p["omega"]), float(p["F_press"])
    m.start(theta, w, F)
    m.P[LY.P_VST_OP] = m.v_st(theta, w)
    mbs = exu.SystemContainer().AddSystem()
    sensors = _exudyn_roller(mbs, m, _TrunnionMotion(m, theta, w, m.pressing_offset(F)))
    mbs.Assemble()
    T = cycles * 2 * math.pi / w
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = T
    ss.timeIntegration.numberOfSteps = int(round(T / h))
    ss.timeIntegration.verboseMode = 0
    ss.timeIntegration.generalizedAlpha.spectralRadius = spectral_radius
    ss.timeIntegration.newton.numericalDifferentiation.doSystemWideDifferentiation = True
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = 0.0   # every step
    exu.config.printToConsole = False   # its note on the user functions' allocations
    try:
        t0 = time.perf_counter()
        ok = mbs.SolveDynamic(ss)
        wall = time.perf_counter() - t0
    finally:
        exu.config.printToConsole = True
    if not ok:
        raise RuntimeError(f"Exudyn did not converge at h = {h:g} s")
    pos, vel, om = (mbs.GetSensorStoredData(k) for k in sensors)
    # Fz' at every step, then at the communication instants: Exudyn cuts a step whose Newton
    # iteration fails into smaller ones, which shifts its grid off them, so linear in time
    # between the steps (the resampling the order analysis does anyway)
    t_out = dt_out * np.arange(1, int(round(T / dt_out)) + 1)
    fz = [_fz_prime(m.P, F, c, v, o) for c, v, o in zip(pos[:, 1:], vel[:, 1:], om[:, 1:])]
    steps = len(pos) - 1
    return (t_out, np.interp(t_out, pos[:, 0], fz),
            {"steps": steps, "extra_steps": steps - int(round(T / h))}, wall)


class _TrunnionMotion:
    """The trunnion frame along the kernel's motion at time t [s]: Q [m] and the Tait-Bryan
    angles (x, y, z) [rad] that turn the rest frame J0 (local z along the trunnion axis, global
    y) onto the axis a; its rotation matrix and angular velocity [rad/s] (central differences)."""
    J0 = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
    DT = 1e-7   # [s]

    def __init__(self, m, theta, w, x0):
        P = m.P
        self.args = (theta, P[LY.P_S], P[LY.P_PITCH] > 0.5, P[LY.P_ROLL] > 0.5)
        self.x_start, self.w, self.x0 = m.phase, w, x0

    def pose(self, t):
        qz, ax, ay, az = contact.trunnion_line(self.x_start + self.w * t, *self.args)
        return np.array([self.x0, 0.0, qz, math.atan2(az, ay), math.asin(ax), 0.0])

    def rate(self, t):
        return (self.pose(t + self.DT) - self.pose(t - self.DT)) / (2 * self.DT)

    def rot(self, t):
        from exudyn.rigidBodyUtilities import RotXYZ2RotationMatrix
        return self.J0 @ RotXYZ2RotationMatrix(self.pose(t)[3:])

    def ang_vel(self, t):   # skew(omega) = R' R^T
        W = (self.rot(t + self.DT) - self.rot(t - self.DT)) @ self.rot(t).T / (2 * self.DT)
        return np.array([W[2, 1], W[0, 2], W[1, 0]])


def _exudyn_roller(mbs, m, tmotion):
    """The driven trunnion, the roller on its cylindrical joint and the groove's loads in the
    Exudyn system mbs; returns the sensors of the roller's position, velocity and angular
    velocity (global, every step)."""
    import exudyn as exu
    from exudyn.itemInterface import GenericJoint, LoadForceVector, LoadTorqueVector, \
        MarkerBodyRigid, SensorNode
    from exudyn.rigidBodyUtilities import RigidBodyInertia
    P = m.P
    q0, R0, w0, v0 = tmotion.pose(0.0)[:3], tmotion.rot(0.0), tmotion.ang_vel(0.0), tmotion.rate(0.0)[:3]
    trunnion = mbs.CreateRigidBody(inertia=RigidBodyInertia(1.0, np.diag([1e-3] * 3)),
                                   referencePosition=q0, referenceRotationMatrix=R0,
                                   initialVelocity=v0, initialAngularVelocity=w0)
    mg = mbs.AddMarker(MarkerBodyRigid(bodyNumber=mbs.CreateGround(),
                                       localHT=exu.HT(rotation=tmotion.J0)))
    mbs.AddObject(GenericJoint(
        markerNumbers=[mg, mbs.AddMarker(MarkerBodyRigid(bodyNumber=trunnion))],
        constrainedAxes=[1] * 6, offsetUserFunction=lambda mbs, t, i, par: list(tmotion.pose(t)),
        offsetUserFunction_t=lambda mbs, t, i, par: list(tmotion.rate(t))))
    a0 = R0[:, 2]
    wr0 = w0 + (m.Y[LY.Y_OM] - w0 @ a0) * a0     # spin om about a, rolling without slip
    roller = mbs.CreateRigidBody(
        inertia=RigidBodyInertia(P[LY.P_M_ROLLER], np.diag([P[LY.P_IT], P[LY.P_IT], P[LY.P_IS]])),
        referencePosition=q0, referenceRotationMatrix=R0, initialVelocity=v0,
        initialAngularVelocity=wr0)
    mr = mbs.AddMarker(MarkerBodyRigid(bodyNumber=roller))
    slide = 0 if m.p["traverse"] else 1
    mbs.AddObject(GenericJoint(markerNumbers=[mbs.AddMarker(MarkerBodyRigid(bodyNumber=trunnion)),
                                              mr], constrainedAxes=[1, 1, slide, 1, 1, 0]))
    node = mbs.GetObject(roller)["nodeNumber"]
    res = np.zeros(LY.R_LEN)
    OV = exu.OutputVariableType

    def groove(mbs):
        c = mbs.GetNodeOutput(node, OV.Position)
        v = mbs.GetNodeOutput(node, OV.Velocity)
        om = mbs.GetNodeOutput(node, OV.AngularVelocity)
        contact.groove_contact(tuple(c), tuple(v), tuple(om), P, res)
        return res

    mbs.AddLoad(LoadForceVector(markerNumber=mr, loadVectorUserFunction=lambda mbs, t, f:
                                list(groove(mbs)[LY.R_FX:LY.R_FZ + 1])))
    mbs.AddLoad(LoadTorqueVector(markerNumber=mr, loadVectorUserFunction=lambda mbs, t, f:
                                 list(groove(mbs)[LY.R_MX:LY.R_MZ + 1])))
    return [mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=o, storeInternal=True,
                                     writeToFile=False))
            for o in (OV.Position, OV.Velocity, OV.AngularVelocity)]


def _fz_prime(P, F, c, v, om):
    """Fz' = Fz F_press / Fx [N] of the roller at centre c [m], velocity v [m/s], angular
    velocity om [rad/s] (global), as the FMU computes it."""
    res = np.zeros(LY.R_LEN)
    contact.groove_contact(tuple(c), tuple(v), tuple(om), P, res)
    return fz_mod(-res[LY.R_FX], -res[LY.R_FZ], F)
