"""Merge the bundled pair: a dome onto the open neck, in each mode, and write the results.

    python3 examples/python/merge_pair.py [OUT_DIR]
"""

import pathlib
import sys

import lapis

MERGE = pathlib.Path(__file__).resolve().parents[2] / "assets" / "merge"


def main(out_dir="."):
    target = lapis.read_mesh(str(MERGE / "neck.obj"))
    pairs = lapis.read_pairs(str(MERGE / "dome_on_neck.json"))  # one loop pair, one key
    for mode, source in (("independent", "dome.obj"), ("dependent", "dome_placed.obj"), ("transition", "dome.obj")):
        V, F, report = lapis.merge(*lapis.read_mesh(str(MERGE / source)), *target, pairs, mode=mode)
        out = pathlib.Path(out_dir) / f"dome_on_neck_{mode}.obj"
        lapis.write_mesh(str(out), V, F)
        print(f"{out}: {V.shape[0]} vertices, seam valid {report['seam']['valid']}, "
              f"{report['timings_ms']['total']:.1f} ms")


if __name__ == "__main__":
    main(*sys.argv[1:])
