"""Friction law of Fig. 8 with the project's tanh form (model.md), and the spin moment of the
elliptical contact under it, Eqs. (14)-(16)."""
import math

import numpy as np


# tanh x = x P(x^2) / Q(x^2): Lambert's continued fraction x / (1 + x^2 / (3 + x^2 / (5 + ...
# x^2 / 17))) multiplied out; its error at |x| = 1/2 is 1.5e-22 (exact arithmetic)
TANH_P = (34459425.0, 4729725.0, 135135.0, 990.0, 1.0)
TANH_Q = (34459425.0, 16216200.0, 945945.0, 13860.0, 45.0)


def tanh_clipped(x):
    """tanh(x) from one exp, or below |x| = 1/2 a rational function: glibc's tanh takes about
    twice as long (the contact model's friction laws and the analytic model's row call it in
    every step's inner loops).  Below 1/2, 1 - exp(-2|x|) would cancel (3e-13 relative at
    1e-4, where a slide creeps: another libm's last bit of exp would move the outputs where a
    roller's slide lets go), so Lambert's continued fraction cut at 17 (TANH_P / TANH_Q).  Relative error below 4 eps
    (tests/test_needles.py); NaN stays NaN."""
    a = abs(x)
    if a >= 19.0:
        t = 1.0                      # exact in double precision
    elif a < 0.5:
        y = a * a
        p0, p1, p2, p3, p4 = TANH_P
        q0, q1, q2, q3, q4 = TANH_Q
        t = a * ((((p4 * y + p3) * y + p2) * y + p1) * y + p0) / \
            ((((q4 * y + q3) * y + q2) * y + q1) * y + q0)
    else:
        e = math.exp(-2.0 * a)
        t = (1.0 - e) / (1.0 + e)
    return t if x >= 0.0 else -t


def mu_tanh(v, mu_s, v_st):
    """Friction coefficient mu(v) = mu_s tanh(3 v / v_st) (Fig. 8), 99.5 % of mu_s at v_st.

    v, v_st in m/s.  v_st = 0 degenerates to Coulomb friction mu_s sign(v) (0 at v = 0).
    """
    v = np.asarray(v, dtype=float)
    if v_st <= 0.0:
        return mu_s * np.sign(v)
    return mu_s * np.tanh(3.0 * v / v_st)


def spin_moment(mu, fn, a1, wn, vst):
    """Spin moment [N m] of the roller-groove contact about its normal, Eqs. (14)-(16): the
    contact's semi-major axis a = a1 f_n^(1/3) [m] (Eq. 15, a1 from hertz.hertz_point) and
    3/8 mu f_n a, regularised in the spin rate wn [rad/s] like the sliding friction (tanh of
    3 wn a / v_st); v_st = 0: Coulomb (tanh -> sign).  Scalars; the contact kernel compiles it
    (contact.groove_contact), traverse.py steps with it, the analytic kernel compiles it."""
    a = a1 * fn ** (1.0 / 3.0)
    t = math.tanh(3.0 * wn * a / vst) if vst > 0 else \
        math.copysign(1.0, wn) if wn != 0 else 0.0
    return 0.375 * mu * t * fn * a


# The automatic v_st scales with the whirl and vanishes at rest; it never falls below this
# [m/s].  Under the tanh law a contact held at a fraction g of mu f_n creeps at
# (v_st / 3) atanh(g): at this floor and g = 0.99, 0.9 um/s.  A Hertz contact of the default
# geometry starts to slide after about 0.5 um of elastic tangential displacement (Mindlin,
# 3 mu P (2 - nu) / (8 G a), a the ellipse's mean semi-axis: 0.5 um at 1 kN, 3.5 um at 18 kN),
# so over a second at standstill the regularised law creeps about what the real contact
# deforms before it slides (docs/model.md; tests/test_reduced_model.py).
V_ST_FLOOR = 1e-6


def v_st_auto(A, B, Vp=0.0):
    """Automatic transition velocity [m/s]: a quarter of the peak sliding speed sqrt(A^2+B^2),
    with the plunge's sliding Vp [m/s] (sliding.amplitude_plunge) added in quadrature, and
    at least V_ST_FLOOR (a joint at rest or straight)."""
    h = np.hypot(A, B)
    if Vp != 0.0:
        h = np.hypot(h, Vp)
    return max(float(h) / 4.0, V_ST_FLOOR)
