#!/usr/bin/env python3
"""Writes the deform app's bundled event logs (1200x800 windows). Pixel positions were read off
screenshots of the app at each step.

  assets/events/make_deform_demo.py > assets/events/deform_demo.json
      `scripts/demo deform` and docs/images/deform_app.png, on the armadillo with
      assets/selections/armadillo_hand.*: orbit to a front three-quarter view, pull the right
      hand up and out with the gizmo's arrows, turn it with a ring, colour by edge-length
      distortion.
  assets/events/make_deform_demo.py bench > assets/events/deform_bench.json
      the --benchmark run of bench/README.md, on bunny00 Loop-subdivided once (150,818 vertices): lasso
      the bottom as fixed and the ear tips as the handle, wait for the setup (an "idle" event
      holds the replay while the app is busy), then drag the handle up and sideways.
"""
import json
import math
import sys

W, H = 1200, 800
events, frame = [], 5


def ev(kind, **fields):
    events.append({"type": kind, "frame": frame, "time": frame / 30.0, **fields})


def drag(button, start, end, steps=20, wait=2):
    """Press at start, move to end in steps (one a frame), release; then wait frames."""
    global frame
    ev("move", x=start[0], y=start[1])
    ev("button", x=start[0], y=start[1], button=button, action=1, mods=0)
    for k in range(1, steps + 1):
        frame += 1
        ev("move", x=start[0] + (end[0] - start[0]) * k / steps, y=start[1] + (end[1] - start[1]) * k / steps)
    frame += 1
    ev("button", x=end[0], y=end[1], button=button, action=0, mods=0)
    frame += wait


def key(code, wait=2):
    global frame
    ev("key", key=code, action=1, mods=0)
    frame += 1
    ev("key", key=code, action=0, mods=0)
    frame += wait


RIGHT, LEFT = 1, 0
def lasso(corners, wait=2):
    """A closed lasso through the corners (a drag along its edges, 5 steps an edge)."""
    global frame
    path = []
    for a, b in zip(corners, corners[1:] + corners[:1]):
        path += [(a[0] + (b[0] - a[0]) * k / 5, a[1] + (b[1] - a[1]) * k / 5) for k in range(5)]
    ev("move", x=path[0][0], y=path[0][1])
    ev("button", x=path[0][0], y=path[0][1], button=0, action=1, mods=0)
    for p in path[1:]:
        frame += 1
        ev("move", x=p[0], y=p[1])
    frame += 1
    ev("button", x=path[-1][0], y=path[-1][1], button=0, action=0, mods=0)
    frame += wait


KEY_L, KEY_2, KEY_3 = 76, 50, 51
STEPS = [s for s in sys.argv[1:]] or ["orbit", "move", "turn", "colour"]
if "bench" in STEPS or "bench-paint" in STEPS:
    key(KEY_L)
    key(KEY_2)
    lasso([(420, 555), (850, 555), (850, 650), (420, 650)])  # the bottom: fixed
    key(KEY_3)
    lasso([(420, 165), (625, 165), (625, 235), (420, 235)])  # the ear tips: the handle
    frame += 30
if "bench" in STEPS:
    ev("idle")  # the replay waits here for the setup (the app's busy()), then drags
    frame += 10
    drag(LEFT, (527, 124), (527, 84), wait=10)  # the y arrow: ears up
    drag(LEFT, (615, 172), (675, 172), wait=10)  # the x arrow: and back
if "orbit" in STEPS:
    drag(RIGHT, (560, 420), (242, 440))  # yaw += 318 px * 0.008: face the armadillo's front-right
if "move" in STEPS:
    drag(LEFT, (395, 288), (335, 296), wait=10)  # the x arrow: the hand out to the side
    drag(LEFT, (417, 199), (417, 139), wait=10)  # the y arrow: and up
if "turn" in STEPS:
    # The z ring (the large circle), grabbed at its upper left and swept 40 degrees.
    cx, cy, r = 417, 225, 78
    start = (cx + r * math.cos(math.radians(150)), cy - r * math.sin(math.radians(150)))
    end = (cx + r * math.cos(math.radians(190)), cy - r * math.sin(math.radians(190)))
    drag(LEFT, start, end, wait=10)
if "colour" in STEPS:
    key(67)  # C: colour by edge-length distortion
frame += 5
json.dump({"format": "lapis-events", "version": 1, "width": W, "height": H, "events": events}, sys.stdout, indent=1)
print()
