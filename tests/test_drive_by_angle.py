"""Driving the whirl by angle (drive_by_angle, input shaft_angle) instead of by omega: a master
that integrates the shaft angle itself sets, at each communication point, the angle for the
end of the step; the FMU's whirl_angle lands on it and the thrust is the omega-driven one."""
import math

import numpy as np
import pytest

from harness.fmus import ensure_fmu
from harness.runs import run_fmu
from harness.input_transients import RUNUP_START, revolution_orders

DT, T = 1e-4, 0.3


@pytest.mark.parametrize("name", ["TripodRoller", "TripodRollerAnalytic"])
def test_driving_by_angle_equals_driving_by_omega(name):
    # a run-up 4 -> 12 Hz: by omega, FMPy holds omega(t_n) over each step, so the whirl angle
    # at t_n+1 is the sum of omega(t_k) dt; by angle, the master sets exactly that sum for the
    # end of each step (its input table shifted by one step): the two runs are the same motion
    t = DT * np.arange(int(round(T / DT)) + 1)
    w = 2 * math.pi * (4.0 + 8.0 * t / T)
    x_end = np.concatenate([[0.0], np.cumsum(w[:-1] * DT)])      # whirl angle at t_n
    by_omega = run_fmu(ensure_fmu(name), RUNUP_START, stop_time=T, output_interval=DT,
                       outputs=["Fz_joint", "whirl_angle"],
                       inputs={"time": list(t), "omega": list(w)})
    # the angle for the end of the step starting at t_n is x_end[n + 1]
    by_angle = run_fmu(ensure_fmu(name), dict(RUNUP_START, drive_by_angle=True, omega=w[0]),
                       stop_time=T, output_interval=DT, outputs=["Fz_joint", "whirl_angle"],
                       inputs={"time": list(t[:-1]), "shaft_angle": list(x_end[1:])})
    n = min(len(by_omega["time"]), len(by_angle["time"]))
    # the whirl angles: the same sums, up to the rounding of (target - x) / dt * dt, a few ulps
    # of x (<= 30 rad) a step over 3000 steps: far below 1e-9 rad
    assert np.allclose(by_angle["whirl_angle"][:n], by_omega["whirl_angle"][:n],
                       rtol=0, atol=1e-9)
    a = revolution_orders(by_angle["time"][:n], by_angle["whirl_angle"][:n],
                          by_angle["Fz_joint"][:n])
    b = revolution_orders(by_omega["time"][:n], by_omega["whirl_angle"][:n],
                          by_omega["Fz_joint"][:n])
    assert len(a) >= 2
    for ra, rb in zip(a, b):
        assert abs(ra["order3"] / rb["order3"] - 1) < 1e-3
