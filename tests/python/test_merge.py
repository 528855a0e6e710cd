"""Merging: every mode on the bundled pairs, the same mesh as `lapis merge`, the report as a dict."""

import numpy as np
import pytest

import lapis
from conftest import SOURCE_DIR

MERGE = SOURCE_DIR / "assets" / "merge"


def mesh(name):
    return lapis.read_mesh(str(MERGE / name))


@pytest.mark.parametrize("mode,source", [
    ("independent", "dome.obj"),
    ("dependent", "dome_placed.obj"),
    ("transition", "dome.obj"),
])
def test_modes_equal_the_cli(tmp_path, cli, mode, source):
    sV, sF = mesh(source)
    tV, tF = mesh("neck.obj")
    pairs = lapis.read_pairs(str(MERGE / "dome_on_neck.json"))
    assert len(pairs) == 1 and pairs[0].shape == (1, 2)
    V, F, report = lapis.merge(sV, sF, tV, tF, pairs, mode=mode)
    cli("merge", "--source", MERGE / source, "--target", MERGE / "neck.obj", "--pairs", MERGE / "dome_on_neck.json",
        "--mode", mode, "--out", tmp_path / "out.obj")
    W, G = lapis.read_mesh(str(tmp_path / "out.obj"))
    assert np.array_equal(V, W) and np.array_equal(F, G)
    assert report["seam"]["valid"] and report["seam"]["boundary_edges"] == 0
    # The target stays where it is, but for the seam band the smoothing moved.
    kept = report["target_map"] >= 0
    merged = report["target_map"][kept]
    still = ~np.isin(merged, report["smoothed"])
    assert still.sum() > 0.5 * tV.shape[0]
    assert np.array_equal(V[merged[still]], tV[kept][still]) or mode == "transition"


def test_optimal_boundary_equals_the_cli(tmp_path, cli):
    sV, sF = mesh("bump.obj")
    tV, tF = mesh("plate.obj")
    regions = lapis.read_regions(str(MERGE / "bump_regions.json"), sV, sF, tV, tF)
    V, F, report = lapis.merge_optimal(sV, sF, tV, tF, regions)
    cli("merge", "--mode", "optimal", "--source", MERGE / "bump.obj", "--target", MERGE / "plate.obj", "--regions",
        MERGE / "bump_regions.json", "--out", tmp_path / "out.obj")
    W, G = lapis.read_mesh(str(tmp_path / "out.obj"))
    assert np.array_equal(V, W) and np.array_equal(F, G)
    assert report["energy"] <= report["user_energy"] and report["boundary"].size > 0
    _, _, free = lapis.merge_optimal(sV, sF, tV, tF, regions, hold_feature=False)
    assert 0 <= report["feature_distortion"] <= free["feature_distortion"]


def test_pairs_as_plain_lists_and_errors():
    sV, sF = mesh("dome.obj")
    tV, tF = mesh("neck.obj")
    V, F, _ = lapis.merge(sV, sF, tV, tF, [[(175, 384)]])
    assert V.shape[1] == 3
    with pytest.raises(lapis.InvalidArgument, match="mesh_merge::"):
        lapis.merge(sV, sF, tV, tF, [[(0, 384)]])  # vertex 0 is not on the source boundary
    with pytest.raises(ValueError, match="mode must be independent, dependent or transition"):
        lapis.merge(sV, sF, tV, tF, [[(175, 384)]], mode="optimal")
