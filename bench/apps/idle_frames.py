#!/usr/bin/env python3
"""What a frame of the apps costs on this machine's software GL (Xvfb + Mesa llvmpipe), with
the picture of an unchanged scene reused and, as the baseline in the same run, drawn again
every frame (--no-frame-cache).

    python3 bench/apps/idle_frames.py [--build build] [--size 1280x800]

Each row runs an app headless on a bundled mesh and replays one of two inputs: `hover`, 60
pointer moves over the 3D view with nothing pressed (an idle window: picking, a brush circle,
panels), and `orbit`, a right-drag orbiting the camera through the same 60 moves (the scene
must be drawn every frame). The viewer's --benchmark report gives the median and p95 frame
time. Prints a table and writes bench/results/idle_frames.json.
"""

import argparse
import datetime
import json
import os
import pathlib
import platform
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]


def events(kind, width, height):
    out, frame = [], 10
    if kind == "orbit":
        out.append({"type": "move", "frame": frame, "x": width * 0.35, "y": height * 0.4})
        out.append({"type": "button", "frame": frame + 1, "x": width * 0.35, "y": height * 0.4,
                    "button": 1, "action": 1, "mods": 0})
        frame += 2
    for k in range(60):
        out.append({"type": "move", "frame": frame, "x": width * 0.35 + 4 * k, "y": height * 0.4 + k})
        frame += 1
    if kind == "orbit":
        out.append({"type": "button", "frame": frame, "x": width * 0.35 + 240, "y": height * 0.4 + 60,
                    "button": 1, "action": 0, "mods": 0})
    return {"format": "lapis-events", "version": 1, "width": width, "height": height, "events": out}


def run(app, args, kind, cache, size, scratch):
    width, height = (int(v) for v in size.split("x"))
    replay = scratch / f"{kind}.json"
    replay.write_text(json.dumps(events(kind, width, height)))
    report = scratch / "report.json"
    cmd = ["xvfb-run", "-a", "-s", f"-screen 0 {width}x{height}x24", str(app), *args, "--headless",
           "--size", size, "--replay", str(replay), "--exit-after-replay", "--benchmark", str(report)]
    if not cache:
        cmd.append("--no-frame-cache")
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=scratch)
    return json.loads(report.read_text())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--size", default="1280x800")
    opts = parser.parse_args()
    build = pathlib.Path(opts.build)
    external = ROOT / "assets" / "external"
    rows = [("lapis-deform", build / "apps/mesh_deform/lapis-deform", [str(p)], p.stem)
            for p in sorted(external.glob("*.off"))]
    rows.append(("lapis-merge", build / "apps/mesh_merge/lapis-merge", ["--preset", "2"], "preset 2"))
    rows.append(("lapis-hair-sketch", build / "apps/hair_sketch/lapis-hair-sketch", [], "default session"))
    results = []
    header = f"{'app':18} {'input':22} {'kind':6} {'cached median/p95 ms':>22} {'redrawn median/p95 ms':>23} {'ratio':>6}"
    print(header)
    with tempfile.TemporaryDirectory() as tmp:
        scratch = pathlib.Path(tmp)
        for name, app, args, label in rows:
            for kind in ("hover", "orbit"):
                cached = run(app, args, kind, True, opts.size, scratch)
                redrawn = run(app, args, kind, False, opts.size, scratch)
                ratio = redrawn["frame_ms_median"] / cached["frame_ms_median"]
                print(f"{name:18} {label:22} {kind:6} {cached['frame_ms_median']:10.1f} / {cached['frame_ms_p95']:7.1f}"
                      f"   {redrawn['frame_ms_median']:10.1f} / {redrawn['frame_ms_p95']:7.1f} {ratio:6.1f}",
                      flush=True)
                results.append({"app": name, "input": label, "kind": kind, "cached": cached, "redrawn": redrawn})
    out = ROOT / "bench" / "results" / "idle_frames.json"
    out.write_text(json.dumps({"date": datetime.date.today().isoformat(), "machine": platform.machine(),
                               "cpus": os.cpu_count(), "size": opts.size, "results": results}, indent=1) + "\n")
    print(f"wrote {out.relative_to(ROOT)}")


if __name__ == "__main__":
    sys.exit(main())
