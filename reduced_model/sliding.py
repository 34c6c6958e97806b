"""Sliding velocities of the roller on the groove, Eqs. (18)-(24) (small-angle forms)."""
import math

import numpy as np


def amplitude_A(s, omega, theta, pitch=True):
    """A = s w theta^2 / 2 [m/s], Eq. (19)/(24): sliding from pitching (0 without pitch)."""
    return 0.5 * s * omega * theta**2 if pitch else 0.0


def amplitude_B(r, omega, theta, roll=True):
    """B = -r w (1 - cos theta) / cos theta [m/s], Eq. (20)/(24): sliding from rolling.
    Scalars (math.cos: the contact FMU derives it at every input change of a master)."""
    if not roll:
        return 0.0
    c = math.cos(theta)
    return -r * omega * (1.0 - c) / c


def amplitude_plunge(vp, theta, pitch=True):
    """|v_p| sin(theta) [m/s]: the largest sliding from plunging.  The spider's plunge speed v_p
    adds to the roller's travel along the groove, so Eq. (19) becomes v1 = (dz/dt + v_p) sin phi
    and the plunge slides the roller by v_p sin phi, phi up to theta (0 without pitch)."""
    return abs(vp) * math.sin(theta) if pitch else 0.0


def groove_travel(x, s, theta):
    """Roller travel along the groove z = s theta sin wt [m], Eq. (18) (small angle)."""
    return s * theta * np.sin(x)


def v1(x, A):
    """Sliding velocity from pitching v1 = A sin 2wt [m/s], Eq. (19)."""
    return A * np.sin(2.0 * x)


def v2(x, B):
    """Sliding velocity from rolling v2 = B cos 2wt [m/s], Eq. (20)."""
    return B * np.cos(2.0 * x)


def V(x, A, B):
    """Combined sliding velocity V = A sin 2wt + B cos 2wt [m/s], Eq. (24)."""
    return v1(x, A) + v2(x, B)


def alpha(A, B):
    """alpha [rad] with sin alpha = B/sqrt(A^2+B^2), cos alpha = A/sqrt(A^2+B^2), Eq. (24)-(25)."""
    return float(np.arctan2(B, A))


def beta(A, B):
    """beta [rad] with sin beta = -A/sqrt(A^2+B^2), cos beta = B/sqrt(A^2+B^2), Eq. (27)."""
    return float(np.arctan2(-A, B))
