#!/usr/bin/env python3
"""Writes assets/events/deform_demo.json, the event log `scripts/demo deform` replays on the
armadillo (assets/selections/armadillo_hand.*) at 1200x800: orbit to a front three-quarter
view, pull the right hand up and out with the gizmo's arrows, turn it with a ring, colour by
edge-length distortion. Pixel positions were read off screenshots of the app at each step.

  assets/events/make_deform_demo.py > assets/events/deform_demo.json
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
STEPS = [s for s in sys.argv[1:]] or ["orbit", "move", "turn", "colour"]
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
