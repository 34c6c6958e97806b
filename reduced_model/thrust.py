"""Thrust of one roller and of the three-roller joint, Eqs. (25)-(27), in the reduced model.

``scene`` is a validated dict (see ``scene.validate``), SI units.  Whirl angle x = w t [rad].
"""
import math

import numpy as np

from . import sliding
from .orders import wrap_deg
from .scene import pressing_load


def _load(scene):
    return pressing_load(scene["F_press"], scene.get("torque", 0.0), scene["s"])


def fz_mod(Fx, Fz, F):
    """Fz_mod [N]: the thrust Fz [N] scaled to the pressing load F [N], Fz F / Fx, the paper's
    Fz' (its Fig. 16); 0 while the roller carries no load in F's direction (Fx F <= 1e-9 F^2:
    coast has F and Fx both negative).  Scalars; both FMUs' kernels compile it."""
    return Fz * F / Fx if Fx * F > 1e-9 * max(F * F, 1.0) else 0.0


def spin_inertia(m, r, r_bore):
    """Spin inertia of the roller as a thick ring, I = m (r^2 + r_bore^2) / 2 [kg m^2]."""
    return 0.5 * m * (r**2 + r_bore**2)


def amplitudes(scene):
    """A, B [m/s] of Eq. (24) for the scene's motion switches."""
    A = sliding.amplitude_A(scene["s"], scene["omega"], scene["theta"], scene["pitch"])
    B = sliding.amplitude_B(scene["r_roller"], scene["omega"], scene["theta"], scene["roll"])
    return float(A), float(B)


def transition_velocity(scene):
    """v_st [m/s] in use: the scene's, or the automatic sqrt(A^2+B^2+Vp^2)/4 when it is 0 (Vp
    the plunge's sliding): equations.transition_velocity, the analytic FMU's."""
    from .equations import transition_velocity as of
    return of(scene["v_st"], scene["s"], scene["r_roller"], scene["omega"], scene["theta"],
              scene.get("plunge_speed", 0.0), scene["pitch"], scene["roll"])


def second_order_amplitude(F, mu_s, R, v_st):
    """C [N], Eq. (25): amplitude of the 2nd order of ft = F mu(R sin u).

    C = F mu_s (2/pi) I, I = int_0^pi tanh(k sin u) sin u du, k = 3 R / v_st; Coulomb limit
    (v_st = 0) 4/pi F mu_s.  The integrand is analytic and 2 pi periodic (half its integral over
    one period is I), so the trapezoid rule on n points converges as exp(-n d), d = asinh(pi /
    (2 k)) the distance of tanh's nearest pole from the real axis: n = 36 / d points leave
    e^-36 ~ 2e-16.  Above k = 1e4 (n beyond 2e5), I = 2 - pi^2 / (12 k^2) + O(k^-4), the two
    ends' boundary layers int_0^inf 2 u (1 - tanh k u) du.
    """
    if R <= 0.0 or F <= 0.0 or mu_s <= 0.0:
        return 0.0
    if v_st <= 0.0:
        return 4.0 / np.pi * F * mu_s
    k = 3.0 * R / v_st
    if k > 1e4:
        val = 2.0 - np.pi ** 2 / (12.0 * k * k)
    else:
        n = max(64, int(np.ceil(36.0 / np.arcsinh(np.pi / (2.0 * k)))))
        su = np.sin(np.arange(n) * (2.0 * np.pi / n))
        val = np.pi / n * float(np.sum(np.tanh(k * su) * su))
    return F * mu_s * 2.0 / np.pi * val


