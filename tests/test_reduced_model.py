"""Physics tests of the reduced model (Eqs. 1-8, 18-27).

Reference values are derived here independently: trig identities, the Jacobi-Anger/Taylor
error of the small-angle pitch, and hand-computed amplitudes from the paper's formulas.
"""
import math

import numpy as np
import pytest

from reduced_model import kinematics as kin
from reduced_model import scene as sc
from reduced_model.analysis import analytic_report
from reduced_model.orders import last_cycle_orders, order_component
from reduced_model.thrust import closed_form, time_series

DEG = math.pi / 180

# Scenes far from the default: each changes one thing by a large factor.  Angles stay at or
# below 8 deg here because Eq. (27) takes sin(phi) ~ theta sin wt, whose own error in order 3
# is theta^2/8 (0.24 % at 8 deg, 1.5 % at 20 deg; tested separately below).
FAR_SCENES = {
    "default": {},
    "angle 5 deg": {"theta": 5 * DEG},
    "angle 8 deg, 30 Hz": {"theta": 8 * DEG, "omega": 2 * math.pi * 30},
    "speed 2 Hz": {"omega": 2 * math.pi * 2},
    "load 8 kN": {"F_press": 8000.0},
    "friction 0.15, v_st 2 mm/s": {"mu_groove": 0.15, "v_st": 0.002},
    "geometry": {"s": 0.035, "r_roller": 0.025, "r_groove": 0.0253, "r_bore": 0.015},
    "pitch only": {"yaw": False, "roll": False, "axial": False},
    "no spin inertia": {"spin_inertia": False},
}


@pytest.mark.parametrize("name", list(FAR_SCENES))
def test_fft_matches_closed_form(name):
    r = analytic_report(FAR_SCENES[name])
    for k in ("order1", "order3"):
        fft, cf = r[k], r["closed_form"][k]
        assert fft["amplitude"] > 0.1
        assert abs(fft["amplitude"] / cf["amplitude"] - 1) < 0.005, (k, fft, cf)
        dp = (fft["phase_deg"] - cf["phase_deg"] + 180) % 360 - 180
        assert abs(dp) < 0.5, (k, fft, cf)


def test_default_scene_against_hand_values():
    # model.md: A = 21.05 mm/s, B = -18.42 mm/s, v_st = 6.99 mm/s, C = 69.8 N, beta = -131.2 deg
    w, th = 20 * math.pi, 10 * DEG
    A = 0.022 * w * th**2 / 2
    B = -0.019 * w * (1 - math.cos(th)) / math.cos(th)
    cf = closed_form(sc.validate())
    assert cf["A"] == pytest.approx(A, rel=1e-12)
    assert cf["B"] == pytest.approx(B, rel=1e-12)
    assert cf["v_st"] == pytest.approx(math.hypot(A, B) / 4, rel=1e-12)
    # tanh(12 sin u) is nearly a square wave: C just below 4/pi mu F = 70.03 N
    assert 69.0 < cf["C"] < 4 / math.pi * 55.0
    assert cf["beta_deg"] == pytest.approx(math.degrees(math.atan2(-A, B)), abs=1e-9)
    assert cf["beta_deg"] == pytest.approx(-131.2, abs=0.05)


def test_small_angle_pitch_error_in_order3_is_theta2_over_8():
    # sin(theta sin x) = 2 J1(theta) sin x + ...; 2 J1(theta)/theta = 1 - theta^2/8 + O(theta^4)
    for deg in (15, 20, 25):
        th = deg * DEG
        r = analytic_report({"theta": th, "spin_inertia": False})
        ratio = r["order3"]["amplitude"] / r["closed_form"]["order3"]["amplitude"]
        assert ratio == pytest.approx(1 - th**2 / 8, abs=0.1 * th**2 / 8 + 2e-4), deg


def test_phase_convention_of_eq27():
    # order 3 of ftz at beta, order 1 at beta + 180 deg (model.md), checked on the FFT
    r = analytic_report({"spin_inertia": False})
    beta = r["beta_deg"]
    d3 = (r["friction"]["order3"]["phase_deg"] - beta + 180) % 360 - 180
    d1 = (r["friction"]["order1"]["phase_deg"] - (beta + 180) + 180) % 360 - 180
    assert abs(d3) < 0.5 and abs(d1) < 0.5


