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
  T4  kinematics:                s = V'(x) + rho_c p',   V' = v1 + v2 (1 + rho_c / r)
      (the roller centre, rho_c = r_groove - r_roller + Hertz approach from the groove axis,
      must follow the rolling trunnion's tilt xi as well as its contact point)
  T5  normal force:              f_n = K (rho_c / sqrt(1 - p^2) - (r_groove - r_roller))^1.5
  T6  forces on the groove:      Fz = -f_n (p sin phi + beta cos phi),
                                 Fx = f_n (sqrt(1 - p^2) + p^2 - p xi),  F . a = 0 (T1) gives Fy

The periodic solution of T4 (implicit trapezoidal rule over one whirl cycle, the start value by
a secant iteration on the cycle map) is tabulated once per operating point; ``Traverse.at``
interpolates it (a whirl angle in, the forces out: what the analytic FMU does per step).
Kinematics are the exact Eqs. (1), (5) (the contact model's).
"""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from .friction import spin_moment
from .hertz import hertz_point
from .orders import order_spectrum
from .scene import (BY_NAME, MAX_SUBSTEPS, StepRefused, check_traverse_mu, pressing_load,
                    too_long)
from .thrust import Thrust, fz_mod, spin_inertia, transition_velocity

N_PER_CYCLE = 360          # table points a whirl cycle (24 scenes: order 3 within 0.02 % of 1440)
MICRO_SLIP_G = 0.95        # friction never above 95 % of mu_s f_n: the roller never slides across
FULL_SLIP_REL = 0.05       # order 3 within 5 % (complex) of Eq. (27): Eqs. 18-27 hold
REGIMES = ("full slip", "traverse", "micro-slip")
PERIODIC_TOL = 1e-7        # the secant's target: |s(2 pi) - s(0)| <= PERIODIC_TOL x v_st
SETTLED_TOL = 1e-5         # periodic enough: the tanh friction moves by <= 3 SETTLED_TOL of
                           # mu f_n over the mismatch, far below compare's 0.1 % settling
STALL = 3                  # cycles without a better one: the secant is in the map's noise
MAX_CYCLES = 60            # cycles of the cycle map the secant may run
# Where the traverse model was checked against the contact model (docs/validation.md: three
# named scenes and a Halton grid over the first five ranges, harness/validation.py; every other
# parameter at its default): (quantity, unit, lowest, highest, its value in a scene).  The
# grid spans a launch (50 kN per roller, 25 deg, from 0.5 Hz) to motorway speeds; its error
# grows with the roller's inertia against the load (the quasi-static balance misses it: -19 % at
# 32 Hz and 470 N), so the checked range also bounds that ratio, where the grid stayed within
# 5 %.  Outside, the CLI and the analytic FMU say so.
INERTIA_LIMIT = 0.1
INERTIA = "roller inertia m r (2 omega)^2 / load"   # its CHECKED name


def inertia_ratio(sc: dict) -> float:
    """The roller's inertia force over the pressing load, m_roller r_roller (2 omega)^2 / F
    (the traverse slide runs at twice the whirl); inf without load."""
    F = abs(pressing_load(sc["F_press"], sc.get("torque", 0.0), sc["s"]))
    a = sc["m_roller"] * sc["r_roller"] * (2.0 * sc["omega"]) ** 2
    return a / F if F > 0 else (math.inf if a > 0 else 0.0)


CHECKED = (
    ("theta", "deg", 2.0, 25.0, lambda sc: math.degrees(sc["theta"])),
    ("whirl", "Hz", 0.5, 50.0, lambda sc: abs(sc["omega"]) / (2.0 * math.pi)),
    ("pressing load", "N", 300.0, 50000.0,
     lambda sc: abs(pressing_load(sc["F_press"], sc.get("torque", 0.0), sc["s"]))),
    ("mu_groove", "", 0.03, 0.12, lambda sc: sc["mu_groove"]),
    ("groove clearance", "mm", 0.05, 0.8, lambda sc: 1e3 * (sc["r_groove"] - sc["r_roller"])),
    (INERTIA, "", 0.0, INERTIA_LIMIT, inertia_ratio),
    ("plunge speed", "m/s", -0.1, 0.1, lambda sc: sc.get("plunge_speed", 0.0)),
)
PLUNGE_RANGE = (-0.1, 0.1)   # [m/s] the plunge speeds of the grid's plunging scenes
GRID_RANGES = CHECKED[:5]    # the ranges the validation grid is drawn over
# held at their defaults in that check (the inputs and the ranges above vary); yaw and axial
# are not here: the analytic model does not use them, so they cannot move its result
CHECKED_AT_DEFAULT = ("v_st", "pitch", "roll", "s", "r_roller", "r_bore", "m_roller",
                      "spin_inertia", "spin_moment", "E", "nu")


def outside_span(name: str, v0: float, v1: float) -> str | None:
    """A phrase naming the values v0..v1 [CHECKED's unit] of the CHECKED quantity ``name`` if
    they leave its checked range, else None."""
    _, unit, lo, hi, _ = next(c for c in CHECKED if c[0] == name)
    if lo - 1e-9 * abs(lo) <= v0 and v1 <= hi + 1e-9 * abs(hi):
        return None
    u = f" {unit}" if unit else ""
    span = f"{v0:.4g}" if v0 == v1 else f"{v0:.4g}-{v1:.4g}"
    return f"{name} {span}{u} (checked {lo:g}-{hi:g}{u})"


def outside_checked(sc: dict) -> list[str]:
    """What of scene sc lies outside the range the traverse model was checked in (CHECKED,
    CHECKED_AT_DEFAULT), one short phrase each; [] inside it."""
    out = []
    for name, _, _, _, value in CHECKED:
        v = value(sc)
        phrase = outside_span(name, v, v)
        if phrase:
            out.append(phrase)
    for name in CHECKED_AT_DEFAULT:
        p = BY_NAME[name]
        if name in sc and sc[name] != p.default:
            u = f" {p.unit}" if p.unit not in ("1", "") else ""
            out.append(f"{name} = {sc[name]:g}{u} (checked at {p.default:g}{u} only)")
    return out


# numpy's names over libm's scalar functions: the march's one-float-at-a-time path (numpy's
# own vector sin may differ in the last bit, so a compiled twin could not match it)
SCALAR = SimpleNamespace(sin=math.sin, cos=math.cos, sqrt=math.sqrt, arctan=math.atan,
                         arcsin=math.asin)


class Traverse:
    """Periodic (settled) solution of the reduced traverse model at one operating point.

    ``scene``: a validated analytic scene (SI).  Attributes: ``x`` whirl angles [rad] of the
    table (one cycle, endpoint included), ``p`` [1], ``beta`` [1], ``fn`` [N], ``slip`` [m/s],
    ``Fx``, ``Fy``, ``Fz``, ``Fz_mod`` [N] on it; ``g_max`` [1]: the largest friction over
    mu_s f_n; ``rho_c`` [m]; ``cycles`` of the cycle map the secant iteration used;
    ``mismatch`` [m/s]: |s(2 pi) - s(0)| of the table, ``settled``: whether it is periodic
    (mismatch <= SETTLED_TOL x v_st; else the secant ran MAX_CYCLES cycles, or stalled,
    without getting there, and the table is the best cycle run).
    """

    def __init__(self, scene: dict, n: int = N_PER_CYCLE, periodic: bool = True):
        self.scene = sc = scene
        self.n = n
        w = sc["omega"]
        if w <= 0 and periodic:
            raise ValueError("omega = 0: the traverse model needs a whirling joint; allowed "
                             "range (0, 10000] rad/s (or traverse = false)")
        check_traverse_mu(sc["mu_groove"])
        self.F = F = pressing_load(sc["F_press"], sc.get("torque", 0.0), sc["s"])
        self.mu = mu = sc["mu_groove"]
        self.vst = transition_velocity(sc)
        self.r = r = sc["r_roller"]
        Rg = sc["r_groove"]
        self.K, self.a1, _ = hertz_point(r, Rg, sc["E"], sc["nu"])
        self.clear = Rg - r
        self.rho_c = self.clear + (F / self.K) ** (2.0 / 3.0) if F > 0 else self.clear
        self.vp = sc.get("plunge_speed", 0.0)   # the spider's plunge speed [m/s]
        self._sm = bool(sc["spin_moment"])
        # the roller's spin inertia in T2 [kg m^2] (0: the spin-inertia thrust switched off)
        self.inertia = spin_inertia(sc["m_roller"], r, sc["r_bore"]) if sc["spin_inertia"] \
            else 0.0
        self.held = F > 0 and mu > 0 and self.vst > 0   # else nothing holds the roller
        if not periodic:              # the operating point only, for march
            return
        self.x = 2.0 * math.pi * np.arange(n + 1) / n
        self._drive()
        if not self.held:                             # no friction, or no slip to drive it
            self.p = np.zeros(n + 1)
            self.slip = self.V.copy()                 # nothing holds the roller: it slips by V
            self.cycles, self.mismatch = 0, 0.0
        else:
            self.p, self.cycles, self.mismatch = self._periodic()
        self.settled = self.mismatch <= SETTLED_TOL * self.vst
        self._tabulate()

    # --- the driving motion on the table (exact Eqs. 1, 5; z = s tan(phi), Eq. 18) ---------
    def _drive_on(self, x, m=np):
        """The driving motion at whirl angles x [rad] (numpy array, or a float with m = SCALAR):
        phi, xi [rad], V [m/s] (T4's driven slip), dphi [rad/s], spin [rad/s] (rolling along
        the groove), b_inertia [N] (T2's inertia part of f_b).  fmu_src/native/analytic_step.c
        (march) does the same operations in the same order."""
        sc = self.scene
        w, th = sc["omega"], sc["theta"]
        T = math.tan(th) if sc["pitch"] else 0.0
        k = (1.0 - math.cos(th)) / (2.0 * math.cos(th)) if sc["roll"] else 0.0   # e / s
        tz = T * m.sin(x)
        phi = m.arctan(tz)
        dphi = T * w * m.cos(x) / (1.0 + tz * tz)
        q = k * m.sin(2.0 * x)
        xi = m.arcsin(q)
        dxi = 2.0 * w * k * m.cos(2.0 * x) / m.sqrt(1.0 - q * q)
        zd = sc["s"] * T * w * m.cos(x)
        if self.vp != 0.0:                                  # the plunge: travel along z
            zd = zd + self.vp
        zdd = -sc["s"] * T * w * w * m.sin(x)
        r = sc["r_roller"]
        v1 = zd * m.sin(phi)                                # Eq. (19), exact
        v2 = -r * dxi                                       # Eq. (20), exact
        V = v1 + v2 * (1.0 + self.rho_c / r)                # T4
        return phi, xi, V, dphi, zd / r, -self.inertia * zdd / (r * r)

    def _drive(self):
        (self.phi, self.xi, self.V, self.dphi, self.spin,
         self.b_inertia) = self._drive_on(self.x)
        # plain lists: the time-stepping loop reads them one float at a time
        self._V, self._bi = self.V.tolist(), self.b_inertia.tolist()
        self._dphi, self._spin = self.dphi.tolist(), self.spin.tolist()

    # --- T2, T3, T5 at one table point ------------------------------------------------------
    def _fn(self, p):
        d = self.rho_c / math.sqrt(1.0 - p * p) - self.clear
        return self.K * d ** 1.5 if d > 0 else 0.0

    def _beta(self, i, p, fn):
        """f_b / f_n, T2, at table point i."""
        return self._beta_at(p, fn, self._bi[i], self._dphi[i], self._spin[i])

    def _beta_at(self, p, fn, bi, dphi, spin):
        """f_b / f_n, T2, where the drive gives b_inertia bi [N], dphi and spin [rad/s]."""
        b = bi
        if self._sm:   # the spin moment, Eqs. (14)-(16), against the spin wn [rad/s]
            b -= spin_moment(self.mu, fn, self.a1, dphi + spin * p, self.vst) * p / self.r
        return b / fn

    def _share(self, s, B):
        """p >= 0 [1] for the slide slip |s| [m/s] when the spin needs |f_b| / f_n = B (T3):
        the slip vector (s, t) at angle a from the slide, mu tanh(3 |s| / (v_st cos a)) sin a
        = B, solved by bisection and Newton on a in [0, pi/2) (its left side rises from 0 to
        mu); then p = mu tanh(3 |v| / v_st) cos a."""
        mu, k = self.mu, 3.0 / self.vst
        B = min(B, mu * (1.0 - 1e-9))
        s = abs(s)
        if B <= 0.0:
            return mu * math.tanh(k * s)
        if s == 0.0:
            return 0.0
        lo, hi = 0.0, 0.5 * math.pi
        a = min(math.asin(min(B / (mu * math.tanh(k * s) + 1e-300), 1.0)), 1.5)
        for _ in range(60):
            c, sn = math.cos(a), math.sin(a)
            th = math.tanh(k * s / c)
            f = mu * th * sn - B
            if f > 0:
                hi = a
            else:
                lo = a
            df = mu * (th * c + sn * (1.0 - th * th) * k * s * sn / (c * c))
            an = a - f / df if df > 0 else 0.5 * (lo + hi)
            if not lo < an < hi:
                an = 0.5 * (lo + hi)
            if abs(an - a) < 1e-10:
                a = an
                break
            a = an
        return mu * math.tanh(k * s / math.cos(a)) * math.cos(a)

    def _p(self, i, s):
        """p at table point i for the slide slip s [m/s]."""
        return self._p_at(s, self._bi[i], self._dphi[i], self._spin[i])

    def _p_at(self, s, bi, dphi, spin, p0=None):
        """p for the slide slip s [m/s] where the drive gives bi, dphi, spin (T2, T3, T5: beta
        depends weakly on p through f_n and the spin moment: fixed point), from p0 when it is
        given and of p's sign (the march: a nearby point's p), else from beta = 0."""
        sign = -1.0 if s > 0 else 1.0
        p = sign * self.mu * math.tanh(3.0 * abs(s) / self.vst)
        if p0 is not None and p0 * sign > 0.0:
            p = p0
        for _ in range(6):
            q = sign * self._share(s, abs(self._beta_at(p, self._fn(p), bi, dphi, spin)))
            if abs(q - p) < 1e-11 * self.mu:
                return q
            p = q
        return p

    # --- the periodic solution of T4 in the slide slip s ----------------------------------------
    def _step(self, rhs0, s, h, P1, p0=None):
        """s1 [m/s] of one trapezoidal step of T4 from slip s over h [s]: the root of
        f(z) = rho_c P1(z) - h/2 z - rhs0, P1 the p of the step's end point.  Newton: f falls
        with slope <= -h/2 and |p| <= mu, so its root lies in [lo, hi]; a Newton step that
        leaves the bracket (it overshoots on the tanh's knee and can cycle there) is a
        bisection instead.  p0 (the march): P1 takes a guess for its fixed point as second
        argument, p0 first, then the last p it gave (the table: p0 None, one argument)."""
        rho, mu = self.rho_c, self.mu
        e = 1e-6 * self.vst              # finite-difference step of the Newton slope
        lo, hi = -2.0 * (rho * mu + rhs0) / h, 2.0 * (rho * mu - rhs0) / h
        z = min(max(s, lo), hi)
        g = p0
        for _ in range(200):
            p1 = P1(z) if p0 is None else P1(z, g)
            g = p1
            res = rho * p1 - 0.5 * h * z - rhs0
            if res > 0.0:
                lo = z
            elif res < 0.0:
                hi = z
            else:
                break
            d = (rho * ((P1(z + e) if p0 is None else P1(z + e, p1)) - p1)) / e - 0.5 * h
            dz = -res / d
            if not lo < z + dz < hi:
                dz = 0.5 * (lo + hi) - z
            z += dz
            if abs(dz) < 1e-9 * self.vst:
                break
        return z

    def _slip_step(self, rhs0, s, h, bi, dphi, spin, p0):
        """(s1 [m/s], p1 [1]) of one trapezoidal step of T4 from slip s and p0 over h [s], the
        march's first choice: T3 and T4 together as Newton on the slip vector (s, t), t >= 0
        across the slide, where _step nests T3's inversion (and T2's fixed point) inside its
        Newton and costs three to four times as much.  The friction mu tanh(k |v|) v / |v|
        (k = 3 / v_st) gives p = -mu g s / |v| and |f_b| / f_n = mu g t / |v|; the residuals
        are T4, rho_c p - h/2 s - rhs0, and T2's demand, mu g t / |v| - |beta(p)| (capped as
        _share caps it), with the friction's Jacobian exact and beta's weak dependence on p
        left out of it.  None when it does not settle within 30 iterations to 1e-9 v_st (the
        start from rest, some steps after a jump: about one step in 200 over random scenes;
        the caller takes _step).  Where T3 determines the slip the two agree within 2e-6 of
        v_st, mu and the thrust over 2000 steps (tests/test_traverse.py; measured 1e-11 to
        2e-8)."""
        rho, mu, k = self.rho_c, self.mu, 3.0 / self.vst
        kt = 0.5 * h
        cap = mu * (1.0 - 1e-9)
        tol = 1e-9 * self.vst
        t = 0.0
        if p0 != 0.0:   # the last step's slip angle
            t = abs(s * min(abs(self._beta_at(p0, self._fn(p0), bi, dphi, spin)), cap) / p0)
        for _ in range(30):
            v = math.sqrt(s * s + t * t)
            gv, dg, us, ut = k, k, 0.0, 0.0      # the friction's slope at v = 0
            if v > 0.0:
                g = math.tanh(k * v)
                gv, dg, us, ut = g / v, k * (1.0 - g * g), s / v, t / v
            p = -mu * gv * s
            B = min(abs(self._beta_at(p, self._fn(p), bi, dphi, spin)), cap)
            a11 = mu * (gv * (1.0 - us * us) + dg * us * us)
            a22 = mu * (gv * (1.0 - ut * ut) + dg * ut * ut)
            a12 = mu * (dg - gv) * us * ut
            r1 = rho * p - kt * s - rhs0
            r2 = mu * gv * t - B
            j11 = -rho * a11 - kt
            j12 = -rho * a12
            det = j11 * a22 - j12 * a12          # < 0: the friction's Jacobian is semi-definite
            if not det < 0.0:
                return None
            ds = (j12 * r2 - a22 * r1) / det
            dt = (a12 * r1 - j11 * r2) / det
            s += ds
            t = abs(t + dt)
            if abs(ds) < tol and abs(dt) < tol:
                v = math.sqrt(s * s + t * t)
                return s, -mu * (math.tanh(k * v) / v if v > 0.0 else k) * s
        return None

    def _cycle(self, s0):
        """One whirl cycle of T4, rho_c dp/dt = s - V', by the trapezoidal rule in s (never
        singular: d(rho_c p - h s / 2)/ds <= -h / 2): the slide slip s [m/s] and p [1] at
        every table point (kept on every pass: the secant's last pass is the table)."""
        n, h = self.n, 2.0 * math.pi / self.scene["omega"] / self.n
        rho, V, P = self.rho_c, self._V, self._p
        s = s0
        p0 = P(0, s)
        ss, ps = [s], [p0]
        for i in range(n):
            rhs0 = rho * p0 + 0.5 * h * (s - V[i] - V[i + 1])
            s = self._step(rhs0, s, h, lambda z: P(i + 1, z))
            p0 = P(i + 1, s)
            ss.append(s)
            ps.append(p0)
        return ss, ps

    def _periodic(self):
        """The slide slip over one cycle with s(2 pi) = s(0): secant on the cycle map.  Returns
        p on the table, the number of cycles run and |s(2 pi) - s(0)| [m/s].  The cycle map
        carries the rounding of 360 inner solves, amplified where the slip crosses the tanh's
        knee (up to about 1e-5 v_st, measured): where the secant wanders in that noise (no
        better cycle in STALL tries) and the best cycle is within SETTLED_TOL, it stops there;
        the table is the best cycle run."""
        vst = self.vst
        tol, max_cycles = PERIODIC_TOL * vst, MAX_CYCLES
        a = 0.0
        ga = self._cycle(a)[0][-1] - a
        b = a + ga
        ss, ps = self._cycle(b)
        gb = ss[-1] - b
        best, stall = (abs(gb), ss, ps), 0
        used = 2
        while abs(gb) > tol and gb != ga and used < max_cycles:
            a, ga, b = b, gb, b - gb * (b - a) / (gb - ga)
            ss, ps = self._cycle(b)
            gb = ss[-1] - b
            used += 1
            if abs(gb) < best[0]:
                best, stall = (abs(gb), ss, ps), 0
            else:
                stall += 1
                if stall >= STALL and best[0] <= SETTLED_TOL * vst:
                    break
        mismatch, ss, ps = best
        self.slip = np.array(ss)
        return np.array(ps), used, mismatch

    def _tabulate(self):
        p = self.p
        n1 = p.size
        fn = np.array([self._fn(q) for q in p]) if self.F > 0 else np.zeros(n1)
        beta = np.array([self._beta(i, p[i], fn[i]) if fn[i] > 0 else 0.0 for i in range(n1)])
        slip = self.slip
        self.fn, self.beta, self.slip = fn, beta, slip
        self.Fz, self.Fx, self.Fy, self.Fz_mod = groove_forces(fn, p, beta, self.phi, self.xi,
                                                               self.F)
        self.g_max = float(np.max(np.hypot(p, beta)) / self.mu) if self.mu > 0 else 0.0
        self._rows = [tuple(r) for r in np.column_stack(
            [self.Fz, self.Fz_mod, self.Fx, self.Fy, np.abs(slip)]).tolist()]
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
        return self._sm

    def at(self, x):
        """(Fz, Fz_mod, Fx, Fy, slip speed) at whirl angle x [rad] (scalar), N and m/s: linear
        interpolation in the periodic table (plain floats: the analytic FMU's per-step path)."""
        u = (x % 6.283185307179586) * self._scale
        i = int(u)
        if i >= self.n:
            i = self.n - 1
        f = u - i
        a0, a1, a2, a3, a4 = self._rows[i]
        b0, b1, b2, b3, b4 = self._rows[i + 1]
        return (a0 + f * (b0 - a0), a1 + f * (b1 - a1), a2 + f * (b2 - a2), a3 + f * (b3 - a3),
                a4 + f * (b4 - a4))

    def state_at(self, x):
        """(slide slip s [m/s], p [1]) of the periodic solution at whirl angle x [rad]: where
        march starts when the inputs begin to move."""
        u = x % (2.0 * math.pi)
        return float(np.interp(u, self.x, self.slip)), float(np.interp(u, self.x, self.p))

    def march(self, s, p, x, dt):
        """The slide stepped in time at this operating point, for inputs that move (T4 is an
        ODE in time; the table is its periodic solution): from slide slip s [m/s] and p [1]
        (s None: at rest on the groove bottom, p = 0) at whirl angle x [rad] over dt [s], by
        the table's trapezoidal rule in substeps of at most the table's spacing (each solved
        by _slip_step, or _step where that does not settle).  Works on
        Traverse(scene, periodic=False).  Returns (s, p, x at the end, the outputs there as
        ``at`` gives them).  Scalar libm math throughout: the analytic FMU's compiled march
        (fmu_src/native/analytic_step.c) is this, bit for bit (tests/test_fast.py)."""
        w = self.scene["omega"]
        nd = abs(w) * dt * self.n / (2.0 * math.pi) - 1e-9
        if nd > MAX_SUBSTEPS:     # refused before it starts (a host's huge step)
            raise StepRefused(too_long(dt, 2.0 * math.pi / (abs(w) * self.n)))
        n = max(1, math.ceil(nd))
        h = dt / n
        wh = w * h
        _, _, V0, _, _, _ = self._drive_on(x, SCALAR)
        if s is None:
            s, p = V0, 0.0
        for i in range(n):
            phi, xi, V1, dphi, spin, bi = self._drive_on(x + wh * (i + 1), SCALAR)
            if self.held:
                rhs0 = self.rho_c * p + 0.5 * h * (s - V0 - V1)
                sp = self._slip_step(rhs0, s, h, bi, dphi, spin, p)
                if sp is None:
                    s = self._step(rhs0, s, h, lambda z, g: self._p_at(z, bi, dphi, spin, g), p)
                    p = self._p_at(s, bi, dphi, spin, p)
                else:
                    s, p = sp
            V0 = V1
        if not self.held:
            s, p = V0, 0.0
        fn = self._fn(p) if self.F > 0 else 0.0
        beta = self._beta_at(p, fn, bi, dphi, spin) if fn > 0 else 0.0
        Fz, Fx, Fy, Fz_mod = groove_forces(fn, p, beta, phi, xi, self.F, SCALAR)
        return s, p, x + wh * n, (Fz, Fz_mod, Fx, Fy, abs(s))

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
        5 % of Eq. 27), else 'traverse'."""
        fz27 = Thrust(self.scene).at(self.x[:-1], np)[0]        # Eqs. (18)-(27), numpy only
        a, ph = order_spectrum(fz27, 1, (3,))
        return regime_of(self.g_max, self.orders()[3], (float(a[0]), float(ph[0])))


def groove_forces(fn, p, beta, phi, xi, F, m=np):
    """T6: (Fz, Fx, Fy, Fz_mod) [N] on the groove from the normal force fn [N], p, beta [1],
    the pitch phi and roll tilt xi [rad] (numpy arrays, or floats with m = SCALAR), F the
    pressing load [N]."""
    Fz = -fn * (p * m.sin(phi) + beta * m.cos(phi))
    Fx = fn * (m.sqrt(1.0 - p * p) + p * p - p * xi)
    # T1 on the groove: the ideal bearing takes no force along the trunnion axis
    # a = (sin xi, cos xi cos phi, cos xi sin phi), so F . a = 0 gives Fy
    Fy = -(Fx * m.sin(xi) + Fz * m.cos(xi) * m.sin(phi)) / (m.cos(xi) * m.cos(phi))
    if m is SCALAR:
        return Fz, Fx, Fy, fz_mod(Fx, Fz, F)
    return Fz, Fx, Fy, np.vectorize(fz_mod, otypes=[float])(Fx, Fz, F)


def regime_of(g_max, o3, o3_eq27) -> str:
    """The regime from the friction's reach and the order-3 change against Eq. (27)."""
    if g_max < MICRO_SLIP_G:
        return "micro-slip"
    c = o3[0] * np.exp(1j * math.radians(o3[1]))
    c27 = o3_eq27[0] * np.exp(1j * math.radians(o3_eq27[1]))
    if abs(c27) > 0 and abs(c - c27) <= FULL_SLIP_REL * abs(c27):
        return "full slip"
    return "traverse"

