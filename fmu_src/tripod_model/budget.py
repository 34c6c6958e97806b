"""The adaptive substeps' budget (steplib.adaptive_steps) and the line the FMU logs when a step
runs out of it.  Plain Python (no numba): the model imports it to word a refusal.
"""
from reduced_model.scene import MAX_SUBSTEPS, too_long  # noqa: F401  (kernel's, too)
from .layout import FAIL_ESTIMATE, FAIL_FLOOR, FAIL_LONG, FAIL_TRIES, H_FAIL, H_FAIL_DONE, H_FAIL_H, P_HMAX

# The adaptive substeps' budget, so that a step ends in bounded time whatever the state
# (a state a host set, a scene that drives the error estimate there):
# - the floor: ADAPT_FLOOR x the largest adaptive substep P[P_HMAX] (the scene's accuracy bound:
#   at most 1e-4 s and 1/1960 of a whirl cycle; oppoint.substep).  The extrapolated step's
#   error estimate falls as h^2: 1e8 below the largest substep it is 1e16 smaller, at
#   rounding's level, so a substep that still fails there has no smooth solution to resolve.
#   Ordinary scenes go down to 1e-5 x the largest (the lumped row's stiff modes after a step
#   input), a thousand times above it;
# - the tries: ADAPT_TRIES_MIN + ADAPT_TRIES_PER per largest substep in the span.  A step input's
#   boundary layer costs ordinary scenes up to about 5,000 tries whatever the span (the lumped
#   and needle-resolved rows' stiff modes), steady running a few per largest substep: ten times
#   both.  A step that exhausts it costs about 0.2 s a roller with the ideal or lumped bearing
#   (one try: three linearly implicit substeps), where an unbounded one ran for minutes.
# A non-finite error estimate stops at once: no smaller substep makes it finite.
# And a communication step takes at most MAX_SUBSTEPS substeps (its length over the substep the
# scene asks for; 2^20, about a second of work): a longer one is refused before it starts.
# How far ordinary scenes run from all three: python -m benchmarks.step_budget.
ADAPT_FLOOR = 1e-8
ADAPT_TRIES_MIN = 5e4
ADAPT_TRIES_PER = 100.0


WHY = {FAIL_ESTIMATE: "the error estimate is not finite",
       FAIL_FLOOR: f"the substep fell below its floor, {ADAPT_FLOOR:g} x the largest",
       FAIL_TRIES: f"the substeps tried reached their budget, {ADAPT_TRIES_MIN:g} + "
                   f"{ADAPT_TRIES_PER:g} per largest substep in the step"}
# the refusal of a step whose adaptive substeps ran out: a printf format of the share of the
# step done [%], the substep and the largest [s], for the reason {why} (WHY); the FMU's binary
# words it alike
ADAPT_REFUSAL = ("the adaptive substeps stopped at %.3g %% of the step ({why}; substep %.3g s, "
                 "largest %.3g s): the state cannot be stepped")


def adapt_refusal(why: str) -> str:
    """ADAPT_REFUSAL's format for the reason why."""
    return ADAPT_REFUSAL.replace("{why}", why)


def refusal(hs, P) -> str:
    """One line on why a step stopped short (hs[H_FAIL] != FAIL_NONE: adaptive_steps, or
    kernel.run_substeps for a step too long) and where, for the FMU's log."""
    if hs[H_FAIL] == FAIL_LONG:
        return too_long(hs[H_FAIL_DONE], hs[H_FAIL_H])
    return adapt_refusal(WHY.get(float(hs[H_FAIL]), "unknown")) % (
        100.0 * hs[H_FAIL_DONE], hs[H_FAIL_H], P[P_HMAX])
