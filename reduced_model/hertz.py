"""Hertz point contact of the roller (sphere, radius r) in the groove (concave cylinder, radius
Rg, axis along z), Eqs. (13)-(15) and Table 1, with the Brewe-Hamrock approximations of the
elliptic integrals (model.md; within about 2 % of the exact ones).  SI units throughout.
Shared by the contact model and the reduced traverse model.
"""
import math


def groove_curvature_radii(r, Rg):
    """Effective radii Rx (along the groove, z) and Ry (across) [m] of sphere-in-groove."""
    return r, r * Rg / (Rg - r)


def hertz_point(r, Rg, E, nu):
    """Hertz coefficients of the roller-groove contact.

    Returns (K, a1, k_ellipse): f_n = K delta^1.5 [N, m] (Eqs. 10, 13 and Table 1, n = 3/2),
    semi-major axis of the contact ellipse a = a1 f_n^(1/3) [m] (Eq. 15), and the ellipse
    ratio k = a/b.
    """
    Rx, Ry = groove_curvature_radii(r, Rg)
    Rp = 1.0 / (1.0 / Rx + 1.0 / Ry)                       # 1/sum of curvatures
    Es = E / (1.0 - nu * nu)                                # E' for two equal materials
    k = 1.0339 * (Ry / Rx) ** 0.636                         # ellipticity a/b
    Ee = 1.0003 + 0.5968 * Rx / Ry                          # elliptic integral E(e)
    Fe = 1.5277 + 0.6023 * math.log(Ry / Rx)                # elliptic integral K(e)
    # delta(F) = Fe (9/(2 Ee Rp) (F/(pi k E'))^2)^(1/3); at F = 1 N:
    d1 = Fe * (9.0 / (2.0 * Ee * Rp) * (1.0 / (math.pi * k * Es)) ** 2) ** (1.0 / 3.0)
    K = d1 ** -1.5
    a1 = (6.0 * k * k * Ee * Rp / (math.pi * Es)) ** (1.0 / 3.0)   # a = Dy/2 at F = 1 N
    return K, a1, k
