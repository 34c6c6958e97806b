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
(roller_setup.place_on_cycle, which the FMU's binary compiles too).  This module gives the
model the settled cycle (a Traverse, cached), without numba.  How close the start is: docs/integrators.md, "The start".
"""
from __future__ import annotations

from functools import lru_cache

from reduced_model import scene as scene_mod
from reduced_model.traverse import Traverse
from .roller_setup import PARAM_NAMES, uses_table

_TABLE_KEYS = tuple(scene_mod.defaults("analytic"))


@lru_cache(maxsize=8)
def _table(items):
    return Traverse(dict(items))


def traverse_table(p: dict, theta, omega, F, plunge_speed):
    """The traverse model's periodic table at these inputs (a joint's rollers share it), or
    None where it does not hold the roller (it then starts at the groove bottom, at rest
    along the trunnion): coast or reverse whirl (F <= 0 or omega <= 0), no groove friction,
    mu_groove >= 1, ``traverse`` off (the slide locked), or a scene whose cycle the model
    does not settle or solve."""
    if not uses_table(params_array(p), omega, F):
        return None
    sc = {k: p[k] for k in _TABLE_KEYS}
    sc.update(theta=theta, omega=omega, F_press=F, torque=0.0, plunge_speed=plunge_speed)
    try:
        table = _table(tuple(sorted(sc.items())))
    except (ValueError, ArithmeticError):   # a scene the traverse model cannot solve
        return None
    return table if table.settled else None


def params_array(p: dict) -> list:
    """The table's values T (roller_setup.PARAM_NAMES' order, floats) of the scene p."""
    return [float(p[n]) for n in PARAM_NAMES]
