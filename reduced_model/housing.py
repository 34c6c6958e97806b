"""The joint's forces on the housing in the housing frame, from the rollers' groove-frame forces.

Housing frame (rotates with the housing, model.md): Z the shaft axis (every groove's z), X along
roller 1's trunnion axis, Y = Z x X.  Roller i (i = 0, 1, 2) sits in the groove at housing angle
a_i = 2 pi i / 3 (its whirl phase, model.md "Three rollers"); its groove frame is right-handed:
y_i (trunnion axis, radial) = (cos a_i, sin a_i), x_i (pressing) = y_i x Z = (sin a_i, -cos a_i).

Plain Python on scalars: the contact FMU's compiled step takes it through numba
(tripod_model/kernel.py), the analytic FMU's through reduced_model/analytic_kernel.py, compiled the
same way: one implementation.
"""
import math

_C = (1.0, math.cos(2.0 * math.pi / 3.0), math.cos(4.0 * math.pi / 3.0))
_S = (0.0, math.sin(2.0 * math.pi / 3.0), math.sin(4.0 * math.pi / 3.0))


def housing_forces(fx1, fy1, r1, fx2, fy2, r2, fx3, fy3, r3):
    """(F_housing_x, F_housing_y [N], T_housing [N m]): the rollers' forces on the grooves
    (pressing fx_i, lateral fy_i along the trunnion axis [N]) summed in the housing frame, and
    their torque about the shaft axis at the contact radius r_i [m], positive in the sense the
    transmitted torque drives (sum of r_i fx_i; the torque about +Z is its negative).  A
    roller that is not simulated passes zeros."""
    fx = (fx1, fx2, fx3)
    fy = (fy1, fy2, fy3)
    r = (r1, r2, r3)
    X = 0.0
    Y = 0.0
    T = 0.0
    for i in range(3):   # left to right, the same sums on every path
        X += fx[i] * _S[i] + fy[i] * _C[i]
        Y += -fx[i] * _C[i] + fy[i] * _S[i]
        T += r[i] * fx[i]
    return X, Y, T


def spider_orbit(s, theta, x):
    """The spider centre on Eq. (5)'s orbit in the housing frame [m]: e (cos 2x, sin 2x), e =
    s (1 - cos theta) / (2 cos theta), x roller 1's whirl angle [rad] (the rollers' prescribed
    lines of Eqs. (1)-(8) meet there: docs/model.md, "The floating spider")."""
    c = math.cos(theta)
    e = s * (1.0 - c) / (2.0 * c)
    return e * math.cos(2.0 * x), e * math.sin(2.0 * x)
