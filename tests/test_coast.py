"""Coast and reverse whirl (issue: the driveline envelope, item 1), checked by the model's own
symmetry, derived here: turning the joint by 180 deg about the trunnion axis y maps x -> -x and
z -> -z.  Pitching (about x) and rolling (about z) change sign, yawing and the axial slide
(about and along y) do not; the pressing direction flips.  Reverse whirl, x(t) = -|w| t,
changes the sign of exactly the odd motions, pitching and rolling (Eqs. 1-8: sin x, sin 2x odd;
cos x, cos 2x even).  So drive at -w is coast at +w turned about y: Fx, Fz, contact_z and the
whirl angle flip, Fy, contact_y, the roller's spin and slip speed stay.  Any asymmetry in the
contact law, the integrators or the pressing offset breaks it.  The analytic FMU, which runs
coast through that symmetry, is checked against the contact FMU in all four quadrants."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from harness.fmus import ensure_fmu

_RUN = r'''
import json, sys
import numpy as np
from fmpy import simulate_fmu
req = json.loads(sys.argv[1])
inputs = None
if req.get("inputs"):
    names = [k for k in req["inputs"] if k != "time"]
    inputs = np.array(list(zip(req["inputs"]["time"], *(req["inputs"][k] for k in names))),
                      dtype=[("time", float)] + [(k, float) for k in names])
logs = []
try:
    r = simulate_fmu(req["fmu"], stop_time=req["stop"], output_interval=1e-4,
                     start_values=req["sv"], input=inputs,
                     logger=lambda c, n, s, cat, msg: logs.append(msg.decode()))
    np.save(req["out"], r)
    print(json.dumps({"ok": True, "log": logs}))
except Exception as e:
    print(json.dumps({"ok": False, "log": logs, "error": str(e)}))
'''
# output of the reverse run: (its image in the coast run, sign).  Roller 2 at +120 deg in one
# run is the roller at -120 deg = 240 deg, roller 3, in the other (x -> -x)
FLIP = {"Fz": ("Fz", -1), "Fx": ("Fx", -1), "Fy": ("Fy", 1), "contact_y": ("contact_y", 1),
        "contact_z": ("contact_z", -1), "whirl_angle": ("whirl_angle", -1),
        "roller_spin": ("roller_spin", 1), "slip_speed": ("slip_speed", 1),
        "Fz_joint": ("Fz_joint", -1), "Fz_2": ("Fz_3", -1), "Fx_2": ("Fx_3", -1),
        "Fy_2": ("Fy_3", 1), "Fz_3": ("Fz_2", -1)}


def run(name, sv, tmp_path, tag, stop=0.2, inputs=None):
    out = tmp_path / f"{tag}.npy"
    p = subprocess.run([sys.executable, "-c", _RUN, json.dumps(
        {"fmu": str(ensure_fmu(name)), "sv": sv, "out": str(out), "stop": stop,
         "inputs": inputs})], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    r = json.loads(p.stdout.strip().splitlines()[-1])
    return (np.load(out) if r["ok"] else None), r


@pytest.mark.parametrize("sv,rel", [
    ({}, 1e-10), ({"integrator": 1}, 1e-10),
    # rollers 2 and 3 sit at 2 pi/3 and 4 pi/3, whose images -2 pi/3 and -4 pi/3 are the same
    # angles up to 2 pi but not the same floats: rounding of the angle, carried by the stiff
    # contact over 2000 steps (measured 7e-10 of the signal)
    ({"n_rollers": 3}, 1e-8),
    # the generalized-alpha Newton stops at its tolerance, not at rounding: the two runs'
    # iterations part by that much (measured 3e-7 of the signal over 2000 steps)
    ({"bearing": 1}, 1e-5)], ids=["ideal", "integrator1", "three-rollers", "lumped"])
def test_drive_in_reverse_is_coast_turned_about_the_trunnion_axis(sv, rel, tmp_path):
    w = 20 * math.pi
    a, _ = run("TripodRoller", dict(sv, omega=-w, F_press=1000.0), tmp_path, "a")
    b, _ = run("TripodRoller", dict(sv, omega=w, F_press=-1000.0), tmp_path, "b")
    assert np.min(b["Fx"]) < -900.0 and np.max(a["Fx"]) > 900.0   # coast presses the -x flank
    for k, (image, sign) in FLIP.items():
        scale = np.max(np.abs(a[k]))
        assert np.max(np.abs(a[k] - sign * b[image])) <= rel * scale, k
    # and it is a different state from forward drive (order 3 moves, not just its sign)
    c, _ = run("TripodRoller", dict(sv, omega=w, F_press=1000.0), tmp_path, "c")
    assert np.max(np.abs(c["Fz"] + b["Fz"])) > 0.1 * np.max(np.abs(c["Fz"]))


def test_torque_through_zero_runs_finite_and_bounded(tmp_path):
    """300 -> -300 N m over 0.2 s, three rollers: every roller leaves its drive flank, crosses
    the running clearance (2 (r_groove - r_roller) = 0.4 mm) and lands on the coast flank; the
    outputs stay finite and within the friction bound, no refusal."""
    inputs = {"time": [0.0, 0.05, 0.25, 0.3], "torque": [300.0, 300.0, -300.0, -300.0]}
    r, info = run("TripodRoller", {"n_rollers": 3}, tmp_path, "rev", stop=0.3, inputs=inputs)
    assert r is not None, info
    for k in ("Fx", "Fz", "Fz_joint", "T_housing", "F_housing_x"):
        assert np.all(np.isfinite(r[k])), k
    I = 0.5 * 0.06 * (0.019 ** 2 + 0.0125 ** 2)
    spin = I / 0.019 ** 2 * 0.022 * math.tan(math.radians(10)) * (20 * math.pi) ** 2
    assert np.all(np.abs(r["Fz"]) <= 1.05 * (0.055 * np.abs(r["Fx"]) + spin) + 1e-6)
    # drive at the start, coast at the end, carried by the housing both ways (within the
    # traverse's rise of the pressing force)
    first, last = r["time"] < 0.05, r["time"] > 0.26
    assert np.mean(r["T_housing"][first]) == pytest.approx(300.0, rel=0.1)
    assert np.mean(r["T_housing"][last]) == pytest.approx(-300.0, rel=0.1)
    assert np.all(r["F_roller"][last] == pytest.approx(-300.0 / (3 * 0.022)))


def _order3(r):
    from reduced_model.orders import last_cycle_orders
    return last_cycle_orders(r["time"], r["Fz_joint"], np.abs(r["whirl_angle"]), (3,))[3]


@pytest.mark.parametrize("omega,F", [(1, 1), (-1, -1), (-1, 1), (1, -1)],
                         ids=["drive", "coast-reverse", "drive-reverse", "coast"])
def test_the_analytic_fmu_in_every_quadrant_against_the_contact_fmu(omega, F, tmp_path):
    """Three rollers, 10 Hz, 1000 N, 0.4 s: order 3 of Fz_joint over the last whole cycle of
    the whirl angle, analytic against contact within 2 % and 1 deg (measured: 0.5 %, 0.4 deg
    in each).  The analytic FMU runs coast as drive at the opposite whirl turned about the
    trunnion axis (the symmetry above), and reverse whirl by stepping the slide in time."""
    sv = {"n_rollers": 3, "omega": omega * 20 * math.pi, "F_press": F * 1000.0}
    c, _ = run("TripodRoller", sv, tmp_path, "c", stop=0.4)
    # (paired with the contact FMU's ideal bearing: no needle row)
    a, info = run("TripodRollerAnalytic", dict(sv, needle_row=False), tmp_path, "a", stop=0.4)
    assert a is not None, info
    (ac, pc), (aa, pa) = _order3(c), _order3(a)
    assert aa == pytest.approx(ac, rel=0.02)
    assert abs((pa - pc + 180) % 360 - 180) < 1.0
    assert np.all(np.sign(a["Fx"]) == F) and np.all(np.sign(c["Fx"][1:]) == F)


def test_the_analytic_fmu_takes_the_torque_through_zero(tmp_path):
    inputs = {"time": [0.0, 0.05, 0.25, 0.3], "torque": [300.0, 300.0, -300.0, -300.0]}
    a, info = run("TripodRollerAnalytic", {"n_rollers": 3}, tmp_path, "a", stop=0.3,
                  inputs=inputs)
    assert a is not None, info
    assert all(np.all(np.isfinite(a[k])) for k in a.dtype.names)
    last = a["time"] > 0.26
    assert np.all(a["Fx"][last] < 0) and np.all(a["Fx"][a["time"] < 0.05] > 0)
    assert np.mean(a["T_housing"][last]) == pytest.approx(-300.0, rel=0.1)


def test_coast_and_reverse_over_the_grid():
    """docs/validation.md's coast and reverse table, rerun: the analytic FMU within the
    checked range's tolerances of the contact FMU (those of the drive grid: median below 2 %,
    worst below 5 %, phase within 3 deg; measured 0.4 %, 1.4 %, 1.9 deg), coast and reverse
    each other's image (Fz flips: same amplitude, phase 180 deg apart; to the periodicity test's
    0.1 %), and the table current."""
    from harness import validation
    rows = validation.quadrant_rows()
    rel = np.abs([r["rel"] for r in rows])
    assert len(rows) == 21
    assert np.median(rel) < 0.02 and rel.max() < 0.05
    assert max(abs(r["dphase"]) for r in rows) < 3.0
    by = {(r["scene"], r["quadrant"]): r for r in rows}
    for scene in {r["scene"] for r in rows}:
        c, rv = by[scene, "coast"], by[scene, "reverse"]
        for k in ("contact", "analytic"):
            assert rv[k][0] == pytest.approx(c[k][0], rel=1e-3)
            assert abs((rv[k][1] - c[k][1]) % 360 - 180) < 0.1
    doc = (validation.ROOT / "docs" / "validation.md").read_text()
    assert validation.quadrant_markdown(rows) in doc, "docs/validation.md is stale: make docs"


@pytest.mark.parametrize("c", [0.0, 1e-3], ids=["from-geometry", "1mm"])
def test_the_flanks_sit_the_running_clearance_apart(c):
    """In-process, one roller, 1000 N drive then coast: the contact point lies on the drive
    flank, then on the coast flank.  By the parameter's definition each flank is an arc of
    radius r_groove centred c / 2 - (r_groove - r_roller) off the track's mid-plane, on its own
    side (c = 0: 2 (r_groove - r_roller), one cylinder), and the roller's surface point reaches
    the Hertz approach (f_n / K)^(2/3) past it: its distance from the arc centre is r_groove
    plus that, to rounding (1e-12 m).  The pressing load in use is carried either way
    (Fx's mean +-F within the traverse's 10 %)."""
    from reduced_model import hertz
    from tripod_model import layout
    from tripod_model.model import ContactModel
    Rg, r = 0.0192, 0.019
    K = hertz.hertz_point(r, Rg, 206e9, 0.3)[0]
    d = 0.5 * c - (Rg - r) if c else 0.0
    for F in (1000.0, -1000.0):
        m = ContactModel({"running_clearance": c})
        p = m.p
        fx = [m.step(1e-4, p["theta"], p["omega"], F)["Fx"] for _ in range(500)]
        assert np.mean(fx) == pytest.approx(F, rel=0.1) and np.all(np.sign(fx) == np.sign(F))
        res = m._res
        centre = math.copysign(d, F)
        dist = math.hypot(res[layout.R_PX] - centre, res[layout.R_PY])
        assert dist - Rg == pytest.approx((res[layout.R_FN] / K) ** (2 / 3), abs=1e-12)
        assert res[layout.R_PX] * F > 0          # on its own flank


# the generalized-alpha Newton stops at its tolerance, not at rounding: the lumped bearing's
# runs part by that much (measured 7.7e-6 of contact_y), and so may any run where a decision
# taken at a tolerance flips on rounding
NEWTON_REL = 5e-5


# the lumped row across the load's zero: the adaptive substeps' accept and reject decisions flip
# on rounding there and leave a difference of the order of their local error (measured 8.0e-5
# of contact_y, 4.9e-5 of it 2-5 ms after the zero; the clearance, were it to move the contact,
# would move it by half its 0.6 mm change, 0.15 of contact_y's scale)
CROSSING_REL = 5e-4


@pytest.mark.parametrize("sv,rel,settle,across", [
    # measured 2.2e-9 (Fz_joint) away from the load's zero
    ({"n_rollers": 3}, 1e-8, 2e-3, NEWTON_REL),
    ({"bearing": 1}, NEWTON_REL, 5e-3, CROSSING_REL)], ids=["three-rollers", "lumped"])
def test_the_running_clearance_moves_the_flanks_not_the_contact(sv, rel, settle, across,
                                                                 tmp_path):
    """Through a torque reversal 300 -> -300 N m, running clearance 1 mm against
    the geometry's 0.4 mm: each flank is the same arc, moved across the track, so every force
    and the contact point along the trunnion are the same to rounding (the coast symmetry's
    1e-8 of each signal with three rollers: positions round differently about a moved centre,
    and the stiff contact carries that over 3000 steps), and with the lumped bearing to the
    Newton's tolerance.  The crossing spans more, nothing else: the roller goes with the
    trunnion (held on it, or on the row), which jumps across the clearance at the load's zero.
    Within `settle` of that zero the bound is the Newton's for both: the load's step there is
    taken by the error-controlled adaptive substeps (genalpha.GA_STEP_IN), whose accept and
    reject decisions, and the Newton's stops, can flip on rounding (three rollers: 2.4e-9 of
    Fz_joint there through the FMU, 2.7e-8 in a run in process that reaches the zero at other
    loads), and the lumped row settles from what they leave within about 20 ms, its friction
    around the loaded arc damping the roller's tilt (contact_y: 4.9e-5 of its scale 2-5 ms after
    the zero, 2.4e-6 at 5-10 ms, 3.6e-7 at 15-20 ms, 6.4e-10 at 20-30 ms): 2 ms, and 5 ms for
    the lumped row."""
    inputs = {"time": [0.0, 0.05, 0.25, 0.3], "torque": [300.0, 300.0, -300.0, -300.0]}
    a, _ = run("TripodRoller", sv, tmp_path, "a", stop=0.3, inputs=inputs)
    b, info = run("TripodRoller", dict(sv, running_clearance=1e-3), tmp_path, "b", stop=0.3,
                  inputs=inputs)
    assert b is not None, info
    names = ("Fx", "Fy", "Fz", "Fz_joint", "contact_y", "T_housing") + (
        ("Fx_2", "Fz_3") if sv.get("n_rollers") == 3 else ())
    crossing = np.abs(a["time"] - 0.15) <= settle   # the torque's zero: 300 -> -300 over 0.2 s
    assert crossing.sum() >= 40
    for k in names:
        d, scale = np.abs(a[k] - b[k]), np.max(np.abs(a[k]))
        assert np.max(d[~crossing]) <= rel * scale, k
        assert np.max(d[crossing]) <= across * scale, k


def test_a_running_clearance_below_the_grooves_is_refused(tmp_path):
    """Below 2 (r_groove - r_roller) the one-cylinder flanks would overlap and the roller touch
    both (a gothic arch, outside the paper's contact law): the FMU logs why and does not run."""
    r, info = run("TripodRoller", {"running_clearance": 3e-4}, tmp_path, "x")
    assert r is None
    assert any("running_clearance = 0.0003 m is below 2 (r_groove - r_roller) = 0.0004 m"
               in line for line in info["log"]), info
