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
