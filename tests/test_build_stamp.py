"""An FMU is stale when any of its sources differs in content from what it was built from, not
only when a source is newer: a source edited while a build ran (after the build read it, before
the FMU was written) left an FMU newer than its sources and out of date."""
import os

from harness.fmus import builder


def test_stale_by_content_not_by_time(tmp_path, monkeypatch):
    b = builder()
    src = tmp_path / "model.py"
    src.write_text("x = 1\n")
    monkeypatch.setattr(b, "BUILD", tmp_path)
    monkeypatch.setattr(b, "_sources", lambda name: [src])
    fmu = b.fmu_path("X")
    assert b.is_stale("X")                       # no FMU
    fmu.write_bytes(b"fmu")
    assert b.is_stale("X")                       # no record of its sources
    b._stamp("X").write_text(b.sources_hash("X") + "\n")
    assert not b.is_stale("X")
    # edited "during the build": older than the FMU, other content
    src.write_text("x = 2\n")
    t = fmu.stat().st_mtime
    os.utime(src, (t - 10, t - 10))
    assert b.is_stale("X")


def test_the_built_fmus_carry_their_sources_hash():
    b = builder()
    for name in ("TripodRoller", "TripodRollerAnalytic"):
        b.build(name)
        assert b._stamp(name).read_text().strip() == b.sources_hash(name)


def test_kept_objects_are_found_by_the_content_of_their_sources(tmp_path):
    """aot.compile_functions keeps what it compiles by aot.cache_key: the same sources give the
    same key, any byte of any source another key (a fresh clone reuses the objects; an edit
    compiles again), and so do another spec or target."""
    b = builder()
    aot = b.build_module("aot")
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "a.py").write_text("x = 1\n")
    (pkg / "b.py").write_text("y = 2\n")
    key = aot.cache_key("m:f", ("linux64",), sources=(pkg,))
    assert key == aot.cache_key("m:f", ("linux64",), sources=(pkg,))
    assert key != aot.cache_key("m:g", ("linux64",), sources=(pkg,))
    assert key != aot.cache_key("m:f", ("linux64", "win64"), sources=(pkg,))
    (pkg / "b.py").write_text("y = 3\n")
    assert key != aot.cache_key("m:f", ("linux64",), sources=(pkg,))
    # and the project's own: every package a compiled model imports
    assert {p.name for p in aot.SOURCES} == {"fmu_src", "reduced_model", "driveline"}
