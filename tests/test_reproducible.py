"""The same sources give the same FMU, byte for byte: a GUID derived from the model's content,
no build time, binaries without build paths or link stamps (fmu_src/build.py content_guid,
fmu_src/native_fmu.py), and `tripod-thrust build --check` to tell where an FMU came from."""
import os
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from harness.fmus import builder, check_fmu, ensure_fmu

ROOT = Path(__file__).resolve().parents[1]


def _tree(base: Path, text: str) -> list:
    (base / "pkg").mkdir(parents=True)
    f = base / "pkg" / "model.py"
    f.write_text(text)
    return [f]


def test_the_guid_follows_the_content_not_the_folder(tmp_path, monkeypatch):
    b = builder()
    xml = b'<fmiModelDescription fmiVersion="2.0" modelName="X" guid="{old}">'
    guids = []
    for folder, text in (("a", "x = 1\n"), ("other folder", "x = 1\n"), ("c", "x = 2\n")):
        files = _tree(tmp_path / folder, text)
        monkeypatch.setattr(b, "ROOT", tmp_path / folder)
        monkeypatch.setattr(b, "_sources", lambda name, files=files: files)
        guids.append(b.content_guid("X", xml))
    assert guids[0] == guids[1] != guids[2]
    assert re.fullmatch(r"\{[0-9a-f]{8}-[0-9a-f]{4}-5[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}\}",
                        guids[0])
    # (the last folder's sources) another model description, another GUID; the guid attribute
    # itself does not count
    assert b.content_guid("X", xml.replace(b'"X"', b'"Y"')) != guids[2]
    assert b.content_guid("X", xml.replace(b"{old}", b"{new}")) == guids[2]


@pytest.mark.parametrize("name", ["TripodRoller", "TripodRollerAnalytic"])
def test_the_model_description_names_its_content_and_its_tool(name):
    fmu = ensure_fmu(name)
    with zipfile.ZipFile(fmu) as z:
        xml = z.read("modelDescription.xml")
        assert {i.date_time for i in z.infolist()} == {(1980, 1, 1, 0, 0, 0)}
    head = xml.split(b">", 2)[1]
    assert b"generationDateAndTime" not in head and b"PythonFMU" not in xml
    version = re.search(r'^version = "([^"]+)"', (ROOT / "pyproject.toml").read_text(), re.M)[1]
    assert f'generationTool="tripod-thrust {version}"'.encode() in head
    assert re.search(rb'guid="([^"]+)"', head)[1].decode() == builder().content_guid(name, xml)


def test_check_names_an_fmu_from_elsewhere(tmp_path):
    fmu = ensure_fmu("TripodRoller")
    same, line = check_fmu(fmu)
    assert same and "built from this checkout" in line
    other = tmp_path / "other.fmu"
    with zipfile.ZipFile(fmu) as zin, zipfile.ZipFile(other, "w") as zout:
        for i in zin.infolist():
            data = zin.read(i.filename)
            if i.filename.endswith(".dll"):
                data = data[:-1] + bytes([data[-1] ^ 1])
            zout.writestr(i, data)
    same, line = check_fmu(other)
    assert not same and "binaries/win64/TripodRoller.dll differ" in line
    p = subprocess.run([sys.executable, "-m", "harness.cli", "build", "--check", str(other)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 1 and "not from this checkout" in p.stdout


def _clean_against_head() -> bool:
    return subprocess.run(["git", "-C", str(ROOT), "diff", "--quiet", "HEAD", "--"],
                          capture_output=True).returncode == 0


def _build_in_clone(dest: Path) -> bytes:
    subprocess.run(["git", "clone", "-q", str(ROOT), str(dest)], check=True)
    env = dict(os.environ, PYTHONPATH=f"{dest}{os.pathsep}{dest / 'fmu_src'}")
    p = subprocess.run([sys.executable, "-c", "from harness.fmus import ensure_fmu; "
                        "print(ensure_fmu('TripodRoller'))"], cwd=dest, env=env,
                       capture_output=True, text=True, timeout=3600)
    assert p.returncode == 0, p.stderr[-3000:]
    return Path(p.stdout.strip().splitlines()[-1]).read_bytes()


@pytest.mark.slow   # (a build in a fresh clone: minutes)
def test_two_clean_checkouts_build_the_same_fmu(tmp_path):
    # the commit cloned into a folder with a space in its name and built there; against this
    # checkout's FMU where this checkout is that commit, else against a second clone
    a = _build_in_clone(tmp_path / "clone a")
    b = ensure_fmu("TripodRoller").read_bytes() if _clean_against_head() else \
        _build_in_clone(tmp_path / "clone b")
    assert a == b


@pytest.mark.parametrize("name", ["TripodRoller", "TripodRollerAnalytic", "Powertrain"])
def test_the_model_description_is_written_without_pythonfmu(name):
    """The shipped FMU's model description comes from description.py and the parameter table,
    with pythonfmu not importable (the project does not depend on it)."""
    code = ("import sys; sys.modules['pythonfmu'] = None\n"
            "from harness.fmus import builder\n"
            f"sys.stdout.buffer.write(builder().model_description({name!r}))\n")
    p = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, timeout=300)
    assert p.returncode == 0, p.stderr.decode()[-2000:]
    with zipfile.ZipFile(ensure_fmu(name)) as z:
        assert z.read("modelDescription.xml") == p.stdout


def test_the_generated_variables_table_is_kept_for_a_reader():
    """What the build generates for each binary (model_data.c: the variables, sizes, notes and
    the compiled functions' names) is kept in build/generated/<FMU>/<platform>/, for this
    build: it names the FMU's GUID."""
    fmu = ensure_fmu("TripodRollerAnalytic")
    with zipfile.ZipFile(fmu) as z:
        guid = re.search(rb'guid="([^"]+)"', z.read("modelDescription.xml"))[1].decode()
    for target in ("linux64", "win64"):
        text = (builder().generated_path("TripodRollerAnalytic") / target /
                "model_data.c").read_text()
        assert f'const char MODEL_GUID[] = "{guid}";' in text
        assert "const ModelVar MODEL_VARS[]" in text