class Thrust:
    """The reduced model's thrust of one roller for one operating point (scene).

    Constants are computed once; ``at(x, m)`` evaluates Eqs. (2), (18)-(26) and the spin term at
    whirl angle x [rad] with the math module ``m``: ``math`` for a scalar (the analytic FMU's
    per-step path, no numpy overhead) or ``numpy`` for arrays (time_series).  One code path.
    """

    def __init__(self, scene):
        self.A, self.B = amplitudes(scene)
        vst = transition_velocity(scene)
        self.k = 3.0 / vst if vst > 0 else 1e300          # tanh(3V/v_st); Coulomb at v_st = 0
        self.muF = scene["mu_groove"] * _load(scene)      # Eq. (11): ft = mu(V) F
        self.th = scene["theta"] if scene["pitch"] else 0.0
        self.zamp = scene["s"] * self.th                   # Eq. (18): z = s theta sin wt
        # the plunge speed [m/s] adds to dz/dt in v1 (sliding.amplitude_plunge)
        self.vp = scene.get("plunge_speed", 0.0) if scene["pitch"] else 0.0
        self.kspin = 0.0
        if scene["spin_inertia"] and scene["pitch"]:
            I = spin_inertia(scene["m_roller"], scene["r_roller"], scene["r_bore"])
            # (I/r^2) d2z/dt2 with d2z/dt2 = -w^2 s theta sin wt (constant w)
            self.kspin = -I / scene["r_roller"] ** 2 * scene["omega"] ** 2 * self.zamp

    def at(self, x, m=math):
        """(Fz, ftz, ft, V, phi, F_spin) at whirl angle x; N, N, N, m/s, rad, N."""
        sx = m.sin(x)
        V = self.A * m.sin(2.0 * x) + self.B * m.cos(2.0 * x)   # Eq. (24)
        phi = self.th * sx                                      # Eq. (2)
        if self.vp != 0.0:                                      # plunging: v_p sin(phi)
            V = V + self.vp * m.sin(phi)
        ft = self.muF * m.tanh(self.k * V)                      # Eqs. (11), (25), Fig. 8
        ftz = ft * m.sin(phi)                                   # Eq. (26)
        fs = self.kspin * sx
        return ftz + fs, ftz, ft, V, phi, fs


def time_series(scene, x):
    """All reduced-model signals at whirl angles ``x`` [rad] (array).

    Returns a dict of arrays: phi [rad], z [m], v1, v2, V [m/s], mu [-], ft, ftz, F_spin, Fz [N].
    Fz = ftz (+ F_spin when scene['spin_inertia']), the thrust on the groove.
    """
    x = np.asarray(x, dtype=float)
    th = Thrust(scene)
    Fz, ftz, ft, V, phi, fs = th.at(x, np)
    load = _load(scene)
    return dict(phi=phi, z=th.zamp * np.sin(x), v1=sliding.v1(x, th.A), v2=sliding.v2(x, th.B),
                V=V, mu=ft / load if load > 0 else np.zeros_like(x), ft=ft, ftz=ftz,
                F_spin=fs, Fz=Fz)


def three_roller_thrust(scene, x):
    """Housing thrust [N]: sum of Fz of rollers at whirl phases 0, 120, 240 deg."""
    x = np.asarray(x, dtype=float)
    return sum(time_series(scene, x + 2.0 * np.pi * i / 3.0)["Fz"] for i in range(3))


def _phasor(a, p_deg):
    return a * np.exp(1j * np.radians(p_deg))


def _from_phasor(c):
    a = float(abs(c))
    return (a, float(wrap_deg(np.degrees(np.angle(c)))) if a > 0 else 0.0)


def closed_form(scene):
    """Closed form of Eqs. (24)-(27) plus the spin-inertia term.

    Returns a dict: A, B [m/s], v_st [m/s], C [N], alpha_deg, beta_deg, friction orders 1 and 3
    (Eq. 27: C theta/2 at beta + 180 deg and at beta), spin-inertia order 1 and the totals,
    each order as (amplitude N, phase deg).
    """
    A, B = amplitudes(scene)
    R = float(np.hypot(A, B))
    vst = transition_velocity(scene)
    C = second_order_amplitude(_load(scene), scene["mu_groove"], R, vst)
    th = scene["theta"] if scene["pitch"] else 0.0
    bet = np.degrees(sliding.beta(A, B)) if R > 0 else 0.0
    half = C * th / 2.0
    o1 = (half, float(wrap_deg(bet + 180.0))) if half > 0 else (0.0, 0.0)
    o3 = (half, float(wrap_deg(bet))) if half > 0 else (0.0, 0.0)
    spin = (0.0, 0.0)
    if scene["spin_inertia"] and th > 0:
        I = spin_inertia(scene["m_roller"], scene["r_roller"], scene["r_bore"])
        amp = I / scene["r_roller"]**2 * scene["s"] * th * scene["omega"]**2
        spin = (amp, 180.0) if amp > 0 else (0.0, 0.0)   # -amp sin wt
    total1 = _from_phasor(_phasor(*o1) + _phasor(*spin))
    return dict(A=A, B=B, v_st=vst, C=C,
                alpha_deg=float(np.degrees(sliding.alpha(A, B))) if R > 0 else 0.0,
                beta_deg=float(bet),
                friction={1: o1, 3: o3}, spin={1: spin}, total={1: total1, 3: o3})
