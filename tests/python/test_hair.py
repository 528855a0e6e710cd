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


def test_live_hairstyle_follows_the_session():
    s = small(lapis.HairSession.load(str(SESSIONS / "parting.json"), replay=False))
    s.replay()
    live = lapis.LiveHairstyle(s)
    r = live.update()
    b = s.build()
    # The first update solves from scratch, like build(): the same strands and field. The field
    # agrees to rounding only: the multigrid's residual norms are OpenMP reductions, whose
    # partial sums add up in the order the threads finish (5e-13 seen on a loaded machine).
    assert np.array_equal(r["points"], b["points"]) and np.array_equal(r["offsets"], b["offsets"])
    assert np.abs(live.field - b["field"]).max() <= 1e-10 * np.abs(b["field"]).max()
    assert live.roots.shape == (len(b["offsets"]) - 1, 3)
    assert r["constraints"] == b["constraints"]
    kept = r["points"].copy()

    # An edit: only the diff reaches the solver, and the result is the one build() finds.
    s.remove_primitive(len(s.primitives) - 1)
    r2 = live.update()
    assert r2["solves"][0]["removed"] > 0 and r2["solves"][0]["added"] == 0
    b2 = s.build()
    assert np.array_equal(r2["offsets"], b2["offsets"])
    assert np.abs(r2["points"] - b2["points"]).max() < 1e-4
    # The earlier result is still alive, so its storage was not written into.
    assert np.array_equal(r["points"], kept)
    assert not np.shares_memory(r["points"], r2["points"])


def test_live_hairstyle_regrows_into_dropped_storage():
    s = small(lapis.HairSession.load(str(SESSIONS / "parting.json"), replay=False))
    s.replay()
    live = lapis.LiveHairstyle(s)
    r = live.update()
    address = r["points"].__array_interface__["data"][0]
    view = r["offsets"]  # a view keeps the storage: it is not reused while any array is alive
    del r
    r = live.update()
    assert r["points"].__array_interface__["data"][0] != address
    del view
    r = None
    r = live.update()
    r = live.update()  # two buffers alternate once every older result is gone
    addresses = {live.update()["points"].__array_interface__["data"][0] for _ in range(3)}
    assert len(addresses) <= 2


def test_hair_attributes_round_trip(tmp_path):
    points = np.array([[0, 0, 0], [0, 1, 0], [0, 2, 0], [1, 0, 0], [1, 1, 0]], dtype=np.float32)
    offsets = np.array([0, 3, 5], dtype=np.int32)
    thickness = np.linspace(1, 2, 5).astype(np.float32)
    lapis.write_hair(str(tmp_path / "a.hair"), points, offsets, thickness=thickness, transparency=0.25,
                     colors=[0.5, 0.25, 0.125], info="two strands")
    a = lapis.read_hair_attributes(str(tmp_path / "a.hair"))
    assert np.array_equal(a["thickness"], thickness)
    assert np.array_equal(a["transparency"], np.full(5, 0.25, np.float32))
    assert a["colors"].shape == (5, 3) and np.array_equal(a["colors"][3], np.float32([0.5, 0.25, 0.125]))
    assert a["info"] == "two strands"
    p, o = lapis.read_hair(str(tmp_path / "a.hair"))
    assert np.array_equal(p, points) and np.array_equal(o, offsets)
    colors = np.random.default_rng(1).random((5, 3)).astype(np.float32)
    lapis.write_hair(str(tmp_path / "b.hair"), points, offsets, colors=colors)
    assert np.array_equal(lapis.read_hair_attributes(str(tmp_path / "b.hair"))["colors"], colors)
    with pytest.raises(ValueError, match=r"thickness must be a number or have shape \(5,\), not \(4,\)"):
        lapis.write_hair(str(tmp_path / "c.hair"), points, offsets, thickness=thickness[:4])
    with pytest.raises(ValueError, match=r"colors must be an RGB triple or have shape \(5, 3\)"):
        lapis.write_hair(str(tmp_path / "c.hair"), points, offsets, colors=[1, 2])


def test_field_method_is_a_setting_each_method_solves_alike():
    s = small(lapis.HairSession.load(str(SESSIONS / "parting.json")))
    s.field_method = lapis.FieldMethod.thesis
    exact = s.build()["field"]
    s.field_method = lapis.FieldMethod.multigrid
    assert s.field_method == lapis.FieldMethod.multigrid
    iterative = s.build()["field"]
    s.field_method = lapis.FieldMethod.refactorize
    refactorized = s.build()["field"]
    # The direct paths agree to rounding, the multigrid one to its tolerance; none is zero.
    assert np.abs(exact).max() > 0.1
    assert 0 < np.abs(iterative - exact).max() < 1e-3 * np.abs(exact).max()
    assert np.abs(refactorized - exact).max() < 1e-9 * np.abs(exact).max()
    with pytest.raises(TypeError):
        s.field_method = "multigrid"


def test_live_hairstyle_applies_the_session_details_without_regrowing_for_them():
    s = small(lapis.HairSession.load(str(SESSIONS / "curly_bob.json")))
    assert s.details == ["length", "cut", "clump", "curl"]
    live = lapis.LiveHairstyle(s)
    first = live.update()
    assert first["regrown"]
    points = first["points"].copy()
    again = live.update()  # nothing changed: the grown strands are reused, the details reapplied
    assert not again["regrown"]
    assert np.array_equal(again["points"], points)
    built = s.build()
    assert np.array_equal(built["points"], points)  # the same details as the one-shot build


def test_live_hairstyle_previews_every_kth_strand_as_the_update_grows_it():
    s = small(lapis.HairSession.load(str(SESSIONS / "wavy_long.json")))  # a clump, waves and frizz
    live = lapis.LiveHairstyle(s)
    p = live.preview(5)
    assert len(p["solves"]) == 2
    r = live.update()
    assert r["solves"] == []  # the preview's solve holds
    o = r["offsets"]
    assert len(p["offsets"]) - 1 == (len(o) - 1 + 4) // 5
    for k in range(len(p["offsets"]) - 1):
        mine = p["points"][p["offsets"][k]:p["offsets"][k + 1]]
        assert np.array_equal(mine, r["points"][o[5 * k]:o[5 * k + 1]])
    with pytest.raises(lapis.InvalidArgument, match="stride must be at least 1"):
        live.preview(0)
