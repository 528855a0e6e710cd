"""Hair: sessions loaded and saved, primitives added from 3D points, the field solved and the
strands grown as `lapis hair` grows them, strands as points + offsets, .hair and OBJ exports."""

import shutil

import numpy as np
import pytest

import lapis
from conftest import SOURCE_DIR

SESSIONS = SOURCE_DIR / "assets" / "sessions"


def small(session):
    """Fewer unknowns and strands than the bundled sessions ask for: the same code, faster."""
    session.grid_unknowns = 6000
    session.roots = 300
    return session


def test_build_equals_the_cli(tmp_path, cli):
    s = small(lapis.HairSession.load(str(SESSIONS / "parting.json"), replay=False))
    s.replay()  # after the settings, as the CLI applies its flags before replaying
    r = s.build()
    points, offsets = r["points"], r["offsets"]
    assert points.dtype == np.float32 and points.shape[1] == 3
    assert offsets.dtype == np.int32 and offsets[0] == 0 and offsets[-1] == points.shape[0]
    assert abs(len(offsets) - 1 - 300) < 30 and r["constraints"] > 0  # roots are placed about that many
    assert r["field"].shape == tuple(reversed(r["grid"]["dims"])) + (3,)
    lapis.write_hair(str(tmp_path / "py.hair"), points, offsets)
    cli("hair", "--session", SESSIONS / "parting.json", "--grid-unknowns", 6000, "--roots", 300, "--out-hair",
        tmp_path / "cli.hair")
    assert (tmp_path / "py.hair").read_bytes() == (tmp_path / "cli.hair").read_bytes()
    p2, o2 = lapis.read_hair(str(tmp_path / "cli.hair"))
    grown = np.diff(offsets) > 0  # .hair stores every strand; one of a single point too
    assert np.array_equal(p2, points) and np.array_equal(np.diff(o2), np.diff(offsets)) and grown.any()


def test_session_round_trip_and_primitives(tmp_path):
    # The session names its head relative to itself (../head.obj): save it where that resolves.
    for f in ("head.obj", "head_scalp.txt"):
        shutil.copy(SOURCE_DIR / "assets" / f, tmp_path / f)
    (tmp_path / "sessions").mkdir()
    s = small(lapis.HairSession.load(str(SESSIONS / "smooth.json")))
    before = list(s.primitives)
    s.add_stream_curve([[0.0, 0.95, 0.35], [0.0, 0.9, -0.3], [0.0, 0.4, -0.9]], tail_segments=2)
    assert s.primitives == before + ["stream_curve"]
    s.save(str(tmp_path / "sessions" / "s.json"))
    t = lapis.HairSession.load(str(tmp_path / "sessions" / "s.json"), replay=False)
    assert t.primitives == s.primitives and t.roots == 300
    a, b = s.build(), t.build()
    assert np.array_equal(a["points"], b["points"]) and np.array_equal(a["offsets"], b["offsets"])
    t.remove_primitive(len(t.primitives) - 1)
    assert not np.array_equal(t.build()["points"], a["points"])
    lapis.write_strands_obj(str(tmp_path / "s.obj"), a["points"], a["offsets"])
    assert (tmp_path / "s.obj").read_text().count("\nl ") > 0
    with pytest.raises(lapis.InvalidArgument, match="out of range"):
        t.remove_primitive(99)


def test_strand_arrays_are_checked(tmp_path):
    with pytest.raises(TypeError, match="points must be float32, not float64"):
        lapis.write_hair(str(tmp_path / "x.hair"), np.zeros((2, 3)), [0, 2])
    with pytest.raises(ValueError, match="offsets must run from 0 to the 2 points"):
        lapis.write_hair(str(tmp_path / "x.hair"), np.zeros((2, 3), np.float32), [0, 1])
    with pytest.raises(lapis.IoError, match="missing.json"):
        lapis.HairSession.load(str(tmp_path / "missing.json"))