def test_order_analysis_sine_convention():
    x = 2 * np.pi * np.arange(720) / 720
    y = 2.5 * np.sin(3 * x + math.radians(-40)) + 1.0 * np.sin(x + math.radians(170))
    assert order_component(y, 3) == pytest.approx((2.5, -40.0), abs=1e-9)
    assert order_component(y, 1) == pytest.approx((1.0, 170.0), abs=1e-9)
    # a run of 2.3 cycles at non-uniform rate: last whole cycle, phase referred to x = 0
    t = np.linspace(0, 1, 5001)
    xr = 2 * np.pi * 2.3 * t
    res = last_cycle_orders(t, 2.5 * np.sin(3 * xr + math.radians(-40)), xr, orders=(1, 3))
    assert res[3][0] == pytest.approx(2.5, rel=1e-4)
    assert res[3][1] == pytest.approx(-40.0, abs=0.05)
    assert res[1][0] < 1e-4


@pytest.mark.parametrize("over", [{"theta": 0.0}, {"omega": 0.0}, {"theta": 0.0, "omega": 0.0}])
def test_zero_angle_or_speed_gives_zero_thrust(over):
    s = sc.validate(over)
    x = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    ts = time_series(s, x)
    for k, v in ts.items():
        assert np.all(np.isfinite(v)), k
    assert np.max(np.abs(ts["Fz"])) == 0.0
    r = analytic_report(over)
    for k in ("order1", "order3"):
        assert r[k]["amplitude"] == 0.0 and r["closed_form"][k]["amplitude"] == 0.0
        assert math.isfinite(r[k]["phase_deg"])


@pytest.mark.parametrize("over", [{}, {"theta": 20 * DEG, "omega": 100.0}])
def test_three_rollers_cancel_order1_and_triple_order3(over):
    r = analytic_report(over)
    j = r["three_rollers"]
    assert j["order1"]["amplitude"] < 0.01 * j["order3"]["amplitude"]
    assert j["order3"]["amplitude"] == pytest.approx(3 * r["order3"]["amplitude"], rel=0.01)


def _convergence_ratio(err, th):
    return err(th) / err(th / 2)


def test_small_angle_kinematics_error_orders():
    x = np.linspace(0, 2 * np.pi, 721)
    s = 0.022

    def e_pitch(th):   # Eq. 1 vs 2: arctan(tan th sin x) - th sin x = O(th^3)
        return np.max(np.abs(kin.pitch_exact(x, th) - kin.pitch_small(x, th)))

    def e_yaw(th):
        return np.max(np.abs(kin.yaw_exact(x, th) - kin.yaw_small(x, th)))

    def e_roll(th):    # Eq. 5 vs 6: arcsin(u) - u with u = O(th^2): O(th^6)
        return np.max(np.abs(kin.roll_exact(x, th, s) - kin.roll_small(x, th)))

    def e_axial(th):   # Eq. 7 vs 8: s (1 - cos xi) = O(xi^2) = O(th^4)
        return np.max(np.abs(kin.axial_exact(x, th, s) - kin.axial_small(x, th, s)))

    th = 0.1
    assert _convergence_ratio(e_pitch, th) == pytest.approx(8, rel=0.02)
    assert _convergence_ratio(e_yaw, th) == pytest.approx(8, rel=0.02)
    assert _convergence_ratio(e_roll, th) == pytest.approx(64, rel=0.05)
    assert _convergence_ratio(e_axial, th) == pytest.approx(16, rel=0.02)
    # and the leading terms themselves: pitch error ~ th^3/3 * max|sin x cos^2 x ...| bounded
    assert e_pitch(th) < th**3 / 2
    # exact roll satisfies Eq. 5 identically
    xi = kin.roll_exact(x, th, s)
    assert np.allclose(np.sin(xi), kin.eccentricity(s, th) * np.sin(2 * x) / s, atol=1e-15)


@pytest.mark.parametrize("over,needle", [
    ({"bogus": 1.0}, "bogus"),
    ({"theta": 45 * DEG}, "theta"),
    ({"theta": -0.1}, "theta"),
    ({"F_press": -2e5}, "F_press"),     # (negative: coast, allowed down to -1e5 N)
    ({"omega": -2e4}, "omega"),         # (negative: reverse whirl, allowed down to -1e4)
    ({"omega": float("nan")}, "omega"),
    ({"mu_groove": float("inf")}, "mu_groove"),
    ({"r_groove": 0.0185}, "r_groove"),
])
def test_bad_input_names_parameter(over, needle):
    with pytest.raises(ValueError, match=needle):
        sc.validate(over)


