"""Shared fixtures: where the CLI and the assets are (CTest passes them in the environment)."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import lapis

SOURCE_DIR = pathlib.Path(os.environ.get("LAPIS_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def cli():
    """Runs the `lapis` command line with the given arguments; skips when CTest did not say where it is."""
    path = os.environ.get("LAPIS_CLI")
    if not path:
        pytest.skip("LAPIS_CLI is not set (CTest sets it)")

    def run(*args):
        return subprocess.run([path, *map(str, args)], check=True, capture_output=True, text=True)

    return run


@pytest.fixture
def bar():
    """A closed box bar along x, (V, F): the deformation tests' shape (thesis fig. 2.7)."""
    return lapis.make_box_bar(16, 3, 3, 4.0, 1.0, 1.0)


def bar_selection(V):
    """ROI: x > 0.5 (the rest is fixed); one region handle: the end cap x > 3.75."""
    roi = np.flatnonzero(V[:, 0] > 0.5).astype(np.int32)
    handle = np.flatnonzero(V[:, 0] > 3.75).astype(np.int32)
    return roi, handle


def bend(angle, lift):
    """A 4x4 turn about z through the bar's end plus a lift in y."""
    c, s = np.cos(angle), np.sin(angle)
    T = np.eye(4)
    T[:2, :2] = [[c, -s], [s, c]]
    T[:3, 3] = np.array([4.0, 0.5, 0.0]) - T[:3, :3] @ np.array([4.0, 0.5, 0.0]) + [0.0, lift, 0.0]
    return T


def write_handles(path, regions, frames):
    """A handles file of `lapis deform`: region handles with one transform per frame."""
    doc = {"regions": [{"vertices": [int(i) for i in r], "transforms": [f[k].tolist() for f in frames]}
                       for k, r in enumerate(regions)], "points": []}
    pathlib.Path(path).write_text(json.dumps(doc))
