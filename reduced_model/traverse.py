"""The reduced traverse model: the roller's slide across the groove, beyond Eqs. (18)-(27).

Eqs. (18)-(27) hold the roller at the groove bottom, so the groove friction follows the driven
slip V at once.  A roller free to slide along the trunnion (ideal bearing) is instead held by
the groove's curvature: it rides up the flank until the slope of the normal force balances the
friction, and crosses the groove bottom when the slip reverses.  That crossing is the third
sliding velocity of Fig. 22; where the friction never reaches mu_s the roller only rocks on the
flank (micro-slip) and the thrust falls far below Eq. (27).  Quasi-static balance of the roller
(its rocking mode, sqrt(F / (m rho)), lies far above 2 w), unknown p(x) = n.a, the tilt of the
contact normal n towards the trunnion axis a at whirl angle x (docs/model.md, "Traverse"):

  T1  lateral balance along a:   friction on the roller f_a = f_n p
  T2  spin balance about a:      f_b = -(I z''/r + M_s p) / r,   beta = f_b / f_n
      (I spin inertia, z the roll along the groove, M_s the spin moment Eq. (16) with the
      spin about the normal w_n = phi' + (z'/r) p)
  T3  tanh friction, inverted:   |f| = mu_s f_n tanh(3 |v| / v_st), v parallel to -f  ->
      slip along a  s = -(v_st / 3) atanh(g) / g * p / mu_s,  g = sqrt(p^2 + beta^2) / mu_s
  T4  kinematics:                s = V'(x) + g(x) p + rho_c p',   V' = v1 + v2 (1 + rho_c / r)
      (the roller centre, rho_c = r_groove - r_roller + Hertz approach from the groove axis,
      must follow the rolling trunnion's tilt xi as well as its contact point; g = -r a_y',
      the trunnion's turn moving the contact, r p off the groove's bottom, along a)
  T5  normal force:              f_n = K (rho_c / sqrt(1 - p^2) - (r_groove - r_roller))^1.5
  T6  forces on the groove:      Fz = -f_n (p sin phi + beta cos phi),
                                 Fx = f_n (sqrt(1 - p^2) + p^2 - p xi),  F . a = 0 (T1) gives Fy

The periodic solution of T4 (implicit trapezoidal rule over one whirl cycle, the start value by
a secant iteration on the cycle map) is tabulated once per operating point; ``Traverse.at``
interpolates it (a whirl angle in, the forces out: what the analytic FMU does per step).
Kinematics are the exact Eqs. (1), (5) (the contact model's).  The equations are kernel.py's
scalar functions (the analytic FMU's binary compiles the same); this module holds a table and
its arrays for the reports and the contact model's start.
"""
from __future__ import annotations

import math

import numpy as np

from . import equations as E
from . import analytic_kernel as K
from . import table as TB
from .analytic_kernel import CHECKED_AT_DEFAULT, CHECKED_RANGES, INERTIA, INERTIA_LIMIT
from .table import (FULL_SLIP_REL, MAX_CYCLES, MICRO_SLIP_G, N_PER_CYCLE, PERIODIC_TOL,
                    SETTLED_TOL, STALL)
from .orders import order_spectrum
from .scene import BY_NAME, MAX_SUBSTEPS, StepRefused, check_traverse_mu, too_long

REGIMES = ("full slip", "traverse", "micro-slip")
__all__ = ["CHECKED_AT_DEFAULT", "FULL_SLIP_REL", "INERTIA", "INERTIA_LIMIT", "MAX_CYCLES",
           "MICRO_SLIP_G", "N_PER_CYCLE", "PERIODIC_TOL", "SETTLED_TOL", "STALL", "Traverse"]


def params_array(sc: dict) -> np.ndarray:
    """The scene's parameters as kernel.py's T (PARAM_NAMES' order; a key the scene lacks at
    its default)."""
    return np.array([float(sc.get(n, BY_NAME[n].default)) for n in E.PARAM_NAMES])


def operating_point(sc: dict) -> np.ndarray:
    """kernel.py's operating point O of the scene (coast: the drive scene whose turn it is)."""
    O = np.zeros(E.O_LEN)
    E.operating_point(params_array(sc), float(sc["theta"]), float(sc["omega"]),
                      float(sc["F_press"]), float(sc.get("torque", 0.0)),
                      float(sc.get("plunge_speed", 0.0)), O)
    return O


