"""Contact law coefficients from the geometry, Eq. (13)-(17) and Table 1.

Roller (sphere, radius r) in the groove (concave cylinder, radius Rg, axis along z): Hertz point
contact with the Brewe-Hamrock approximations of the elliptic integrals (model.md; within about
2 % of the exact ones).  SI units throughout.
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


def needle_line_stiffness(n_spheres, l_needle):
    """Needle line contact, Eq. (17) / Table 1: delta = 3.8e-5 (N_s f)^0.9 / l^0.8 [mm, N].

    Returns C_line [N/m^(10/9)] with the force on the whole needle f_needle = C_line delta^(10/9)
    (the N_s spheres of one needle share the line contact).
    """
    l_mm = l_needle * 1e3
    # whole-needle force P = N_s f: delta_mm = 3.8e-5 P^0.9 / l^0.8  ->  P = (delta_mm l^0.8/3.8e-5)^(1/0.9)
    c_mm = (l_mm ** 0.8 / 3.8e-5) ** (1.0 / 0.9)            # N / mm^(10/9)
    return c_mm * (1e3) ** (10.0 / 9.0)                     # N / m^(10/9)
