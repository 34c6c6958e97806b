"""The driveline example: the powertrain model against closed forms, the launch system file
run by FMPy and libcosim (each in a fresh process), the coupled loop converged, the contact
and analytic joint agreeing in it."""
import math

import numpy as np
import pytest

from driveline import powertrain as pt
from harness import example as E

P = pt.defaults()


def test_mounts_free_vibration_is_the_damped_oscillator():
    """The exact (matrix-exponential) step against the closed-form free response of a
    viscously damped oscillator, x0 e^(-z w t) (cos wd t + z / sqrt(1 - z^2) sin wd t):
    exact in the method, so rounding only."""
    m = pt.Mounts(P)
    x = np.zeros(8)
    x[1] = 1e-3
    h, n = 1e-3, 300
    for _ in range(n):
        x = m.step(x, np.zeros(4), h)
    w = math.sqrt(P["k_y"] / P["mass"])
    z = P["c_y"] / (2 * math.sqrt(P["k_y"] * P["mass"]))
    wd, t = w * math.sqrt(1 - z * z), n * h
    ref = 1e-3 * math.exp(-z * w * t) * (math.cos(wd * t) + z / math.sqrt(1 - z * z) * math.sin(wd * t))
    assert x[1] == pytest.approx(ref, abs=1e-12)
    # a held force settles on the static deflection F / k (8 s: the transient below 1e-15)
    x = np.zeros(8)
    for _ in range(8000):
        x = m.step(x, np.array([0.0, 500.0, 0.0, 0.0]), h)
    assert x[1] == pytest.approx(500.0 / P["k_y"], rel=1e-9)


def test_joint_kinematics_closed_forms():
    """Lifting the joint by dz turns the shaft to asin(sin theta0 + dz / L); moving it
    outboard by dy pushes the spider into the housing by dy (plunge -dy); the plunge speed is
    the plunge's time derivative (central difference, O(h^2))."""
    L, th0 = P["shaft_length"], P["theta0"]
    q = np.array([0.0, 0.0, 0.004, 0.0])
    k = pt.joint_kinematics(q, np.zeros(4), P)
    assert k.theta == pytest.approx(math.asin(math.sin(th0) + 0.004 / L), rel=1e-12)
    k = pt.joint_kinematics(np.array([0.0, 0.003, 0.0, 0.0]), np.zeros(4), P)
    assert k.plunge == pytest.approx(-0.003, rel=1e-12)
    assert k.theta == pytest.approx(th0, rel=1e-12)
    q0, v = np.array([0.002, 0.001, -0.003, 0.01]), np.array([0.05, -0.02, 0.03, 0.4])
    h = 1e-6
    fd = (pt.joint_kinematics(q0 + h * v, v, P).plunge -
          pt.joint_kinematics(q0 - h * v, v, P).plunge) / (2 * h)
    assert pt.joint_kinematics(q0, v, P).plunge_speed == pytest.approx(fd, rel=1e-6)


def test_launch_speed_is_the_torque_impulse():
    """The wheel speed against the torque's integral by quadrature: (m r^2) w = n int T dt."""
    from scipy.integrate import quad
    for t in (0.2, 0.5, 1.7):
        imp = quad(lambda s: pt.launch_torque(s, P), 0, t, points=[P["torque_rise_time"]])[0]
        ref = P["n_shafts"] * imp / (P["vehicle_mass"] * P["wheel_radius"] ** 2)
        assert pt.wheel_speed(t, P) == pytest.approx(ref, rel=1e-10)


def test_housing_force_turns_with_the_housing():
    """The radial force keeps its size and turns with the whirl angle about +y (X from +z
    towards +x); the axial force is along +y."""
    for psi in (0.0, 0.7, 2.5):
        fx, fy, fz = pt.housing_force(30.0, 100.0, -40.0, psi)
        assert fy == 30.0
        assert math.hypot(fx, fz) == pytest.approx(math.hypot(100.0, -40.0), rel=1e-14)
    assert pt.housing_force(0.0, 1.0, 0.0, 0.0) == pytest.approx((0.0, 0.0, 1.0))
    assert pt.housing_force(0.0, 1.0, 0.0, math.pi / 2) == pytest.approx((1.0, 0.0, 0.0))


