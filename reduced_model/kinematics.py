"""Driving motions of the trunnion relative to the groove, Eqs. (1)-(8).

All functions take the whirl angle ``x`` = w t [rad] (array or scalar) and the joint angle
``theta`` [rad]; angles are returned in rad, lengths in m.
"""
import numpy as np


def eccentricity(s, theta):
    """Eccentricity of the spider centre e = s (1 - cos theta) / (2 cos theta) [m] (Ref. 3)."""
    c = np.cos(theta)
    return s * (1.0 - c) / (2.0 * c)


def pitch_exact(x, theta):
    """Pitching angle phi, Eq. (1): tan phi = tan theta sin wt."""
    return np.arctan(np.tan(theta) * np.sin(x))


def pitch_small(x, theta):
    """Pitching angle phi, Eq. (2): phi = theta sin wt."""
    return theta * np.sin(x)


def yaw_exact(x, theta):
    """Yawing angle psi, Eq. (3): tan psi = tan theta cos wt."""
    return np.arctan(np.tan(theta) * np.cos(x))


def yaw_small(x, theta):
    """Yawing angle psi, Eq. (4): psi = theta cos wt."""
    return theta * np.cos(x)


def roll_exact(x, theta, s):
    """Rolling angle xi, Eq. (5): sin xi = e sin 2wt / s."""
    return np.arcsin(eccentricity(s, theta) * np.sin(2.0 * x) / s)


def roll_small(x, theta):
    """Rolling angle xi, Eq. (6): xi = (1 - cos theta) / (2 cos theta) sin 2wt."""
    c = np.cos(theta)
    return (1.0 - c) / (2.0 * c) * np.sin(2.0 * x)


def axial_exact(x, theta, s):
    """Axial displacement of the trunnion centre d [m], Eq. (7): d = s - (e cos 2wt + s cos xi)."""
    e = eccentricity(s, theta)
    return s - (e * np.cos(2.0 * x) + s * np.cos(roll_exact(x, theta, s)))


def axial_small(x, theta, s):
    """Axial displacement d [m], Eq. (8): d = -e cos 2wt."""
    return -eccentricity(s, theta) * np.cos(2.0 * x)
