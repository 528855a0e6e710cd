"""Grow a hairstyle from a bundled session and export it as .hair and OBJ.

    python3 examples/python/grow_hairstyle.py [OUT_STEM]
"""

import pathlib
import sys

import numpy as np

import lapis

SESSIONS = pathlib.Path(__file__).resolve().parents[2] / "assets" / "sessions"


def main(stem="ponytails", roots=2000):
    session = lapis.HairSession.load(str(SESSIONS / "ponytails.json"))  # replays the recorded strokes
    session.roots = int(roots)
    r = session.build()
    points, offsets = r["points"], r["offsets"]  # strand i: points[offsets[i]:offsets[i + 1]]
    lapis.write_hair(f"{stem}.hair", points, offsets)
    lapis.write_strands_obj(f"{stem}.obj", points, offsets)
    lengths = np.diff(offsets)
    print(f"{stem}.hair: {len(lengths)} strands, {lengths.mean():.1f} points each, "
          f"field solved in {r['timings_ms']['solve']:.0f} ms")


if __name__ == "__main__":
    main(*sys.argv[1:])
