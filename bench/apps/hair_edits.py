#!/usr/bin/env python3
"""What one edit costs in the hair app, by stage: the stroke's release to its strands drawn in
the window, as `lapis-hair-sketch --benchmark` reports it (both solves, growth, detail,
self-shadowing, display, drawing). Software GL under Xvfb, 20K strands by default, drawn
within the window's adaptive budget (frames near 80 ms) as a user sees them. The window draws every
k-th strand: an edit grows those first (a preview, the same picture) and the rest after its
frame; "total" is the release to the strands drawn, "all_strands" to every strand grown, and
"previewed" counts the edits that had a preview ("redrawn": of those, the edits whose whole set
then showed other strands).

    python3 bench/apps/hair_edits.py [--build build] [--roots 20000] [--strokes 6] [--draw-segments N]

Each row replays the same strokes, each followed by an `idle` event (the next stroke waits for
the strands of the last), on a new style at the app's default grid and on bundled sessions
with their own grids and details; the first edit of a run also builds the solver, so it is
reported apart. Prints a table of medians over the other edits and writes
bench/results/hair_edits.json.
"""

import argparse
import datetime
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
WIDTH, HEIGHT = 900, 700
STAGES = ["style_solve_ms", "avoidance_ms", "avoidance_solve_ms", "growth_ms", "detail_ms", "occlusion_ms", "display_ms", "draw_ms",
          "waiting_ms", "queued_ms", "handover_ms", "total_ms", "rest_ms", "all_strands_ms"]


def events(strokes):
    """Downward strokes starting on the top of the head in the default view (each start checked
    to be accepted as a stream curve), over its front half."""
    out, frame = [], 10
    starts = [(506, 187), (430, 180), (450, 175), (520, 180), (480, 170), (440, 170), (495, 178), (515, 172)]
    for k in range(strokes):
        x0, y0 = starts[k % len(starts)]
        out.append({"type": "move", "frame": frame, "x": x0, "y": y0})
        out.append({"type": "button", "frame": frame + 1, "x": x0, "y": y0, "button": 0, "action": 1, "mods": 0})
        for i in range(1, 19):
            out.append({"type": "move", "frame": frame + 1 + i // 2, "x": x0 + 2 * i, "y": y0 + 9 * i})
        out.append({"type": "button", "frame": frame + 11, "x": x0 + 36, "y": y0 + 162, "button": 0, "action": 0,
                    "mods": 0})
        out.append({"type": "idle", "frame": frame + 12})
        frame += 20
    return {"format": "lapis-events", "version": 1, "width": WIDTH, "height": HEIGHT, "events": out}


def run(app, session, extra, strokes, roots, draw_segments, scratch):
    replay = scratch / "edits.json"
    replay.write_text(json.dumps(events(strokes)))
    report, saved = scratch / "report.json", scratch / "saved.json"
    args = ["--roots", str(roots)] + (["--draw-segments", str(draw_segments)] if draw_segments is not None else [])
    args += (["--session", str(session)] if session else []) + extra
    cmd = ["xvfb-run", "-a", "-s", f"-screen 0 {WIDTH}x{HEIGHT}x24", str(app), *args, "--size", f"{WIDTH}x{HEIGHT}",
           "--replay", str(replay), "--exit-after-replay", "--benchmark", str(report), "--save-session", str(saved)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=scratch)
    r = json.loads(report.read_text())
    autosave = scratch / "saved.json.autosave.json"  # written on exit
    primitives = len(json.loads(autosave.read_text())["primitives"])
    return r, primitives


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default="build")
    p.add_argument("--roots", type=int, default=20000)
    p.add_argument("--strokes", type=int, default=6)
    p.add_argument("--draw-segments", type=int, default=None,
                   help="strand segments drawn, pinned (0: all); default: the window's adaptive budget")
    o = p.parse_args()
    app = (ROOT / o.build / "apps/hair_sketch/lapis-hair-sketch").resolve()
    if not app.exists():
        sys.exit(f"hair_edits.py: {app} not built")
    rows = [("new style (default grid)", None, []),
            ("new style, lines", None, ["--strands", "lines"]),
            ("smooth.json", ROOT / "assets/sessions/smooth.json", []),
            ("wavy_long.json (details)", ROOT / "assets/sessions/wavy_long.json", [])]
    results = []
    print(f"{'style':28} {'grid':>6} {'edits':>5} " + " ".join(f"{s[:-3]:>12}" for s in STAGES) + "   first edit  previewed  redrawn")
    with tempfile.TemporaryDirectory() as tmp:
        for name, session, extra in rows:
            r, primitives = run(app, session, extra, o.strokes, o.roots, o.draw_segments, pathlib.Path(tmp))
            edits = r.get("edits", [])
            later = edits[1:] if len(edits) > 1 else edits
            median = {s: statistics.median(e[s] for e in later) for s in STAGES} if later else {}
            row = {"style": name, "grid_unknowns": r.get("grid_unknowns"), "strands": r.get("strands"),
                   "segments": r.get("segments"), "drawn_segments": r.get("drawn_segments"),
                   "frame_ms_median": r.get("frame_ms_median"), "frame_ms_p95": r.get("frame_ms_p95"),
                   "primitives_after": primitives, "edits": edits,
                   "median_after_first": median, "first_edit_ms": edits[0]["total_ms"] if edits else None,
                   "previewed": sum(1 for e in later if e.get("preview")),
                   "redrawn": sum(1 for e in later if e.get("redrawn"))}
            results.append(row)
            print(f"{name:28} {r.get('grid_unknowns', 0):>6} {len(edits):>5} " +
                  " ".join(f"{median.get(s, float('nan')):>12.1f}" for s in STAGES) +
                  f"   {row['first_edit_ms'] or float('nan'):>10.0f}  {row['previewed']:>9}  {row['redrawn']:>7}")
    out = ROOT / "bench/results/hair_edits.json"
    out.write_text(json.dumps({"benchmark": "hair_edits", "date": datetime.date.today().isoformat(),
                               "machine": f"{platform.machine()}, {os.cpu_count()} cores",
                               "command": "python3 bench/apps/hair_edits.py " + " ".join(sys.argv[1:]),
                               "roots": o.roots, "draw_segments": o.draw_segments, "rows": results}, indent=2) + "\n")
    print(f"wrote {out.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
