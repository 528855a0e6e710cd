#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets into corpus/<target>/ (run by hand from this
directory's parent or anywhere; outputs are committed). Small meshes in every format the
readers take (PLY binary little / big endian and STL binary packed here byte by byte), the
repository's own sessions, selections and pairs files cut down so that one input stays
cheap, and command lines for the argument parser."""
import json
import os
import struct
import sys

here = os.path.dirname(os.path.abspath(__file__))
repo = os.path.normpath(os.path.join(here, "..", ".."))

# A tetrahedron and a cube of quads: closed, small, with and without polygons to fan.
TET_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
CUBE_Q = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def put(target, name, data):
    d = os.path.join(here, "corpus", target)
    os.makedirs(d, exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(d, name), mode) as f:
        f.write(data)


def obj(v, f, extra=""):
    return "".join("v %g %g %g\n" % p for p in v) + extra + "".join(
        "f " + " ".join(str(i + 1) for i in face) + "\n" for face in f)


def off(v, f, header="OFF", colors=False):
    c = " 255 0 0 255" if colors else ""
    return "%s\n%d %d 0\n" % (header, len(v), len(f)) + "".join("%g %g %g%s\n" % (p + (c,)) for p in v) + \
        "".join("%d %s\n" % (len(face), " ".join(map(str, face))) for face in f)


def ply_header(fmt, v, f, vtype="double", itype="int"):
    return ("ply\nformat %s 1.0\ncomment fuzz seed\nelement vertex %d\nproperty %s x\nproperty %s y\n"
            "property %s z\nelement face %d\nproperty list uchar %s vertex_indices\nend_header\n"
            % (fmt, len(v), vtype, vtype, vtype, len(f), itype)).encode()


def ply_binary(order, v, f, vtype="d", itype="i"):
    names = {"d": "double", "f": "float"}
    inames = {"i": "int", "I": "uint"}
    fmt = "binary_little_endian" if order == "<" else "binary_big_endian"
    body = b"".join(struct.pack(order + vtype * 3, *p) for p in v)
    body += b"".join(struct.pack(order + "B" + itype * len(face), len(face), *face) for face in f)
    return ply_header(fmt, v, f, names[vtype], inames[itype]) + body


def stl_binary(v, f):
    out = b"fuzz seed".ljust(80, b"\0") + struct.pack("<I", len(f))
    for face in f:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v[i]) for i in face) + b"\0\0"
    return out


def stl_ascii(v, f):
    s = "solid seed\n"
    for face in f:
        s += " facet normal 0 0 0\n  outer loop\n" + "".join("   vertex %g %g %g\n" % v[i] for i in face)
        s += "  endloop\n endfacet\n"
    return s + "endsolid seed\n"


def triangles(quads):
    return [t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def meshes():
    put("obj", "tet.obj", obj(TET_V, TET_F))
    put("obj", "cube_quads.obj", obj(CUBE_V, CUBE_Q, "vn 0 0 1\nvt 0.5 0.5\ng cube\nusemtl none\n"))
    put("obj", "negative_indices.obj", "o neg\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3/1/1 -2/1/1 -1/1/1\nl 1 2\n")
    put("obj", "dome.obj", open(os.path.join(repo, "assets/merge/dome.obj")).read())
    put("off", "tet.off", off(TET_V, TET_F))
    put("off", "cube_quads.off", off(CUBE_V, CUBE_Q))
    put("off", "tet_colors.coff", off(TET_V, TET_F, "COFF", colors=True))
    put("off", "comments.off", "# comment\nOFF # header\n3 1 3\n0 0 0\n1 0 0 # v\n0 1 0\n3 0 1 2\n")
    cube_t = triangles(CUBE_Q)
    put("ply", "tet_ascii.ply", ply_header("ascii", TET_V, TET_F).decode() +
        "".join("%g %g %g\n" % p for p in TET_V) + "".join("3 %d %d %d\n" % t for t in TET_F))
    put("ply", "tet_le.ply", ply_binary("<", TET_V, TET_F))
    put("ply", "tet_be.ply", ply_binary(">", TET_V, TET_F))
    put("ply", "cube_quads_le_float.ply", ply_binary("<", CUBE_V, CUBE_Q, "f", "I"))
    put("ply", "cube_be_float.ply", ply_binary(">", CUBE_V, cube_t, "f"))
    put("stl", "tet_ascii.stl", stl_ascii(TET_V, TET_F))
    put("stl", "tet_binary.stl", stl_binary(TET_V, TET_F))
    put("stl", "cube_binary.stl", stl_binary(CUBE_V, cube_t))


def small_settings(d, unknowns=1000, roots=16):
    d["settings"].update({"grid_unknowns": float(unknowns), "roots": roots, "max_length": 40.0})


def sessions():
    for name in ("parting", "smooth", "ponytails"):
        d = json.load(open(os.path.join(repo, "assets/sessions/%s.json" % name)))
        small_settings(d)
        strokes = d.pop("strokes")
        compact = lambda x: json.dumps(x, separators=(",", ":"))
        put("hair_session", name + "_primitives.json", compact(d))
        d["primitives"] = d["primitives"][:1]
        put("hair_session", name + "_one_primitive.json", compact(d))
        d["strokes"] = strokes[:3]
        d["settings"]["field_method"] = "multigrid"
        put("hair_session", name + "_strokes.json", compact(d))


def hair_file(strands, info=b"fuzz seed"):
    points = [p for s in strands for p in s]
    # "HAIR", hair and point counts, arrays (segments | points), default segments,
    # thickness, transparency, colour, 88 bytes of info: 128 bytes.
    head = b"HAIR" + struct.pack("<IIII", len(strands), len(points), 3, 0)
    head += struct.pack("<2f", 1.0, 0.0) + struct.pack("<3f", 1.0, 1.0, 1.0)
    head += info.ljust(88, b"\0")
    body = b"".join(struct.pack("<H", len(s) - 1) for s in strands)
    body += b"".join(struct.pack("<3f", *p) for p in points)
    return head + body


def hair():
    strands = [[(0, 0, 0), (0, 1, 0), (0, 2, 0.5)], [(1, 0, 0), (1, 1, 0)]]
    put("hair_file", "two_strands.hair", hair_file(strands))
    put("hair_file", "one_strand.hair", hair_file([[(0, 0, 0), (1, 1, 1), (2, 2, 2), (3, 3, 3)]]))


def selections():
    roi = open(os.path.join(repo, "assets/selections/armadillo_hand.roi.txt")).read().split()
    put("deform_roi", "armadillo_hand_head.roi.txt", " ".join(roi[:400]) + "\n")
    put("deform_roi", "small.json", json.dumps([int(i) for i in roi[:50]]))
    put("deform_roi", "lines.txt", "1 2 3\n4\t5\n")
    handles = open(os.path.join(repo, "assets/selections/armadillo_hand.handles.json")).read()
    put("deform_handles", "armadillo_hand.handles.json", handles)
    identity = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    put("deform_handles", "two_frames.json", json.dumps({
        "regions": [{"vertices": [0, 1, 2], "transforms": [identity, identity]}],
        "points": [{"vertex": 7, "translations": [[0, 0, 0], [0.1, 0.2, 0.3]]}]}))
    put("merge_pairs", "dome_on_neck.json", open(os.path.join(repo, "assets/merge/dome_on_neck.json")).read())
    put("merge_pairs", "two_loops.json", json.dumps(
        {"pairs": [{"keys": [{"source": 1, "target": 2}, {"source": 3, "target": 4}]}, {"keys": []}]}))
    put("merge_handles", "handles.json", json.dumps({"handles": [5, 6, 7]}))
    put("merge_handles", "empty.json", json.dumps({"handles": []}))


def command_lines():
    lines = [
        (0, ["--in", "a.obj", "--out", "b.ply", "--report", "r.json"]),
        (1, ["--session", "s.json", "--grid-unknowns", "5000", "--roots", "100", "--out-hair", "o.hair"]),
        (2, ["--mesh", "m.off", "--roi", "r.txt", "--handles", "h.json", "--scale-features", "--iterations", "3"]),
        (3, ["--source", "a.obj", "--target", "b.obj", "--pairs", "p.json", "--out", "o.obj",
             "--roi-width", "0.5", "--source-width", "-1", "--smooth", "10"]),
        (4, ["--session", "s.json", "--roots", "20", "--draw-segments", "1000"]),
        (5, ["--mesh", "m.off", "--subdivide", "2", "--export-on-exit", "--full-while-dragging"]),
        (6, ["--source", "a.obj", "--preset", "3"]),
        (3, ["--roi-width", "1e400"]),
        (1, ["--roots", "99999999999999999999"]),
    ]
    for k, (which, argv) in enumerate(lines):
        put("cli_args", "argv_%d" % k, bytes([which]) + b"\0".join(a.encode() for a in argv))


if __name__ == "__main__":
    meshes()
    sessions()
    hair()
    selections()
    command_lines()
    sys.exit(0)
