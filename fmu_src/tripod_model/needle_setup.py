"""The needle-resolved bearing's set-up in plain numpy (model.ContactModel calls it): the row's
geometry, its parameter vector and work arrays (layout.NeedleWork), the static radial offset
of the roller under a load, and the needles' starting state.  ``p`` is the validated parameter
table (reduced_model.scene), SI units.
"""
import math

import numpy as np

from . import hertz, layout as K


def row_bore_radius(p):
    """Radius of the needles' outer race [m]: trunnion + needle diameter + the row's radial
    clearance (r_bore sets the roller's inertia; model.md's 12.5 mm leaves no clearance)."""
    return p["r_trunnion"] + p["d_needle"] + p["needle_clearance"]


def neighbour_distance(p):
    """Centre distance [m] at which two neighbouring needles touch: the needle diameter, or
    less where n_needles of that diameter would over-fill the pitch circle without the
    row's circumferential play (model.md's 46 x 1.6 mm on 11.705 mm over-fill it by
    0.11 mm); then the chord of equal spacing less the play shared out."""
    n = p["n_needles"]
    Rp = p["r_trunnion"] + 0.5 * p["d_needle"] + 0.5 * p["needle_clearance"]
    return min(p["d_needle"], 2 * Rp * math.sin(math.pi / n) - p["needle_circ_clearance"] / n)


def needle_work(p, n, C_line):
    """The parameter vector NP and work arrays of n needles (layout.NeedleWork; needles.py),
    C_line the needles' line-contact constant (hertz.needle_line_stiffness)."""
    ns = p["n_spheres"]
    NP = np.zeros(K.N_LEN)
    rn = 0.5 * p["d_needle"]
    NP[K.N_N] = n
    NP[K.N_NS] = ns
    NP[K.N_RN] = rn
    NP[K.N_RT] = p["r_trunnion"]
    NP[K.N_RBR] = row_bore_radius(p)
    NP[K.N_LN] = p["l_needle"]
    mn = p["rho_needle"] * math.pi * rn ** 2 * p["l_needle"]
    NP[K.N_MN] = mn
    NP[K.N_I1] = mn * (3 * rn ** 2 + p["l_needle"] ** 2) / 12.0   # cylinder, transverse
    NP[K.N_I3] = 0.5 * mn * rn ** 2                                  # about its axis
    NP[K.N_CS] = C_line / ns               # Table 1: C = 8.15e4 l^(8/9) / N_s per sphere
    NP[K.N_DC] = neighbour_distance(p)
    NP[K.N_ZAX] = p["needle_axial_clearance"]
    NP[K.N_HW] = 0.5 * p["roller_width"]
    NP[K.N_MU] = p["mu_needle"]
    NP[K.N_MUR] = p["mu_rolling"]
    NP[K.N_FRIC] = 1.0 if p["friction_needle"] else 0.0
    NP[K.N_ROLLR] = 1.0 if p["rolling_resistance"] else 0.0
    z = np.zeros
    return K.NeedleWork(
        NP=NP, SP=z((n, ns, 3)), FN=z((n, 6)), AN=z((n, 6, 6)), FR=z(6), AR=z((6, 6)),
        ND=z((n, K.D_LEN)), MOM=z((n, 10)), gn=z(6), PM=z((n, 10)), RS=z((6, 13)),
        UN=z((n, 6, 6)), MR=z(10), gn2=z(6), CW=z((n, 6, 6)), XW=z((n, 6, 7)), S=z((6, 6)),
        T=z((6, 13)), BN=z((n, 6, 6)), PB=z((n, 10)), RH=z((n, 6, 7)), XW7=z((n, 6, 13)),
        T7=z((6, 19)), BP=z((n, 6, 6)), LF=z((n, 6, 6)), ZF=z(n))


def radial_offset(p, F):
    """Static x offset of the roller from the trunnion axis [m] under a radial load F [N],
    against the load: needle j at psi_j is squeezed by -E cos(psi_j) - clearance across its
    two races in series; sum_j C_line (approach_j / 2)^(10/9) cos(psi_j) = F solved for E."""
    psi = 2 * np.pi * np.arange(p["n_needles"]) / p["n_needles"]
    c = np.cos(psi)
    Cl = hertz.needle_line_stiffness(p["l_needle"])

    def load(g):   # g = -E > 0
        ap = np.maximum(g * c - p["needle_clearance"], 0.0)
        return float(np.sum(Cl * (0.5 * ap) ** (10 / 9) * c))
    lo, hi = 0.0, p["needle_clearance"] + 1e-3
    for _ in range(100):   # bisection: load(g) is monotonic
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if load(mid) < abs(F) else (lo, mid)
    return 0.5 * (lo + hi) if F < 0 else -0.5 * (lo + hi)


def start_needles(Y, p, phase, theta, n):
    """The n needles' state in Y: equally spaced from the pressing direction, each midway
    between trunnion and bore (equal approach on both races), rolling without slip on both
    races; the roller's offset Y[Y_E] and spin Y[Y_OM] already set, whirl angle phase [rad]."""
    from .contact import trunnion_axial   # numba: the resolved bearing compiles its kernel
    Rt, Rb = p["r_trunnion"], row_bore_radius(p)
    rn = 0.5 * p["d_needle"]
    E = Y[K.Y_E]
    om = Y[K.Y_OM]
    d0 = trunnion_axial(phase, theta, p["s"], p["axial"])
    for j in range(n):
        psi = 2 * math.pi * j / n
        c, s = math.cos(psi), math.sin(psi)
        rho_b = E * c + math.sqrt(Rb ** 2 - (E * s) ** 2)   # bore surface along psi
        rho = 0.5 * (Rt + rho_b)
        vc = 0.5 * om * Rb
        q = K.Y_LEN + K.N_F * j
        Y[q:q + K.N_F] = (rho * c, rho * s, d0, 0.0, 0.0, -vc * s, vc * c, 0.0,
                          0.0, 0.0, om * Rb / (2 * rn))
