"""The floating spider (spider = 1): the three rollers on one rigid spider whose centre and twist
come from the forces (docs/model.md, "The floating spider").  The references are derived here,
apart from the model: the equal loads and the lever of each trunnion from the torque balance of
a rigid tripod, and the spider's orbit from an exact rigid-body solve of three trunnions at 120
deg in the plane normal to the shaft, each reaching its groove at the pressing offset."""
import math

import numpy as np
import pytest
from scipy.optimize import fsolve

from reduced_model.scene import validate
from tripod_model import layout as K
from tripod_model.model import JointModel

S = 0.022              # the default pitch-circle radius [m]
W = 20 * math.pi       # the paper's whirl [rad/s]
F = 1000.0             # the paper's pressing load per roller [N]
DT = 1e-4


def run(params, theta_deg, cycles=3.0, torque=0.0):
    """Outputs of a JointModel over ``cycles`` whirl cycles at the paper's scene (arrays by
    name), the spider's header row after each step, and the model.  A free spider unless
    params say spider = 0."""
    j = JointModel(dict({"spider": 1}, **params, n_rollers=3))
    rows, heads = [], []
    for _ in range(int(round(cycles * 2 * math.pi / W / DT))):
        rows.append(j.step(DT, math.radians(theta_deg), W, 0.0 if torque else F, torque))
        heads.append(j.header.copy())
    return {k: np.array([r[k] for r in rows]) for k in rows[0]}, np.array(heads), j


def e_of(theta):
    """Eq. (5)'s eccentricity [m]."""
    return S * (1 - math.cos(theta)) / (2 * math.cos(theta))


def rigid_centre(theta, x, offset):
    """The centre (X, Y) [m] of a rigid spider whose three trunnions (at 120 deg in the plane
    normal to the shaft n) meet their grooves' mid-planes at the pressing offset [m] off each
    groove's centre line, by a direct solve.  n at roller 1's whirl angle x [rad]: tilted by
    theta, turned so that roller 1's pitch is theta sin x (model.md: Eq. 1 about the pressing
    direction x_1 = -Y, trunnion axis y_1 = X): n = (-sin th sin x, -sin th cos x, cos th)."""
    n = np.array([-math.sin(theta) * math.sin(x), -math.sin(theta) * math.cos(x),
                  math.cos(theta)])

    def axes(psi):
        v = np.array([1.0, 0.0, 0.0]) - n * n[0]
        v /= np.linalg.norm(v)
        out = []
        for i in range(3):   # v turned about n by psi + 120 i deg (Rodrigues)
            a = psi + 2 * math.pi * i / 3
            out.append(v * math.cos(a) + np.cross(n, v) * math.sin(a))
        return out

    def residual(z):
        c = np.array([z[0], z[1], 0.0])
        u = axes(z[2])
        res = []
        for i in range(3):
            a = 2 * math.pi * i / 3
            radial = np.array([math.cos(a), math.sin(a), 0.0])
            pressing = np.array([math.sin(a), -math.cos(a), 0.0])
            target = S * radial + offset * pressing + np.array([0.0, 0.0, z[6 + i]])
            res.extend(c + z[3 + i] * u[i] - target)
        return res

    z = fsolve(residual, [0, 0, 0, S, S, S, 0, 0, 0], xtol=1e-13)
    return z[0], z[1]


def test_a_free_spider_needs_three_rollers_and_no_resolved_row():
    with pytest.raises(ValueError, match="spider = 1 .free. needs n_rollers = 3"):
        validate({"spider": 1, "n_rollers": 1}, "contact")
    with pytest.raises(ValueError, match="bearing 0 or 1"):
        validate({"spider": 1, "n_rollers": 3, "bearing": 2}, "contact")


