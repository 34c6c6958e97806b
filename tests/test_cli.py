"""The analytic command as a user runs it: a fresh process, text and JSON, bad input."""
import json
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from harness.fmus import ensure_fmu


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


def test_header_reports_the_load_in_use():
    # a torque sets the pressing load: torque / (3 s) = 1500 / (3 x 0.022) = 22727 N per
    # roller (was: the header printed the unused F_press = 1000 N)
    p = run("analytic", "--set", "torque=1500")
    assert p.returncode == 0, p.stderr
    head = p.stdout.splitlines()[1]
    assert "pressing load = 22727.3 N per roller" in head and "F_press = 1000" not in head


@pytest.mark.parametrize("args,needle", [
    (["--set", "nope=1"], "nope"),
    (["--theta-deg", "45"], "theta"),
    (["--set", "F_press=-5"], "F_press"),
    (["--set", "omega=-1"], "omega"),
    (["--set", "theta=nan"], "theta"),
    (["--set", "theta"], "NAME=VALUE"),
    # the traverse model's normal would tilt to 90 deg (was a ZeroDivisionError traceback)
    (["--set", "mu_groove=1", "--set", "theta=0.78", "--set", "omega=10000"], "mu_groove < 1"),
])
def test_bad_input_one_line(args, needle):
    p = run("analytic", *args)
    assert p.returncode != 0
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0], p.stderr
    assert p.stdout == ""


def test_parameter_table_in_the_docs_is_generated():
    from pathlib import Path
    from reduced_model.docs import outputs_markdown, params_markdown
    doc = (Path(__file__).resolve().parents[1] / "docs" / "using-the-fmus.md").read_text()
    assert params_markdown() in doc, "docs/using-the-fmus.md parameter table is stale: make docs"
    assert outputs_markdown() in doc, "docs/using-the-fmus.md output table is stale: make docs"


def test_version_is_the_projects():
    import re
    from harness.cli import version
    root = Path(__file__).resolve().parents[1]
    want = re.search(r'^version = "([^"]+)"', (root / "pyproject.toml").read_text(), re.M).group(1)
    p = subprocess.run([sys.executable, "-m", "harness.cli", "--version"], capture_output=True,
                       text=True, cwd=root)
    assert p.returncode == 0 and p.stdout.strip() == f"tripod-thrust {want}" == f"tripod-thrust {version()}"


def test_every_option_in_help_has_its_default_and_every_parameter_its_unit():
    import argparse
    from harness.cli import build_parser
    from reduced_model import scene as scene_mod
    ap = build_parser()
    sub = next(a for a in ap._actions if isinstance(a, argparse._SubParsersAction))
    for name, p in sub.choices.items():
        text = " ".join(p.format_help().split())
        for a in p._actions:
            if not a.option_strings or a.help == argparse.SUPPRESS or a.dest == "help":
                continue
            if a.default not in (None, False, []):
                # the default as the help prints it, e.g. "(default out/bench)"
                assert f"default {a.default}" in text or "(default" in (a.help or ""), (name, a.dest)
        if any(a.dest == "set" for a in p._actions):
            model = "analytic" if name == "analytic" else "contact"
            from driveline.powertrain import PARAMS as POWERTRAIN
            for q in POWERTRAIN if name == "example" else scene_mod.params_for(model):
                unit = "" if q.unit == "1" else f" [{q.unit}]"
                assert f" {q.name}{unit} = " in text, (name, q.name)


def test_bad_communication_step_one_line():
    # refused by the CLI, naming the option and its range (it reached the FMU as an fmi2DoStep
    # error before)
    p = run("compare", "--dt", "0")
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 2 and len(lines) == 1 and "dt = 0" in lines[0] and "(0, inf) s" in lines[0]


def test_bad_bench_run_count_one_line(tmp_path):
    # --runs 0 ended in a statistics traceback (no median of no runs)
    p = run("bench", "--runs", "0", "--out", str(tmp_path))
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 2 and lines == ["tripod-thrust bench: error: --runs = 0: allowed "
                                           "range [1, 1000]"]


@pytest.mark.parametrize("args, needle", [
    # argparse would take --theta as an abbreviation of --theta-deg and run at 0.14 deg
    (["analytic", "--theta", "0.14"], "--theta (did you mean --theta-deg?)"),
    (["compare", "--speed-hz", "15"], "tripod-thrust compare: error: unrecognized arguments"),
    (["compare", "--bearing", "7"], "tripod-thrust compare: error: argument --bearing"),
])
def test_option_spelled_whole_or_refused_in_one_line(args, needle):
    p = subprocess.run([sys.executable, "-m", "harness.cli", *args], capture_output=True,
                       text=True, timeout=120)
    assert p.returncode == 2 and p.stdout == ""
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0], p.stderr


