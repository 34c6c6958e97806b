"""When a run is periodic: orders of the last whole whirl cycle against the cycle before.

A run that starts from rest needs a few whirl cycles before the roller's traverse settles
(at a small joint angle and a large groove clearance about ten).  ``cycle_change`` measures the
change of orders 1 and 3 from one whole cycle to the next; ``settled`` says whether the run is
periodic within a tolerance, counting the drift still to come: the changes of a settling
traverse shrink geometrically, so the drift after the last cycle is estimated from the last two
changes as a geometric series.
"""
from __future__ import annotations

import math

import numpy as np

from .orders import last_cycle_orders
from .scene import BEARING_IDEAL, BEARING_RESOLVED

ORDERS = (1, 3)
REL_TOL = 1e-3      # |complex change| / amplitude: amplitude within 0.1 %, phase within 0.06 deg
FLOOR = 0.01        # an order below 1 % of the largest one is judged against that 1 %
MIN_CYCLES = 3      # two changes: the last one and the drift still to come
NOISE = 1e-7        # a change below this is the integrator's noise, settled whatever its trend
MAX_CYCLES = 40     # the cap
REL_TOL_RESOLVED = 1e-2   # needle-resolved bearing: its chaotic row moves order 3 by about 1 %


def tolerance_for(scene: dict) -> float:
    """The cycle-to-cycle tolerance a scene can meet: REL_TOL, or the needle row's chaos floor
    REL_TOL_RESOLVED with the resolved bearing (bearing = 2)."""
    return REL_TOL_RESOLVED if scene.get("bearing", BEARING_IDEAL) == BEARING_RESOLVED else REL_TOL


def _complex(o):
    return {k: a * np.exp(1j * math.radians(p)) for k, (a, p) in o.items()}


def whole_cycles(whirl_angle) -> int:
    """Whole whirl cycles [1] a run of whirl angles [rad] holds."""
    x = np.asarray(whirl_angle, float)
    return int(math.floor((x[-1] - x[0]) / (2 * math.pi) + 1e-9))


def cycle_orders(t, y, whirl_angle, back=0, orders=ORDERS):
    """Orders of ``y`` over the whole cycle that ends ``back`` cycles before the run's end.
    {k: (amplitude, phase_deg)}."""
    x = np.asarray(whirl_angle, float)
    return last_cycle_orders(t, y, x, orders, x_end=x[-1] - 2 * math.pi * back)


def cycle_change(t, y, whirl_angle, orders=ORDERS, floor=FLOOR) -> dict:
    """Change of each order from the cycle before the last to the last whole cycle.

    Returns {k: {"amplitude_rel", "phase_deg", "complex_rel", "drift_rel"}}: the amplitude's
    relative change, the phase change [deg], |c_n - c_(n-1)| over the order's scale (its
    amplitude, or ``floor`` times the largest order's), and the drift still to come estimated
    from the last two changes (inf when they do not shrink; nan with fewer than 3 cycles).
    """
    n = whole_cycles(whirl_angle)
    if n < 2:
        raise ValueError(f"a cycle-to-cycle change needs two whole cycles; the run has {n}")
    c = [_complex(cycle_orders(t, y, whirl_angle, b, orders)) for b in range(min(n, 3))]
    top = max(abs(v) for v in c[0].values())
    out = {}
    for k in orders:
        scale = max(abs(c[0][k]), floor * top, 1e-300)
        d1 = abs(c[0][k] - c[1][k]) / scale
        drift = math.nan
        if n >= 3:
            d2 = abs(c[1][k] - c[2][k]) / scale
            r = d1 / d2 if d2 > 0 else 0.0
            drift = d1 * r / (1 - r) if r < 0.95 else math.inf
        a0, a1 = abs(c[0][k]), abs(c[1][k])
        dp = math.degrees(np.angle(c[0][k])) - math.degrees(np.angle(c[1][k]))
        out[k] = {"amplitude_rel": (a0 - a1) / a1 if a1 > 0 else 0.0,
                  "phase_deg": (dp + 180.0) % 360.0 - 180.0 if min(a0, a1) > 0 else 0.0,
                  "complex_rel": d1, "drift_rel": drift}
    return out


def settled(change: dict, rel_tol=REL_TOL) -> bool:
    """True when every order's last change and its estimated drift to come are within rel_tol.
    ``change``: cycle_change's result (of one signal)."""
    return all(v["complex_rel"] <= NOISE or
               (v["complex_rel"] <= rel_tol and
                (math.isnan(v["drift_rel"]) or v["drift_rel"] <= rel_tol))
               for v in change.values())


def worst(changes: dict) -> dict:
    """The largest change over signals and orders: {"signal", "order", "complex_rel",
    "amplitude_rel", "phase_deg", "drift_rel"}; changes: {signal: cycle_change result}."""
    best = None
    for sig, ch in changes.items():
        for k, v in ch.items():
            if best is None or v["complex_rel"] > best["complex_rel"]:
                best = dict(v, signal=sig, order=k)
    return best
