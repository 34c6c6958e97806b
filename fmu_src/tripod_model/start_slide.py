"""Where the roller starts along the trunnion: on the settled cycle of the reduced traverse model.

Started at the groove bottom and at rest along the trunnion, a roller whose friction
saturates is thrown up the flank and rocks across the groove at sqrt(F / (m rho)) (the
roller's ring, docs/integrators.md) for 50-200 steps, which the generalized-alpha step resolves
at up to 11 substeps.  The reduced traverse model (reduced_model/traverse.py) gives the settled
cycle's tilt of the contact normal towards the trunnion axis, p(x) = n.a; the slide u that
gives that tilt, its rate, and the spin at which the roller then rolls without slip across the
trunnion axis start the roller where steady running has it (ideal and lumped bearing; with
the needle-resolved row the roller starts at the groove bottom).  The trunnion's line and the
contact slip come from the kernel itself, probed at the start state without a step
(ContactModel.probe), so this module needs no numba: the prebuilt kernel's process never
imports it.  How close the start is: docs/integrators.md, "The start".
"""
from __future__ import annotations

import math
from functools import lru_cache

from reduced_model import scene as scene_mod
from reduced_model.traverse import Traverse
from . import layout as K
from .oppoint import groove_offset

_TABLE_KEYS = tuple(scene_mod.defaults("analytic"))
DX = 1e-4   # whirl-angle step of p's slope [rad]: within one of the table's intervals


@lru_cache(maxsize=8)
def _table(items):
    return Traverse(dict(items))


def traverse_table(p: dict, theta, omega, F, plunge_speed):
    """The traverse model's periodic table at these inputs (a joint's rollers share it), or
    None where it does not hold the roller (it then starts at the groove bottom, at rest
    along the trunnion): coast or reverse whirl (F <= 0 or omega <= 0), no groove friction,
    mu_groove >= 1, ``traverse`` off (the slide locked), or a scene whose cycle the model
    does not settle or solve."""
    if not (F > 0.0 and omega > 0.0 and p["traverse"] and p["friction_groove"]
            and 0.0 < p["mu_groove"] < 1.0):
        return None
    sc = {k: p[k] for k in _TABLE_KEYS}
    sc.update(theta=theta, omega=omega, F_press=F, torque=0.0, plunge_speed=plunge_speed)
    try:
        table = _table(tuple(sorted(sc.items())))
    except (ValueError, ArithmeticError):   # a scene the traverse model cannot solve
        return None
    return table if table.settled else None


def tilt_and_rate(table, x, omega):
    """p [1] of the table's settled cycle at whirl angle x [rad], and its rate dp/dt [1/s]."""
    p = table.state_at(x)[1]
    slope = (table.state_at(x + DX)[1] - table.state_at(x - DX)[1]) / (2.0 * DX)
    return p, slope * omega


def slide_for_tilt(tilt, rate, D, a, ad, sweeps=8):
    """Slide u [m] of the roller centre along the trunnion axis a = (ax, ay) (its x and y
    components; ad their rates [1/s]) that tilts the contact normal towards a by n.a = tilt
    [1], and u' [m/s] that keeps n.a on tilt's rate [1/s].  The centre is at (D + u ax, u ay)
    [m] from the facing flank's arc centre in the groove's cross-section
    (contact.groove_contact), so that u q = tilt rho - D ax with q = ax^2 + ay^2 and rho the
    centre's distance; a fixed point on rho, which the slide changes by its square only
    (|ax| << 1: 8 sweeps reach rounding), and that relation's time derivative, linear in u'."""
    ax, ay = a
    adx, ady = ad
    q = ax * ax + ay * ay
    u = 0.0
    for _ in range(sweeps):
        rho = math.hypot(D + u * ax, u * ay)
        u = (tilt * rho - D * ax) / q
    cx, cy = D + u * ax, u * ay
    rho = math.hypot(cx, cy)
    # d/dt: u' q + u q' = rate rho + tilt rho' - D ax', rho' = (cx cx' + cy cy') / rho
    # with cx' = u' ax + u ax', cy' = u' ay + u ay'
    qd = 2.0 * (ax * adx + ay * ady)
    coef = q - tilt * (cx * ax + cy * ay) / rho
    rhs = rate * rho + tilt * (cx * u * adx + cy * u * ady) / rho - D * adx - u * qd
    return u, rhs / coef


def slip_across(L, res):
    """The contact point's slip [m/s] across the trunnion axis: along b = a x n / |a x n|, the
    direction in which the spin about a moves the contact point (a the trunnion axis in L, n
    the contact normal and v_t the slip in res: contact.groove_contact).  The slip along a is
    the slide's."""
    ax, ay, az = L[K.L_AX], L[K.L_AY], L[K.L_AZ]
    nx, ny = res[K.R_NX], res[K.R_NY]
    bx, by, bz = -az * ny, az * nx, ax * ny - ay * nx
    return (res[K.R_VTX] * bx + res[K.R_VTY] * by + res[K.R_VTZ] * bz) / math.sqrt(
        bx * bx + by * by + bz * bz)


def rolling_spin(om0, v0, v1):
    """Spin [rad/s] at which the roller rolls without slip across the trunnion axis, from that
    slip v0 at spin om0 and v1 at om0 + 1 [m/s] (slip_across; linear in the spin); om0 where
    the spin moves no slip (the roller off its flank: a load too light to press it on)."""
    d = v1 - v0
    return om0 - v0 / d if d != 0.0 else om0


def place_on_cycle(m, table, theta, omega, F, vp):
    """Put the roller of ContactModel m (at its start state, at the groove bottom) where the
    table's settled cycle has it: the slide and its rate, and the spin at which it then rolls
    without slip across the trunnion axis, from the kernel's trunnion line and contact at that
    state (m.probe).  theta [rad], omega [rad/s], F [N], vp [m/s]: the start's inputs."""
    Y = m.Y
    L = m.probe(theta, omega, F, vp)[0]
    tilt, rate = tilt_and_rate(table, Y[K.Y_X], omega)
    Y[K.Y_U], Y[K.Y_UD] = slide_for_tilt(tilt, rate, groove_offset(m.P, F) - m.P[K.P_FLANK],
                                         (L[K.L_AX], L[K.L_AY]), (L[K.L_ADX], L[K.L_ADY]))

    def across(om):   # the slip across the trunnion axis [m/s] at spin om
        Y[K.Y_OM] = om
        return slip_across(*m.probe(theta, omega, F, vp))
    om0 = Y[K.Y_OM]
    Y[K.Y_OM] = rolling_spin(om0, across(om0), across(om0 + 1.0))
    if not all(math.isfinite(Y[i]) for i in (K.Y_U, K.Y_UD, K.Y_OM)):
        Y[K.Y_U], Y[K.Y_UD], Y[K.Y_OM] = 0.0, 0.0, om0   # the groove bottom, at rest