def inertia_ratio(sc: dict) -> float:
    """The roller's inertia force over the pressing load, m_roller r_roller (2 omega)^2 / F
    (the traverse slide runs at twice the whirl); inf without load."""
    O = operating_point(sc)
    return K.inertia_ratio(sc["m_roller"], sc["r_roller"], O[E.O_W], O[E.O_F])


def _value(k):
    return lambda sc: K.checked_value(params_array(sc), operating_point(sc), k)


# Where the traverse model was checked against the contact model (kernel.CHECKED_RANGES, with
# the scene's value of each): (quantity, unit, lowest, highest, its value in a scene).  Outside,
# the CLI and the analytic FMU say so.
CHECKED = tuple((name, unit, lo, hi, _value(k))
                for k, (name, unit, lo, hi) in enumerate(CHECKED_RANGES))


def outside_span(name: str, v0: float, v1: float) -> str | None:
    """A phrase naming the values v0..v1 [CHECKED's unit] of the CHECKED quantity ``name`` if
    they leave its checked range, else None (the analytic FMU's wording: kernel.phrase)."""
    k = next(i for i, c in enumerate(CHECKED_RANGES) if c[0] == name)
    if K.inside(k, v0, v1):
        return None
    return K.phrase(k, False) % v0 if v0 == v1 else K.phrase(k, True) % (v0, v1)


def outside_checked(sc: dict) -> list[str]:
    """What of scene sc lies outside the range the traverse model was checked in (CHECKED,
    CHECKED_AT_DEFAULT), one short phrase each; [] inside it."""
    W = np.zeros(K.W_LEN)
    K.note_outside(params_array(sc), operating_point(sc), W)
    return [text[2:] for code, _, text in K.notes(W) if code != K.NOTE_OUTSIDE]


