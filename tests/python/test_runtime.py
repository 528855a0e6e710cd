"""Long calls release the GIL; repeated calls leak neither references nor memory."""

import gc
import sys
import threading
import time
import weakref

import numpy as np

import lapis


def test_precompute_releases_the_gil(source_dir):
    # The bunny after one Loop step: 151K vertices, a precompute of about a second.
    path = source_dir / "assets" / "external" / "bunny00.off"
    assert path.exists(), f"{path} is missing: scripts/setup extracts it from libcgal-demo"
    V, F = lapis.loop_subdivide(*lapis.read_mesh(str(path)), 1)
    assert len(V) > 150_000, len(V)
    low, high = V[:, 1].min(), V[:, 1].max()
    roi = np.flatnonzero(V[:, 1] > low + 0.3 * (high - low))
    handle = np.flatnonzero(V[:, 1] > high - 0.1 * (high - low))
    d = lapis.Deformer(V, F, "naive")
    d.set_selection(roi, regions=[handle])
    span = {}

    def work():
        span["start"] = time.perf_counter()
        d.precompute()
        span["end"] = time.perf_counter()

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    duration = span["end"] - span["start"]
    # Ticks strictly inside the call, away from its ends: none if the call held the GIL.
    margin = 0.1 * duration
    inside = [t for t in ticks if span["start"] + margin < t < span["end"] - margin]
    assert duration > 0.02, duration
    assert len(inside) > 100, (len(inside), duration)


def rss_mb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096 / 2**20


def test_no_leak_over_1000_calls():
    V, F = lapis.make_box_bar(8, 3, 3, 4.0, 1.0, 1.0)
    roi = np.flatnonzero(V[:, 0] > 0.5)
    handle = np.flatnonzero(V[:, 0] > 3.5)
    d = lapis.Deformer(V, F, "implicit")
    d.set_selection(roi, regions=[handle])
    d.precompute()
    T = np.eye(4)[None].copy()
    T[0, 1, 3] = 0.2
    refs = (sys.getrefcount(V), sys.getrefcount(F), sys.getrefcount(T))

    def calls(n):
        for _ in range(n):
            W = d.deform(T)
            lapis.face_areas(W, F)
            lapis.cotan_laplacian(W, F)
            lapis.read_handles  # attribute lookups only
        return W

    calls(100)
    gc.collect()
    objects, before = len(gc.get_objects()), rss_mb()
    W = calls(1000)
    gc.collect()
    assert (sys.getrefcount(V), sys.getrefcount(F), sys.getrefcount(T)) == refs
    assert len(gc.get_objects()) <= objects + 10
    # The arrays own their C++ storage: dropping the last reference frees it.
    alive = weakref.ref(W)
    del W
    assert alive() is None
    assert rss_mb() - before < 8, rss_mb() - before
