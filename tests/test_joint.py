"""A joint described once (reduced_model/joint.py): the example joint files load, are the paper's
joint scaled as they say, and `tripod-thrust compare --joint FILE` runs each and finds it inside
the checked range; a file with a missing or unknown key, a value out of range or a geometry that
cannot be built is refused with one line naming the key."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from harness.cli import main
from reduced_model.joint import EXAMPLES, JOINT_KEYS, for_model, load_joint, scaled
from reduced_model.scene import BY_NAME

FACTORS = {"paper": 1.0, "small-car": 0.82, "light-truck": 1.45}


@pytest.mark.parametrize("name", sorted(FACTORS))
def test_the_example_joints_are_the_papers_scaled(name):
    """Each example file holds every key, the paper's joint scaled by its pitch circle (lengths
    times the factor, the roller's mass with its cube, the groove clearance 0.2 mm): equal to
    joint.scaled within the rounding of the file's digits (1e-12 m)."""
    j = load_joint(EXAMPLES / f"{name}.toml")
    want = scaled(FACTORS[name])
    assert list(j) == list(JOINT_KEYS)
    for k in JOINT_KEYS:
        assert j[k] == pytest.approx(want[k], rel=1e-12, abs=1e-12), k
    assert j["r_groove"] - j["r_roller"] == pytest.approx(2e-4, abs=1e-12)
    assert j["m_roller"] == pytest.approx(BY_NAME["m_roller"].default * FACTORS[name] ** 3)
    if name == "paper":
        assert j == {k: BY_NAME[k].default for k in JOINT_KEYS}


@pytest.mark.parametrize("name", sorted(FACTORS))
def test_compare_runs_each_example_joint_inside_the_checked_range(name):
    """`tripod-thrust compare --joint FILE`: both FMUs with the joint's values, the verdict
    PASS, and the scene inside the range the traverse model was checked in."""
    exe = Path(sys.executable).with_name("tripod-thrust")
    p = subprocess.run([str(exe), "compare", "--joint", str(EXAMPLES / f"{name}.toml"),
                        "--json"], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    r = json.loads(p.stdout)
    assert r["pass"] and r["outside_checked"] == [], r
    assert r["scene"]["s"] == pytest.approx(BY_NAME["s"].default * FACTORS[name])
    assert r["scene"]["n_needles"] == 46


def test_a_json_joint_file_is_the_same_joint(tmp_path):
    j = load_joint(EXAMPLES / "small-car.toml")
    f = tmp_path / "car.json"
    f.write_text(json.dumps(dict(j, name="small car")))
    assert load_joint(f) == j


def test_the_analytic_model_takes_what_it_has():
    j = load_joint(EXAMPLES / "light-truck.toml")
    a = for_model(j, "analytic")
    assert set(a) == {"s", "r_roller", "r_groove", "r_bore", "m_roller", "mu_groove", "E", "nu",
                      "l_needle", "n_needles", "needle_clearance", "needle_axial_clearance",
                      "mu_needle", "mu_rolling"}
    assert for_model(j, "contact") == j


def _bad(tmp_path, text, suffix=".toml"):
    f = tmp_path / f"bad{suffix}"
    f.write_text(text)
    return f


def _paper_without(key=None, **change):
    lines = []
    for k in JOINT_KEYS:
        if k == key:
            continue
        v = change.get(k, BY_NAME[k].default)
        lines.append(f"{k} = {v!r}" if not isinstance(v, str) else f"{k} = {v}")
    return "\n".join(lines) + "\n"


BAD = {   # what the file says: (its text, what the one line must name)
    "missing key": (_paper_without("r_bore"), "missing key 'r_bore'"),
    "unknown key": (_paper_without() + "r_rollers = 0.02\n", "unknown key 'r_rollers'"),
    "out of range": (_paper_without(nu=0.5), "nu = 0.5 is outside the allowed range [0, 0.5)"),
    "a string": (_paper_without(s='"22 mm"'), "s = '22 mm' is not a number"),
    "a boolean": (_paper_without(mu_groove="true"), "mu_groove = True is not a number"),
    "a fraction of a needle": (_paper_without(n_needles=46.5),
                               "n_needles = 46.5 is not an integer"),
    "roller larger than its groove": (_paper_without(r_groove=0.0185),
                                      "r_groove = 0.0185 m: the roller"),
    "bore larger than the roller": (_paper_without(r_bore=0.02), "r_bore = 0.02 m: the bore"),
    "needle row wider than the bore": (_paper_without(r_trunnion=0.012),
                                       "r_trunnion = 0.012 m: the needle row"),
    "needles longer than the roller": (_paper_without(l_needle=0.02),
                                       "l_needle = 0.02 m: the needles are longer"),
    "running clearance below the groove's": (_paper_without(running_clearance=1e-4),
                                             "running_clearance = 0.0001 m: below"),
    "not TOML": ("s = = 1\n", "not valid TOML"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_a_bad_joint_file_is_refused_naming_the_key(case, tmp_path, capsys):
    text, named = BAD[case]
    f = _bad(tmp_path, text)
    assert main(["joint", str(f)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and named in err and str(f) in err, err


def test_a_missing_file_and_bad_json_are_refused(tmp_path, capsys):
    assert main(["compare", "--joint", str(tmp_path / "none.toml")]) == 2
    assert "No such file" in capsys.readouterr().err
    assert main(["joint", str(_bad(tmp_path, "{", ".json"))]) == 2
    assert "not valid JSON" in capsys.readouterr().err


def test_the_joint_command_gives_each_fmu_its_start_values(capsys):
    assert main(["joint", str(EXAMPLES / "small-car.toml"), "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["outside_checked"] == []
    assert set(r["start_values"]["TripodRoller"]) == set(JOINT_KEYS)
    assert r["start_values"]["TripodRollerAnalytic"]["s"] == pytest.approx(0.01804)


def test_the_launch_example_takes_a_joint_file(tmp_path):
    """`tripod-thrust example --joint FILE`: the SSP's joint component gets the file's values
    as start values (the analytic FMU: its eight), and the creep load at the joint's own pitch
    circle; the launch runs (0.05 s here)."""
    import zipfile
    from driveline import powertrain as pt
    from harness import example as E
    j = load_joint(EXAMPLES / "small-car.toml")
    r = E.launch(tmp_path, stop=0.05, step=1e-3, joints=("analytic",), tools=("fmpy",),
                 check_step=False, plots=False, joint=j)
    assert len(r["rows"]) == 1 and r["rows"][0]["tool"] == "fmpy"
    ssd = zipfile.ZipFile(tmp_path / "launch_analytic.ssp").read("SystemStructure.ssd").decode()
    assert f'<ssv:Parameter name="s"><ssv:Real value="{j["s"]!r}"/>' in ssd
    creep = pt.defaults()["torque_creep"] / (3.0 * j["s"])
    assert f'<ssv:Parameter name="F_press"><ssv:Real value="{creep!r}"/>' in ssd
    assert 'name="n_needles"' in ssd            # (the analytic model's needle row)
    assert 'name="d_needle"' not in ssd         # (the contact model's only)