class Traverse:
    """Periodic (settled) solution of the reduced traverse model at one operating point.

    ``scene``: a validated analytic scene (SI), drive (coast: the drive scene whose turn it is).
    Attributes: ``x`` whirl angles [rad] of the table (one cycle, endpoint included), ``p`` [1],
    ``beta`` [1], ``fn`` [N], ``slip`` [m/s], ``Fx``, ``Fy``, ``Fz``, ``Fz_mod`` [N] on it;
    ``g_max`` [1]: the largest friction over mu_s f_n; ``rho_c`` [m]; ``cycles`` of the cycle
    map the secant iteration used; ``mismatch`` [m/s]: |s(2 pi) - s(0)| of the table,
    ``settled``: whether it is periodic (mismatch <= SETTLED_TOL x v_st; else the secant ran
    MAX_CYCLES cycles, or stalled, without getting there, and the table is the best cycle run).
    ``O``: kernel.py's operating point.
    """

    def __init__(self, scene: dict, n: int = N_PER_CYCLE, periodic: bool = True):
        self.scene = sc = scene
        self.n = n
        if sc["omega"] <= 0 and periodic:
            raise ValueError("omega = 0: the traverse model needs a whirling joint; allowed "
                             "range (0, 10000] rad/s (or traverse = false)")
        check_traverse_mu(sc["mu_groove"])
        self.O = O = operating_point(sc)
        self.F, self.mu, self.vst, self.r = O[E.O_F], O[E.O_MU], O[E.O_VST], O[E.O_R]
        self.K, self.a1, self.clear, self.rho_c = O[E.O_K], O[E.O_A1], O[E.O_CLEAR], O[E.O_RHO]
        self.vp, self.inertia = O[E.O_VP], O[E.O_I]
        self.held = O[E.O_HELD] != 0.0
        if not periodic:              # the operating point only, for march
            return
        m = n + 1
        self.x = 2.0 * math.pi * np.arange(m) / n
        self.D = np.zeros(TB.D_COUNT * m)
        T, SS, PS, BS = np.zeros(5 * m), np.zeros(m), np.zeros(m), np.zeros(m)
        self.cycles, self.mismatch, self.g_max = TB.traverse_table(O, self.D, n, T, SS, PS, BS)
        self.settled = self.mismatch <= SETTLED_TOL * self.vst
        self.T = T
        self.slip, self.p = SS, PS
        D = self.D.reshape(TB.D_COUNT, m)
        self.V, self.phi, self.xi = D[TB.D_V], D[TB.D_PHI], D[TB.D_XI]
        self.Fz, self.Fz_mod, self.Fx, self.Fy = (T[k::5] for k in range(4))
        self.fn = np.array([E.normal_force(O, q) if self.F > 0 else 0.0 for q in PS])
        self.beta = np.array([E.beta_at(O, PS[i], self.fn[i], D[TB.D_BI, i], D[TB.D_DPHI, i],
                                        D[TB.D_SPIN, i]) if self.fn[i] > 0 else 0.0
                              for i in range(m)])
        self._rows = [tuple(r) for r in T.reshape(m, 5).tolist()]
        self._flat = T.tolist()     # (plain floats: at() runs per step in the reports)
        self._scale = self.n / (2.0 * math.pi)

    @property
    def rows(self):
        """The periodic table's rows (Fz, Fz_mod, Fx, Fy [N], slip speed [m/s]) at n + 1
        equally spaced whirl angles over a cycle (what at interpolates)."""
        return self._rows

    @property
    def scale(self):
        """Table points per radian of whirl angle [1/rad]."""
        return self._scale

    @property
    def spin_moment_on(self):
        """Whether the spin moment, Eqs. (14)-(16), enters T2."""
        return self.O[E.O_SM] != 0.0

    def at(self, x):
        """(Fz, Fz_mod, Fx, Fy, slip speed) at whirl angle x [rad] (scalar), N and m/s: linear
        interpolation in the periodic table."""
        return tuple(TB.table_at(self._flat, self.n, x, k) for k in range(5))

    def state_at(self, x):
        """(slide slip s [m/s], p [1]) of the periodic solution at whirl angle x [rad]: where
        march starts when the inputs begin to move."""
        u = x % (2.0 * math.pi)
        return float(np.interp(u, self.x, self.slip)), float(np.interp(u, self.x, self.p))

    def march(self, s, p, x, dt):
        """The slide stepped in time at this operating point, for inputs that move (T4 is an
        ODE in time; the table is its periodic solution): from slide slip s [m/s] and p [1] (s
        None: at rest on the groove bottom, p = 0) at whirl angle x [rad] over dt [s]
        (kernel.march).  Works on Traverse(scene, periodic=False).  Returns (s, p, x at the end,
        the outputs there as ``at`` gives them)."""
        nd = E.substeps(self.O, dt)
        if nd > MAX_SUBSTEPS:     # refused before it starts (a host's huge step)
            raise StepRefused(too_long(dt, 2.0 * math.pi / (abs(self.O[E.O_W]) * self.n)))
        X = np.zeros(E.R_LEN)
        X[E.R_HAS_S] = 0.0 if s is None else 1.0
        X[E.R_S], X[E.R_P] = (0.0, 0.0) if s is None else (s, p)
        x1 = E.march(self.O, X, 0, x, dt)
        return float(X[E.R_S]), float(X[E.R_P]), float(x1), tuple(
            float(X[k]) for k in (E.R_FZ, E.R_FZ_MOD, E.R_FX, E.R_FY, E.R_SLIP))

    def orders(self, name="Fz_mod", orders=(1, 3)):
        """{k: (amplitude N, phase deg)} of one of the tabulated signals over the cycle."""
        a, ph = order_spectrum(getattr(self, name)[:-1], 1, orders)
        return {int(k): (float(ak), float(pk)) for k, ak, pk in zip(orders, a, ph)}

    def three_rollers(self, name="Fz_mod", orders=(1, 3)):
        """Orders of the sum over rollers at whirl phases 0, 120, 240 deg."""
        y = getattr(self, name)[:-1]
        s = y + np.roll(y, -self.n // 3) + np.roll(y, -2 * self.n // 3)
        a, ph = order_spectrum(s, 1, orders)
        return {int(k): (float(ak), float(pk)) for k, ak, pk in zip(orders, a, ph)}

    def regime(self) -> str:
        """'micro-slip' (friction never reaches 95 % of mu_s f_n), 'full slip' (order 3 within
        5 % of Eq. 27), else 'traverse' (kernel.regime: the analytic FMU's)."""
        return REGIMES[TB.regime(self.g_max, self.T, self.n, self.O)]

