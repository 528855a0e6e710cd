#!/usr/bin/env python3
"""The Python bindings' overhead: a deform frame at 151K vertices and a hair regrowth at 50K
unknowns called through `import lapis`, against the same calls from C++ in the same run.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_bindings.py [--build build]
        [--frames 20] [--edits 10] [--repetitions 3]

The C++ side is bench_bindings_baseline (built with LAPIS_BUILD_BENCH and the Python module),
a second process that reads the same input files and answers one command per line, so that
the two sides take turns call by call (who goes first alternates) and a slow spell of this
shared machine falls on both. A deform frame is Deformer.deform() on the bunny Loop-subdivided
once (151K vertices), lowest 10% along y fixed, top 5% the handle, turned 45 degrees about z
and moved 0.15 diagonals over the drag (bench_mesh_deform's set-up), for the implicit method
and ARAP. A regrowth is a stroke added to (then removed from) the bundled parting session at
50K unknowns and 20K strands on the multigrid field path: the constraint diff, the field
update and the regrowth of every strand (LiveHairstyle.update()). Both sides' last results are
compared bit for bit. "outside C++ ms" is the part of a Python call that LiveHairstyle's own
timer does not see: the bindings' cost itself. The Python side runs with the allocator the C++
executables link (jemalloc, preloaded) unless --system-allocator. Prints a table and writes
bench/results/python_bindings.json (python_bindings_system_allocator.json).
"""

import argparse
import ctypes.util
import datetime
import json
import os
import pathlib
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import lapis

SOURCE = pathlib.Path(__file__).resolve().parents[2]