def test_scene_file_taken_wherever_help_offers_it(tmp_path):
    """--joint's help says --scene overrides it: every command with --joint takes --scene, and
    its values reach the scene (here the joint angle, in SI)."""
    f = tmp_path / "scene.toml"
    f.write_text("theta = 0.15\n")
    p = subprocess.run([sys.executable, "-m", "harness.cli", "analytic", "--scene", str(f),
                        "--json"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert json.loads(p.stdout)["scene"]["theta"] == 0.15


@pytest.mark.parametrize("edit, needle", [
    # grams meant: a 60 kg roller of the paper's size would be 7.2e6 kg/m3
    (("m_roller = 0.06 ", "m_roller = 60 "), "m_roller = 60 kg is a density of 7.2e+06 kg/m3"),
    # millimetres meant
    (("s = 0.022 ", "s = 22 "), "s = 22 is outside the allowed range (0, 1] m: millimetres?"),
])
def test_a_joint_files_likely_unit_mistake_is_named(tmp_path, edit, needle):
    root = Path(__file__).resolve().parents[1]
    text = (root / "joints" / "paper.toml").read_text()
    assert edit[0] in text
    f = tmp_path / "joint.toml"
    f.write_text(text.replace(edit[0], edit[1]))
    p = run("analytic", "--joint", str(f))
    assert p.returncode == 2 and p.stdout == ""
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0], p.stderr
    assert "grams?" in lines[0] or "(s = 0.022 m)" in lines[0]


def test_every_shipped_joints_roller_is_a_steel_ring():
    # the plausibility check's density from each joint file's mass and ring: steel is
    # 7700-8050 kg/m3; the files' rollers (scaled from the paper's joint) 7175 kg/m3, a ring
    # that is not quite a plain cylinder: within 10 % of steel's 7850
    from reduced_model.joint import EXAMPLES, load_joint
    from reduced_model.scene import roller_density, validate
    for f in sorted(EXAMPLES.glob("*.toml")):
        scene = validate(load_joint(f), "contact")
        assert roller_density(scene) == pytest.approx(7850.0, rel=0.10), f.name


def _in_terminal(argv, timeout=300, python=("-m", "harness.cli")):
    """The CLI (or ``python`` -c ...) run in a pseudo-terminal: (exit status, everything it
    wrote there)."""
    import os
    import pty
    import select
    pid, fd = pty.fork()
    if pid == 0:
        os.execv(sys.executable, [sys.executable, *python, *argv])
    out, end = b"", time.monotonic() + timeout
    while time.monotonic() < end:
        if select.select([fd], [], [], 1.0)[0]:
            try:
                d = os.read(fd, 4096)
            except OSError:
                break
            if not d:
                break
            out += d
    else:
        os.kill(pid, 9)      # out of time: what it wrote so far is the answer
    _, st = os.waitpid(pid, 0)
    return os.waitstatus_to_exitcode(st), out.decode(errors="replace")


def test_a_long_run_shows_its_progress_in_a_terminal():
    # the needle-resolved row's three whirl cycles take 6-17 s: after 2 s the contact FMU's run
    # says how far it got, on one line overwritten in place and cleared before the table; the
    # same run with its output captured (no terminal) writes nothing but the table. The FMUs
    # are built first: a first build (minutes) would eat the terminal's time limit
    for name in ("TripodRoller", "TripodRollerAnalytic"):
        ensure_fmu(name)
    code, out = _in_terminal(["compare", "--bearing", "2", "--max-cycles", "3"])
    assert code in (0, 1), out
    assert "\rcontact FMU: " in out and "of at most 0.300 s simulated" in out, out[:2000]
    assert "whirl cycle 1 done" in out
    assert "\r\x1b[K" in out and "verdict:" in out.split("\r\x1b[K")[-1]
    p = run("compare", "--max-cycles", "3")
    assert p.returncode in (0, 1) and "simulated" not in p.stderr + p.stdout


def test_the_examples_runs_show_their_progress_in_a_terminal():
    # the example's SSP runs report no simulated time: each says which run of how many and its
    # wall time after 2 s, on one line cleared at the end; nothing for a short run
    code = ("import time, sys\nfrom harness.runs import Ticker\n"
            "with Ticker('example: run 1 of 5'): time.sleep(3.2)\n"
            "with Ticker('short run'): time.sleep(0.6)\nprint('done')")
    status, out = _in_terminal([code], timeout=60, python=("-c",))
    assert status == 0, out
    assert re.search(r"\rexample: run 1 of 5, [23] s ", out), out
    assert "\r\x1b[K" in out and "short run" not in out and out.rstrip().endswith("done")