def test_cycle_orders_between_samples():
    # omega 500 rad/s sampled at 1e-4 s: 125.66 samples a whirl cycle, so the earlier cycles'
    # ends fall between samples (compare and the settle watch used to stop there with "less
    # than one whole whirl cycle").  A known periodic signal over just three cycles:
    from reduced_model import steady
    w, dt = 500.0, 1e-4
    t = np.arange(0.0, 3 * 2 * np.pi / w + dt, dt)
    x = w * t
    y = 5.0 * np.sin(x + 0.7) + 6.0 * np.sin(3 * x - 2.5)
    # linear resampling errs by at most dx^2 / 8 max|y''| = (0.05 rad)^2 / 8 x 59 N = 0.018 N
    tol = (w * dt) ** 2 / 8 * (5.0 + 9 * 6.0)
    for back in range(3):
        o = steady.cycle_orders(t, y, x, back)
        assert abs(o[1][0] - 5.0) < tol and abs(o[3][0] - 6.0) < tol
        # order k is a sin(k x + p): p = 0.7 rad and -2.5 rad; a window off by one sample
        # would turn order 3 by 3 x 0.05 rad
        assert abs(np.radians(o[1][1]) - 0.7) < tol / 5.0
        assert abs(np.radians(o[3][1]) + 2.5) < tol / 6.0
    ch = steady.cycle_change(t, y, x)
    assert all(c["complex_rel"] < 2 * tol / 5.0 for c in ch.values())


def test_transition_velocity_floor_at_standstill():
    """At rest the automatic v_st would vanish; both models take friction.V_ST_FLOOR there,
    and that floor means what docs/model.md says: a contact held at 99 % of mu f_n creeps
    under the tanh law about as far in a second as a Hertz contact of the default geometry
    deforms elastically before it slides (Mindlin's 3 mu P (2 - nu) / (8 G a) at 1 kN, G and
    the contact ellipse computed here from E, nu and the Hertz point; within a factor 2:
    measured 0.88 um of creep against 0.50 um)."""
    from reduced_model.friction import V_ST_FLOOR
    from reduced_model.hertz import hertz_point
    from reduced_model.thrust import transition_velocity
    rest = sc.validate({"omega": 0.0}, "analytic")
    assert transition_velocity(rest) == V_ST_FLOOR
    straight = sc.validate({"theta": 0.0}, "analytic")
    assert transition_velocity(straight) == V_ST_FLOOR
    assert transition_velocity(sc.validate({}, "analytic")) > 1000 * V_ST_FLOOR  # not active
    from tripod_model.model import JointModel
    roller = JointModel(sc.validate({"omega": 0.0}, "contact")).rollers[0]
    assert roller.v_st(rest["theta"], 0.0) == V_ST_FLOOR
    p = sc.defaults("analytic")
    _, a1, k = hertz_point(p["r_roller"], p["r_groove"], p["E"], p["nu"])
    a = a1 * 1000.0 ** (1 / 3)      # semi-major axis at 1 kN (Eq. 15), b = a / k
    b = a / k
    G = p["E"] / (2 * (1 + p["nu"]))
    slip_start = 3 * p["mu_groove"] * 1000.0 * (2 - p["nu"]) / (8 * G * math.sqrt(a * b))
    creep = V_ST_FLOOR / 3 * math.atanh(0.99) * 1.0       # [m] in one second
    assert slip_start / 2 < creep < slip_start * 2


@pytest.mark.parametrize("k", [1e-3, 0.3, 3.0, 12.0, 100.0, 1e3])
def test_eq25_amplitude_against_adaptive_quadrature(k):
    """C of Eq. (25) against scipy's adaptive quadrature of its integral (an independent
    method): within 1e-11 relative (quad is asked for 1e-12; the trapezoid rule's own error is
    below 1e-15 by its pole distance)."""
    from scipy.integrate import quad
    from reduced_model.thrust import second_order_amplitude
    F, mu = 1000.0, 0.06
    ref = quad(lambda u: np.tanh(k * np.sin(u)) * np.sin(u), 0.0, np.pi, epsabs=1e-14,
               epsrel=1e-13, limit=400)[0] * F * mu * 2.0 / np.pi
    assert second_order_amplitude(F, mu, k * 0.01, 0.03) == pytest.approx(ref, rel=1e-11)


def test_eq25_amplitude_limits():
    """Coulomb friction (v_st = 0): C = 4/pi F mu; a steep tanh (k = 3e4, past the switch to the
    boundary-layer series) within pi^2/(12 k^2) of it, and both branches agree at the switch."""
    from reduced_model.thrust import second_order_amplitude as C
    F, mu = 1000.0, 0.06
    coulomb = 4.0 / np.pi * F * mu
    assert C(F, mu, 0.01, 0.0) == pytest.approx(coulomb, rel=1e-15)
    k = 3e4
    assert C(F, mu, k * 0.01, 0.03) == pytest.approx(coulomb * (1 - np.pi ** 2 / (24 * k * k)),
                                                     rel=1e-14)
    below, above = C(F, mu, 1e4 * 0.01 * (1 - 1e-12), 0.03), C(F, mu, 1e4 * 0.01 * (1 + 1e-12), 0.03)
    assert below == pytest.approx(above, rel=1e-13)
