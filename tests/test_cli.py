"""The analytic command as a user runs it: a fresh process, text and JSON, bad input."""
import json
import subprocess
import sys

import pytest


def run(*args):
    return subprocess.run([sys.executable, "-m", "harness.cli", *args],
                          capture_output=True, text=True, timeout=120)


def test_analytic_json_keys_and_values():
    p = run("analytic", "--json", "--theta-deg", "10", "--whirl-hz", "10")
    assert p.returncode == 0, p.stderr
    r = json.loads(p.stdout)
    for k in ("scene", "order1", "order3", "closed_form", "three_rollers"):
        assert k in r
    for k in ("order1", "order3"):
        assert set(r[k]) >= {"amplitude", "phase_deg"}
        assert set(r["closed_form"][k]) >= {"amplitude", "phase_deg"}
        assert set(r["three_rollers"][k]) >= {"amplitude", "phase_deg"}
    # model.md: order 3 of one roller about 6.09 N
    assert r["order3"]["amplitude"] == pytest.approx(6.09, rel=0.01)


def test_analytic_text_runs():
    p = run("analytic", "--set", "F_press=2000")
    assert p.returncode == 0, p.stderr
    assert "three rollers order 3" in p.stdout and "beta" in p.stdout


@pytest.mark.parametrize("args,needle", [
    (["--set", "nope=1"], "nope"),
    (["--theta-deg", "45"], "theta"),
    (["--set", "F_press=-5"], "F_press"),
    (["--set", "omega=-1"], "omega"),
    (["--set", "theta=nan"], "theta"),
    (["--set", "theta"], "NAME=VALUE"),
])
def test_bad_input_one_line(args, needle):
    p = run("analytic", *args)
    assert p.returncode != 0
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0], p.stderr
    assert p.stdout == ""


def test_readme_parameter_table_is_generated():
    from pathlib import Path
    from reduced_model.docs import outputs_markdown, params_markdown
    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    assert params_markdown() in readme, "README parameter table is stale: paste `tripod-thrust params`"
    assert outputs_markdown() in readme, "README output table is stale: paste `tripod-thrust params`"
