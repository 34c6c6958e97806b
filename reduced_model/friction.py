"""Friction law of Fig. 8 with the project's tanh form (model.md)."""
import numpy as np


def mu_tanh(v, mu_s, v_st):
    """Friction coefficient mu(v) = mu_s tanh(3 v / v_st) (Fig. 8), 99.5 % of mu_s at v_st.

    v, v_st in m/s.  v_st = 0 degenerates to Coulomb friction mu_s sign(v) (0 at v = 0).
    """
    v = np.asarray(v, dtype=float)
    if v_st <= 0.0:
        return mu_s * np.sign(v)
    return mu_s * np.tanh(3.0 * v / v_st)


def v_st_auto(A, B, Vp=0.0):
    """Automatic transition velocity [m/s]: a quarter of the peak sliding speed sqrt(A^2+B^2),
    with the plunge's sliding Vp [m/s] (sliding.amplitude_plunge) added in quadrature."""
    h = np.hypot(A, B)
    if Vp != 0.0:
        h = np.hypot(h, Vp)
    return float(h) / 4.0