class Baseline:
    """bench_bindings_baseline as a child process: one command per line, one JSON line back."""

    def __init__(self, exe, *args):
        self.proc = subprocess.Popen([str(exe), *map(str, args)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     text=True)
        line = self.proc.stdout.readline().strip()
        if line != "ready":
            raise RuntimeError(f"bench_bindings_baseline did not start (said {line!r}, exit {self.proc.poll()})")

    def ask(self, command):
        self.proc.stdin.write(command + "\n")
        self.proc.stdin.flush()
        return json.loads(self.proc.stdout.readline())

    def close(self):
        self.proc.stdin.write("quit\n")
        self.proc.stdin.close()
        self.proc.wait()


def timed(f):
    t0 = time.perf_counter()
    f()
    return (time.perf_counter() - t0) * 1e3


def take_turns(python_call, cpp_call, calls):
    """Runs call i of each side in turn, the first side alternating; returns (python ms, C++ ms)."""
    py, cpp = [], []
    for i in range(calls):
        if i % 2 == 0:
            py.append(timed(lambda: python_call(i)))
            cpp.append(cpp_call(i))
        else:
            cpp.append(cpp_call(i))
            py.append(timed(lambda: python_call(i)))
    return py, cpp


def drag_setup(V, frames):
    """bench_mesh_deform's selection and drag: (roi, handle, a 4x4 transform per frame)."""
    n = V.shape[0]
    order = np.argsort(V[:, 1], kind="stable")
    roi = np.sort(order[n // 10:]).astype(np.int32)
    handle = order[n - n // 20:].astype(np.int32)
    c = V[handle].mean(axis=0)
    diag = np.linalg.norm(V.max(axis=0) - V.min(axis=0))
    drag = []
    for f in range(1, frames + 1):
        t = f / frames
        a = t * np.pi / 4
        T = np.eye(4)
        T[:2, :2] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
        T[:3, 3] = c - T[:3, :3] @ c + [0.15 * diag * t, 0, 0]
        drag.append(T)
    return roi, handle, drag


def bench_deform(exe, tmp, method, frames, repetitions):
    mesh = SOURCE / "assets" / "external" / "bunny00.off"
    V, F = lapis.loop_subdivide(*lapis.read_mesh(str(mesh)), 1)
    roi, handle, drag = drag_setup(V, frames)
    (tmp / "roi.txt").write_text(" ".join(map(str, roi)))
    (tmp / "handles.json").write_text(json.dumps(
        {"regions": [{"vertices": handle.tolist(), "transforms": [T.tolist() for T in drag]}], "points": []}))
    cpp = Baseline(exe, "deform", mesh, 1, method, tmp / "roi.txt", tmp / "handles.json")
    d = lapis.Deformer(V, F, method)
    d.set_selection(roi, regions=[handle])
    d.precompute()
    last = {}

    def python_frame(i):
        last["W"] = d.deform(drag[i % frames][None])

    py, cc = take_turns(python_frame, lambda i: cpp.ask(f"frame {i % frames}")["ms"], frames * repetitions)
    cpp.ask(f"save {tmp / 'cpp.obj'}")
    cpp.close()
    identical = bool(np.array_equal(lapis.read_mesh(str(tmp / "cpp.obj"))[0], last["W"]))
    return {"job": f"deform frame, {method}", "size": f"{V.shape[0]} vertices", "outside_cpp_ms": None}, py, cc, identical


def stroke_over_head():
    """A stream curve from near the crown over the side of the bundled head, 1.2 radii out."""
    H, _ = lapis.read_mesh(str(SOURCE / "assets" / "head.obj"))
    lo, hi = H.min(axis=0), H.max(axis=0)
    center, R = (lo + hi) / 2, 1.2 * 0.5 * (hi - lo)[0]
    phi = -np.pi / 2 - 0.25
    a = 0.3 + 1.2 * np.linspace(0, 1, 41)
    return center + R * np.stack([np.sin(a) * np.cos(phi), np.cos(a), np.sin(a) * np.sin(phi)], axis=1)


def bench_hair(exe, tmp, edits, repetitions, unknowns=50000, roots=20000):
    session = SOURCE / "assets" / "sessions" / "parting.json"
    stroke = stroke_over_head()
    (tmp / "stroke.json").write_text(json.dumps(stroke.tolist()))
    cpp = Baseline(exe, "hair", session, unknowns, roots, "multigrid", tmp / "stroke.json")
    s = lapis.HairSession.load(str(session), replay=False)
    s.grid_unknowns, s.roots, s.field_method = unknowns, roots, lapis.FieldMethod.multigrid
    s.replay()
    live = lapis.LiveHairstyle(s)
    last = {"r": live.update()}

    inside = []  # the C++ part of each Python call, as LiveHairstyle times it

    def python_edit(i):
        if i % 2 == 0:
            s.add_stream_curve(stroke)
        else:
            s.remove_primitive(len(s.primitives) - 1)
        last["r"] = live.update()
        inside.append(last["r"]["timings_ms"]["total"])

    py, cc = take_turns(python_edit, lambda i: cpp.ask("stroke" if i % 2 == 0 else "unstroke")["ms"],
                        2 * edits * repetitions + 1)  # odd: the last edit adds the stroke
    info_inside = statistics.median(p - c for p, c in zip(py, inside))
    cpp.ask(f"save {tmp / 'cpp.hair'}")
    cpp.close()
    lapis.write_hair(str(tmp / "py.hair"), last["r"]["points"], last["r"]["offsets"])
    identical = (tmp / "py.hair").read_bytes() == (tmp / "cpp.hair").read_bytes()
    size = f"{unknowns // 1000}K unknowns, {len(last['r']['offsets']) - 1} strands"
    return {"job": "hair regrowth (stroke / edit)", "size": size, "outside_cpp_ms": info_inside}, py, cc, identical


def row(info, py, cpp, identical):
    ratios = [p / c for p, c in zip(py, cpp)]
    return dict(info, calls=len(py), python_ms=statistics.median(py), cpp_ms=statistics.median(cpp),
                overhead=statistics.median(py) / statistics.median(cpp) - 1, paired_overhead=statistics.median(ratios) - 1,
                identical=identical, python_ms_all=py, cpp_ms_all=cpp)


def cpu_model():
    for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return platform.processor()


def jemalloc_environment():
    """The environment that gives this process the allocator Lapis' executables link (jemalloc
    with the options of modules/core/allocator), or None when jemalloc is missing."""
    library = ctypes.util.find_library("jemalloc")
    options = re.search(r'malloc_conf = "([^"]*)"',
                        (SOURCE / "modules" / "core" / "allocator" / "jemalloc_options.cpp").read_text())
    if not library or not options:
        return None
    return dict(os.environ, LD_PRELOAD=library, MALLOC_CONF=options.group(1), LAPIS_BENCH_ALLOCATOR="jemalloc")


def command_line(args):
    """The command with every option spelled out (the build tree left out)."""
    words = ["bench/python/bench_bindings.py"]
    for key, value in vars(args).items():
        flag = "--" + key.replace("_", "-")
        if isinstance(value, bool):
            words += [flag] if value else []
        elif key != "build":
            words += [flag, str(value)]
    return " ".join(words)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=str(SOURCE / "build"), help="the build tree (bench/python/bench_bindings_baseline)")
    ap.add_argument("--frames", type=int, default=20, help="deform frames per drag")
    ap.add_argument("--edits", type=int, default=10, help="stroke + removal pairs per repetition")
    ap.add_argument("--repetitions", type=int, default=3)
    ap.add_argument("--methods", default="implicit,arap")
    ap.add_argument("--system-allocator", action="store_true",
                    help="keep Python's allocator (glibc) instead of the C++ side's jemalloc")
    args = ap.parse_args()
    # The same allocator on both sides, so the figures compare the bindings, not two mallocs:
    # glibc maps a large block in 4 KB pages and unmaps it on free, so each frame faults its
    # output and temporaries in again where jemalloc (thp, no decay) reuses them.
    if not args.system_allocator and "LAPIS_BENCH_ALLOCATOR" not in os.environ:
        env = jemalloc_environment()
        if env:
            os.execve(sys.executable, [sys.executable, *sys.argv], env)
    allocator = os.environ.get("LAPIS_BENCH_ALLOCATOR", "system (glibc)")
    print(f"Python side allocator: {allocator}; C++ side: jemalloc when the build links it")
    exe = pathlib.Path(args.build) / "bench" / "python" / "bench_bindings_baseline"
    if not exe.exists():
        raise SystemExit(f"{exe} is missing: configure with -DLAPIS_BUILD_BENCH=ON and build it")
    rows = []
    with tempfile.TemporaryDirectory() as t:
        tmp = pathlib.Path(t)
        for method in args.methods.split(","):
            rows.append(row(*bench_deform(exe, tmp, method, args.frames, args.repetitions)))
        rows.append(row(*bench_hair(exe, tmp, args.edits, args.repetitions)))
    header = ("job", "size", "calls", "Python ms", "C++ ms", "overhead", "paired", "outside C++ ms", "same result")
    table = [(r["job"], r["size"], str(r["calls"]), f"{r['python_ms']:.2f}", f"{r['cpp_ms']:.2f}",
              f"{100 * r['overhead']:+.2f}%", f"{100 * r['paired_overhead']:+.2f}%",
              "-" if r["outside_cpp_ms"] is None else f"{r['outside_cpp_ms']:.3f}", "yes" if r["identical"] else "NO")
             for r in rows]
    widths = [max(len(x) for x in col) for col in zip(header, *table)]
    for line in (header, *table):
        print("  ".join(x.ljust(w) for x, w in zip(line, widths)))
    out = {"date": datetime.date.today().isoformat(), "cpu": cpu_model(), "threads": os.cpu_count(),
           "load_average": os.getloadavg(), "python_allocator": allocator, "python": platform.python_version(), "numpy": np.__version__,
           "allocator_environment": {k: os.environ[k] for k in ("MALLOC_CONF", "GLIBC_TUNABLES") if k in os.environ},
           "command": command_line(args), "rows": rows}
    name = "python_bindings" + ("_system_allocator" if allocator.startswith("system") else "")
    path = SOURCE / "bench" / "results" / f"{name}.json"
    tmp_path = path.with_suffix(".json.tmp")
    tmp_path.write_text(json.dumps(out, indent=2) + "\n")
    tmp_path.replace(path)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