@pytest.mark.parametrize("bearing", [0, 1])
def test_at_a_small_angle_without_friction_the_loads_are_equal(bearing):
    """2 deg, friction off (groove and needles): the spider sits where Eq. (5) puts it and each
    trunnion carries torque / (3 s).  The levers differ by e/s = 3e-4 (Eq. 5) through the
    cycle, which moves the loads by as much; the bound is three times that."""
    r, _, _ = run({"friction_groove": False, "friction_needle": False, "bearing": bearing}, 2.0)
    p, _, _ = run({"friction_groove": False, "friction_needle": False, "bearing": bearing,
                   "spider": 0}, 2.0, cycles=1.0)
    rel = 3 * e_of(math.radians(2)) / S
    last = slice(len(r["Fx"]) * 2 // 3, None)
    for k in ("F_roller_1", "F_roller_2", "F_roller_3", "Fx", "Fx_2", "Fx_3"):
        assert np.max(np.abs(r[k][last] / F - 1)) < rel, k
    # the thrust is the prescribed joint's: without friction nothing drives it along the groove
    assert np.max(np.abs(r["Fz_joint"])) < 1e-9 and np.max(np.abs(p["Fz_joint"])) < 1e-9


@pytest.mark.parametrize("theta_deg", [10.0, 25.0])
def test_without_friction_the_orbit_is_the_rigid_spiders(theta_deg):
    """10 and 25 deg, friction off: the spider's centre leaves Eq. (5)'s orbit by what the twist
    that takes up the groove's clearance moves a rigid spider's centre (the rigid spider with its
    trunnions at the pressing offset x0 against the one at 0: 4.7 um at 10 deg, 32 um at 25 deg),
    within the contact's compliance: the Hertz approach at the load, 4.9 um at 1000 N
    (model.md), bounds how far a trunnion's offset moves with its load; the spider's centre, a
    combination of three, moves less.  (The rigid solve's own orbit differs from Eq. (5)'s
    circle at second order in theta, 0.1 mm at 25 deg: the paper's forms are what the model
    drives, so the twist's shift is what is compared.)"""
    theta = math.radians(theta_deg)
    r, _, j = run({"friction_groove": False}, theta_deg, cycles=1.5)
    x0 = j.rollers[0]._OP[K.OP_X0]
    approach = (F / j.rollers[0].P[K.P_K]) ** (2 / 3)    # Hertz, Eq. (10)
    assert approach == pytest.approx(4.9e-6, rel=0.05)
    e = e_of(theta)
    worst = shift = 0.0
    for k in range(len(r["whirl_angle"]) // 2, len(r["whirl_angle"]), 60):
        x = r["whirl_angle"][k]
        X1, Y1 = rigid_centre(theta, x, x0)
        X0, Y0 = rigid_centre(theta, x, 0.0)
        dx, dy = r["spider_x"][k] - e * math.cos(2 * x), r["spider_y"][k] - e * math.sin(2 * x)
        worst = max(worst, math.hypot(dx - (X1 - X0), dy - (Y1 - Y0)))
        shift = max(shift, math.hypot(X1 - X0, Y1 - Y0))
    assert worst < approach, worst
    assert shift > 4e-6     # (the comparison tells the twist's shift from none)


@pytest.mark.parametrize("bearing", [0, 1])
def test_the_trunnions_moments_add_up_to_the_torque(bearing):
    """10 deg, friction off: sum_i F_i L_i = T at every sample, L_i the lever of trunnion i
    about the shaft axis, L_i = (s - e cos 2x_i)(cos^2 th + sin^2 th sin^2 x_i) / cos th (the
    transverse arm s - e cos 2x_i of Eq. (5)'s centre, turned into the plane normal to the
    shaft).  The lever neglects the pressing offset and the roller's slide along the trunnion
    (x0 tan xi / s, u / s: below 1e-3 here), and the spider's own angular acceleration (J psi''
    / T: below 1e-5); the bound is 1e-3 of T."""
    theta = math.radians(10)
    r, heads, _ = run({"friction_groove": False, "bearing": bearing}, 10.0, cycles=1.5)
    e = e_of(theta)
    x = r["whirl_angle"]
    moment = 0.0
    for i in range(3):
        xi = x + 2 * math.pi * i / 3
        lever = ((S - e * np.cos(2 * xi)) * (math.cos(theta) ** 2
                 + math.sin(theta) ** 2 * np.sin(xi) ** 2) / math.cos(theta))
        moment = moment + r[f"F_roller_{i + 1}"] * lever
    T = 3 * S * F
    last = slice(len(x) // 3, None)
    assert np.max(np.abs(moment[last] / T - 1)) < 1e-3
    # the spider's own balance as it steps: the rollers' generalized moment against T
    assert np.max(np.abs(heads[last, K.OP_SP_GPSI] + T)) < 1e-3 * T


@pytest.mark.parametrize("bearing", [0, 1])
def test_the_forces_on_the_spider_are_its_mass_times_its_acceleration(bearing):
    """Paper's scene with friction, 10 deg: the rollers' forces on the spider across the shaft
    (the step's generalized force, OP_SP_GX, GY) equal its mass times its acceleration in space
    (the outputs' centre, turned with the housing, twice differenced; both sides through the
    same 5 ms moving mean, which the kHz ring of the spider on its contacts leaves and the
    orbit's 30 Hz passes).  Within what the model's equation leaves out, computed from the same
    outputs: the rotating frame's terms on the spider's pose off the orbit q, m_s (2 w |q'| +
    w^2 |q|); with the ideal bearing the rollers' inertia riding on the trunnions, 3 m_roller / 2
    |q''|; and the partitioned step's lag, the rollers' forces one substep h behind: twice F
    (e / s) 2 w h."""
    p = validate({}, "contact")
    ms = p["spider_mass"]
    r, heads, j = run({"bearing": bearing}, 10.0, cycles=1.5)
    t = np.arange(1, len(r["Fx"]) + 1) * DT
    c, s_ = np.cos(W * t), np.sin(W * t)     # the housing turns at w in space (model.md)

    def d1(a):
        return (a[2:] - a[:-2]) / (2 * DT)

    def d2(a):
        return (a[2:] - 2 * a[1:-1] + a[:-2]) / DT ** 2

    def mean(a):
        return np.convolve(a, np.ones(50) / 50, mode="valid")

    ax = d2(c * r["spider_x"] - s_ * r["spider_y"])
    ay = d2(s_ * r["spider_x"] + c * r["spider_y"])
    gx, gy = heads[1:-1, K.OP_SP_GX], heads[1:-1, K.OP_SP_GY]
    Gx, Gy = c[1:-1] * gx - s_[1:-1] * gy, s_[1:-1] * gx + c[1:-1] * gy
    e, x = e_of(math.radians(10)), r["whirl_angle"]
    qx, qy = r["spider_x"] - e * np.cos(2 * x), r["spider_y"] - e * np.sin(2 * x)
    left_out = ms * (2 * W * mean(np.hypot(d1(qx), d1(qy)))
                     + W ** 2 * mean(np.hypot(qx, qy)[1:-1]))
    if bearing == 0:
        left_out += 1.5 * p["m_roller"] * mean(np.hypot(d2(qx), d2(qy)))
    lag = 2 * F * e / S * 2 * W * j.rollers[0]._OP[K.OP_H]
    err = np.hypot(mean(Gx) - ms * mean(ax), mean(Gy) - ms * mean(ay))
    last = slice(len(err) // 3, None)
    assert np.all(err[last] < left_out[last] + lag), np.max(err[last] - left_out[last])
    # (and the balance is not empty: the orbit's inertial force is 1.9 N)
    assert 9 * W ** 2 * e * ms > 4 * (left_out[last].max() + lag)


def test_a_torque_reversal_and_a_launch_stay_finite_and_bounded():
    """300 -> -300 N m over 0.2 s: the rollers cross the running clearance to the coast flank,
    the spider twists across it; and a launch's 3000 N m at 25 deg: every output finite, the
    loads within 10 % of torque / (3 s) and the spider within the clearance of its orbit."""
    j = JointModel({"n_rollers": 3, "spider": 1})
    loads = []
    for k in range(3000):
        tq = 300.0 if k < 500 else -300.0 if k > 2500 else 300.0 - 600.0 * (k - 500) / 2000
        o = j.step(DT, math.radians(10), W, 0.0, tq)
        assert all(math.isfinite(v) for v in o.values())
        loads.append((tq, o["F_roller_1"], o["F_roller_2"], o["F_roller_3"]))
    a = np.array(loads[-300:])
    assert np.all(np.abs(a[:, 1:] / (a[:, :1] / (3 * S)) - 1) < 0.1)
    r, _, _ = run({"spider": 1}, 25.0, cycles=1.0, torque=3000.0)
    for k, v in r.items():
        assert np.all(np.isfinite(v)), k
    last = slice(len(r["Fx"]) // 2, None)
    for i in (1, 2, 3):
        assert np.all(np.abs(r[f"F_roller_{i}"][last] / (3000.0 / (3 * S)) - 1) < 0.1)
    x = r["whirl_angle"]
    e = e_of(math.radians(25))
    off = np.hypot(r["spider_x"] - e * np.cos(2 * x), r["spider_y"] - e * np.sin(2 * x))
    assert np.max(off) < 2 * (0.0192 - 0.019) + 1e-4


def test_compare_sets_the_free_spider_beside_the_prescribed_one():
    """`tripod-thrust compare --set spider=1 --set n_rollers=3 --json`: the built FMUs, the free
    joint against the prescribed one and against the analytic FMU."""
    import json
    import subprocess
    import sys
    p = subprocess.run([sys.executable, "-m", "harness.cli", "compare", "--set", "spider=1",
                        "--set", "n_rollers=3", "--json"], capture_output=True, text=True,
                       timeout=900)
    assert p.returncode == 0, p.stderr[-2000:]
    r = json.loads(p.stdout)
    sp = r["spider"]
    assert r["scene"]["spider"] == 1 and r["pass"] is True
    # the paper's scene: order 3 of the joint's thrust, free within 15 % of prescribed
    # (measured -9.5 %, docs/validation.md); the orbit at 2x within 1 % of Eq. (5)'s e, turned
    # by no more than the twist's shift off the circle allows (4.8 um of e = 0.17 mm: 1.6 deg)
    assert abs(sp["order3_rel"]) < 0.15
    # order 3 follows the load (the friction's thrust is mu times the pressing force): the
    # prescribed joint's pressing force drifted up with the traverse, the free one's did not,
    # so free / prescribed is the inverse of that drift, within 2 points (the rest: the
    # levers' spread and the contact point's traverse, which the load moves too)
    drift = sp["fx_rel"]["prescribed"]
    assert drift > 0.05 and abs(sp["fx_rel"]["free"]) < 0.005
    assert sp["order3_rel"] == pytest.approx(1 / (1 + drift) - 1, abs=0.02)
    ob = sp["orbit"]
    assert ob["amplitude"] / ob["e"] == pytest.approx(1.0, abs=0.01)
    assert abs(math.radians(ob["phase_deg"])) <= 1.1 * ob["off_circle"] / ob["e"]
    assert ob["off_circle"] < 10e-6
    assert -0.05 < sp["loads"]["low_rel"] < 0.0 < sp["loads"]["high_rel"] < 0.05
    from harness.spider_superposition import format_spider
    assert "superposition" in format_spider(sp) and "spider orbit at 2x" in format_spider(sp)


def _spider_table_rows(rows):
    from harness import validation
    return [validation.spider_markdown([r]).splitlines()[2] for r in rows]


def test_the_spider_grid_table_holds_the_paper_scene_as_rerun():
    """docs/validation.md's spider grid, its paper's rows rerun: the rows as written; at the
    paper's scene, order 1 cancelled in both joints, the orbit at 2x within 0.1 % of Eq. (5)'s
    e, and the free spider holding roller 1's mean pressing force within 0.5 % of the load
    where the prescribed joint's drifts above it with the traverse."""
    from harness import validation
    rows = validation.spider_rows({"paper (section 3.1)": {}})
    doc = (validation.ROOT / "docs" / "validation.md").read_text()
    for line in _spider_table_rows(rows):
        assert line in doc, "docs/validation.md is stale: make docs"
    for r in rows:
        for joint in ("free", "prescribed"):
            o = r["Fz_joint"][joint]
            assert o["order1"]["amplitude"] < 1e-3 * o["order3"]["amplitude"]
        assert r["orbit"]["amplitude"] / r["orbit"]["e"] == pytest.approx(1.0, abs=1e-3)
    ideal = rows[0]
    assert abs(ideal["fx_rel"]["free"]) < 0.005 < ideal["fx_rel"]["prescribed"]


@pytest.mark.slow
def test_the_spider_grid_table_is_current():
    """The whole spider grid rerun (about 3 minutes): docs/validation.md's table as written."""
    from harness import validation
    doc = (validation.ROOT / "docs" / "validation.md").read_text()
    assert validation.spider_markdown(validation.spider_rows()) in doc