def test_system_file_names_what_connects():
    """The SSD connects the powertrain's outputs to the joint's inputs of the same names and
    back; each component's start values sit in its parameter bindings."""
    from xml.etree import ElementTree as ET
    root = ET.fromstring(E.system_xml("contact"))
    ns = {"ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription"}
    pairs = {(c.get("startElement"), c.get("startConnector"), c.get("endElement"),
              c.get("endConnector")) for c in root.iterfind(".//ssd:Connection", ns)}
    assert pairs == {("powertrain", n, "joint", n) for n in E.TO_JOINT} | \
        {("joint", n, "powertrain", n) for n in E.TO_POWERTRAIN}
    with pytest.raises(ValueError, match="mass"):
        E.system_xml("contact", {"mass": 0.0})


@pytest.mark.parametrize("joint", ["contact", "analytic"])
def test_short_launch_both_tools(joint, tmp_path):
    """A few tenths of a second of the launch in both tools: every signal finite; the two
    differ only through the first step (FMPy's simulate_ssp hands every input 0 there,
    libcosim the outputs at initialisation), a difference that dies away."""
    ssp = E.write_ssp(tmp_path / "s.ssp", joint, stop=0.4)
    a, b = (E.run_system(ssp, tool, stop=0.4) for tool in E.TOOLS)
    assert len(a["time"]) == len(b["time"]) == 4000
    np.testing.assert_allclose(a["time"], b["time"], rtol=1e-12)
    for r in (a, b):
        assert all(np.isfinite(v).all() for v in r.values())
    t = a["time"]
    # the first step's transient, damped by the mounts (7 %, about 0.2 s an e-fold) and the
    # joint's friction, down to a floor set by where the two runs switch the contact FMU's
    # substep count (its integration error): in the last 0.1 s, of each signal's peak, the
    # mount acceleration 6.6e-4 as built and 1.5-2.2e-3 with the count's thresholds moved by
    # 0.5-2 %, Fz_joint 1.9e-5 (6.8e-5), theta 1.8e-7 (7.7e-7)
    for k, rel in (("powertrain.acc_y", 5e-3), ("joint.Fz_joint", 1e-3), ("powertrain.theta", 1e-3)):
        d = np.abs(a[k] - b[k])
        assert d[t > 0.3].max() < rel * np.abs(a[k]).max(), k
    d = np.abs(a["joint.Fz_joint"] - b["joint.Fz_joint"])
    assert d[t > 0.3].max() <= d[t <= 0.1].max()      # the difference dies away


def test_launch_converged_and_models_agree(tmp_path):
    """The whole launch (docs/driveline-example.md's table): FMPy and libcosim agree on the
    peak lateral acceleration to 1e-7 (the first step's transient has decayed by then); half
    the communication step moves the peak by less than 2 %; the analytic joint gives the
    contact joint's peak within 5 %; the peak lies in the shudder band (order 3 of the wheel
    on the powertrain's lateral mode, stiffened by the joint: 3-6 Hz wheel speed)."""
    r = E.launch(tmp_path, plots=False)
    c = r["checks"]
    assert c["contact: fmpy vs libcosim, peak"] < 1e-7
    assert c["analytic: fmpy vs libcosim, peak"] < 1e-7
    assert c["contact: step 0.0001 s -> 5e-05 s, peak"] < 0.02
    assert c["analytic vs contact, peak"] < 0.05
    for row in r["rows"]:
        assert 3.0 < row["wheel_hz"] < 6.0
        assert row["peak_acc_y"] > 1.0      # a shudder, not numerical noise


def test_cli_refuses_a_bad_powertrain_value(capsys):
    from harness.cli import main
    assert main(["example", "--set", "k_y=-5"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "k_y" in err[0] and "(0, 1e+09]" in err[0]
