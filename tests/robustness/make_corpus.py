#!/usr/bin/env python3
"""Writes the hostile-input corpus of tests/robustness/ (small files, checked in).

Run from anywhere: python3 tests/robustness/make_corpus.py [OUTDIR]. Every file is a case
of tests/tools/test_robustness.sh; the big ones (a line of a million characters) are made
by the test itself. Deterministic: no randomness, fixed geometry.
"""
import math
import os
import struct
import sys

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))


def put(name, data):
    if isinstance(data, str):
        data = data.encode("utf-8")
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)


def blade_points(z, n=160):
    """An elliptic profile (semi-axes 20 and 3, mm) at height z: a crude blade section."""
    return [(20 * math.cos(2 * math.pi * i / n), 3 * math.sin(2 * math.pi * i / n), z)
            for i in range(n)]


def blade_cloud(levels=(0, 0.05, 0.1, 4.95, 5, 5.05, 9.9, 9.95, 10)):
    pts = []
    for z in levels:
        pts += blade_points(z)
    return pts


def xyz_text(pts):
    return "".join("%.9g %.9g %.9g\n" % p for p in pts)


def ply_binary(pts, count=None, fmt="<", typ="f"):
    hdr = ("ply\nformat binary_%s_endian 1.0\nelement vertex %d\n"
           "property %s x\nproperty %s y\nproperty %s z\nend_header\n" %
           ("little" if fmt == "<" else "big", len(pts) if count is None else count,
            *(["float" if typ == "f" else "double"] * 3)))
    body = b"".join(struct.pack(fmt + typ * 3, *p) for p in pts)
    return hdr.encode() + body


def ply_ascii(pts, count=None):
    hdr = ("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
           "property float z\nend_header\n" % (len(pts) if count is None else count))
    return hdr + xyz_text(pts)


def stl_binary(tris, count=None):
    data = b"libsection robustness corpus".ljust(80, b" ")
    data += struct.pack("<I", len(tris) if count is None else count)
    for t in tris:
        data += struct.pack("<3f", 0, 0, 1)
        for v in t:
            data += struct.pack("<3f", *v)
        data += b"\0\0"
    return data


def stream(tables, header="# libsection-stream 1\n# units mm\n", fmt="%.12g"):
    out = header
    for name, cols, rows in tables:
        out += "# table %s\n%s\n" % (name, ",".join(cols))
        out += "".join(",".join(fmt % v for v in r) + "\n" for r in rows)
    return out


POINT_COLS = ["section", "loop", "index", "u", "v", "nu", "nv"]


def points_rows(section, pts):
    rows = []
    n = len(pts)
    for i, (u, v) in enumerate(pts):
        # Outward normal from the neighbours' chord turned clockwise.
        (a, b), (c, d) = pts[(i - 1) % n], pts[(i + 1) % n]
        tx, ty = c - a, d - b
        ln = math.hypot(tx, ty) or 1
        rows.append((section, 0, i, u, v, ty / ln, -tx / ln))
    return rows


def ellipse2d(n=200, a=20.0, b=3.0, cx=0.0):
    return [(cx + a * math.cos(2 * math.pi * i / n), b * math.sin(2 * math.pi * i / n))
            for i in range(n)]


def figure_eight(n=200, a=10.0):
    # Lemniscate of Gerono: crosses itself at the origin.
    return [(a * math.sin(2 * math.pi * i / n), a * math.sin(2 * math.pi * i / n) *
             math.cos(2 * math.pi * i / n)) for i in range(n)]


SPLINE_COLS = ["section", "loop", "degree", "closed", "control_points", "rms", "max", "p95", "iterations",
               "spacing", "max_gap", "gap_start", "gap_end", "layers", "layers_length"]
FRAME_COLS = ["section", "origin_x", "origin_y", "origin_z", "u_x", "u_y", "u_z", "v_x", "v_y", "v_z",
              "n_x", "n_y", "n_z"]


def spline_stream(sections):
    # sections: (id, knots, control points) of closed cubic splines, as fitspline writes them.
    return stream([
        ("frames", FRAME_COLS, [(s, 0, 0, 10 * s, 1, 0, 0, 0, 1, 0, 0, 0, 1) for s, _, _ in sections]),
        ("splines", SPLINE_COLS, [(s, 0, 3, 1, len(c), 0.005, 0.02, 0.01, 12, 0.03, 0.3, 0, 0, 0, 0)
                                  for s, _, c in sections]),
        ("spline_knots", ["section", "loop", "index", "knot"],
         [(s, 0, i, k) for s, ks, _ in sections for i, k in enumerate(ks)]),
        ("spline_ctrl", ["section", "loop", "index", "u", "v"],
         [(s, 0, i, u, v) for s, _, c in sections for i, (u, v) in enumerate(c)])], fmt="%.17g")


def spline_streams():
    # Spline tables camber, compare and tocad crashed or hung on (mutation testing).
    n = 12
    good = [(20 * math.cos(2 * math.pi * i / n), 3 * math.sin(2 * math.pi * i / n)) for i in range(n)]
    knots = list(range(n + 1))
    line = [(0, min(i, n - i)) for i in range(n)]
    put("spline_collinear_stream.csv", spline_stream([(0, knots, good), (1, knots, line), (2, knots, good)]))
    put("spline_equal_knots_stream.csv", spline_stream([(0, knots, good), (1, [0] * (n + 1), good)]))
    put("spline_decreasing_knots_stream.csv", spline_stream([(0, knots, good), (1, knots[:-1] + [0], good)]))
    put("spline_huge_stream.csv", spline_stream([(0, knots, [(u * 1e9, v * 1e9) for u, v in good])]))
    put("spline_far_stream.csv", spline_stream([(0, knots, [(u - 9e14, v) for u, v in good])]))


def main():
    os.makedirs(OUT, exist_ok=True)
    good = blade_cloud()
    good_xyz = xyz_text(good)

    # ---- point clouds
    put("good.xyz", good_xyz)
    put("empty.xyz", "")
    put("empty.ply", "")
    put("only_comments.xyz", "# a scan with no points\n# at all\n")
    put("bom.xyz", "\ufeff" + good_xyz)  # a UTF-8 byte-order mark is skipped
    put("utf16.xyz", ("\ufeff" + "1 2 3\n4 5 6\n").encode("utf-16-le"))
    put("utf16be.xyz", ("\ufeff" + "1 2 3\n4 5 6\n").encode("utf-16-be"))
    put("nan.xyz", good_xyz + "1 nan 3\n")
    put("inf.xyz", "1 2 3\n-inf 2 3\n")
    put("overflow.xyz", "1 2 3\n1e400 2 3\n")
    put("text_in_number.xyz", "1 2 3\n4 5x 6\n")
    put("missing_column.xyz", "1 2 3\n4 5\n")
    put("truncated_line.xyz", good_xyz + "7 8")
    put("missing_z.csv", "x,y,w\n1,2,3\n")
    put("text_in_number.csv", "x,y,z\n1,2,3\n1,two,3\n")
    put("empty_header.csv", "x,y,z\n")
    put("line.xyz", "".join("%g 0 0\n" % (i * 0.1) for i in range(500)))  # collinear
    put("one_point.xyz", "1 2 3\n" * 1000)  # one point repeated
    put("three_points.xyz", "0 0 0\n1 0 0\n0 1 0\n")
    put("giant.xyz", "".join("%.17g %.17g %.17g\n" % (1e300 * x, 1e300 * y, z)
                             for x, y, z in good))
    put("binary_in_text.xyz", b"1 2 3\n\x00\x01\x02\n")

    # ---- PLY
    put("good.ply", ply_binary(good))
    put("truncated_binary.ply", ply_binary(good)[:-100])
    put("truncated_ascii.ply", ply_ascii(good)[:-300])
    put("truncated_header.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n")
    put("billions.ply", ply_binary(good[:10], count=4_000_000_000))
    put("too_many.ply", ply_binary(good[:10], count=11))  # one more than it holds
    put("over_limit.ply", ply_binary(good[:10], count=18_000_000_000_000_000_000))
    put("nan_binary.ply", ply_binary(good[:5] + [(float("nan"), 0, 0)]))
    put("no_xyz.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float a\nend_header\n1\n")
    put("bad_format.ply", b"ply\nformat utf16 1.0\nelement vertex 1\nend_header\n")
    # A PLY mesh whose header claims four billion vertices and faces (read through OpenMesh).
    put("billions_mesh.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
        b"property float x\nproperty float y\nproperty float z\nelement face 4000000000\n"
        b"property list uchar int vertex_indices\nend_header\n" + b"\0" * 64)

    # ---- meshes
    tri = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((1, 0, 0), (1, 1, 0), (0, 1, 0))]
    put("empty.stl", "")
    put("truncated.stl", stl_binary(tri, count=1000))
    put("billions.stl", stl_binary(tri, count=0xFFFFFFFF))
    put("header_only.stl", stl_binary([], count=0)[:84])
    put("short.stl", b"solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0")
    put("nan.stl", stl_binary([((float("nan"), 0, 0), (1, 0, 0), (0, 1, 0))] + tri))
    put("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n")
    put("no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    put("text.obj", "v 0 zero 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    put("billions.off", "OFF\n4000000000 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    put("bad_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    put("truncated.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n")
    # Garbled OFF bodies behind a valid header (OpenMesh's OFF reader looped on such a body:
    # crash-off-body-hang.off; mesh.cpp now reads ascii OFF itself and names the line).
    off_head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"
    put("off_negative_count.off", off_head + "-3 0 1 2\n")
    put("off_short_face.off", off_head + "4 0 1 2\n")
    put("off_text_coordinate.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n")
    put("off_truncated_faces.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    put("off_binary.off", b"OFF BINARY\n" + struct.pack(">3i", 3, 1, 0) +
        struct.pack(">9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack(">5i", 3, 0, 1, 2, 0))
    # Garbled ascii STL (OpenMesh read 'vertex 1 zero 0' as a vertex; mesh.cpp reads STL itself).
    facet = " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex %s\n   vertex 0 1 0\n  endloop\n endfacet\n"
    put("stl_text_coordinate.stl", "solid x\n" + facet % "1 zero 0" + "endsolid x\n")
    put("stl_missing_coordinate.stl", "solid x\n" + facet % "1 0" + "endsolid x\n")
    put("stl_no_endsolid.stl", "solid x\n" + facet % "1 0 0")
    put("stl_two_vertices.stl", "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
        "   vertex 1 0 0\n  endloop\n endfacet\nendsolid x\n")
    # A good ascii OFF in the forms other writers use: comments, the counts on the keyword's
    # line, vertex colours (COFF), a quad and a face colour.
    put("good.off", "# a unit square and a triangle above it\nCOFF 5 2 0\n0 0 0 255 0 0 255\n"
        "1 0 0 255 0 0 255\n1 1 0 255 0 0 255\n0 1 0 255 0 0 255  # last corner\n"
        "0.5 0.5 1 0 0 255 255\n\n4 0 1 2 3 0.5 0.5 0.5\n3 0 1 4\n")

    # A good ascii PLY mesh (a seed for fuzz_ply's read_mesh path).
    put("good_mesh.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")

    # ---- pipe streams (smooth, fitspline and camber read them)
    sec0 = points_rows(0, ellipse2d())
    sec1 = points_rows(1, ellipse2d(a=18))
    good_stream = stream([("points", POINT_COLS, sec0 + sec1)])
    put("good_stream.csv", good_stream)
    put("empty_stream.csv", "")
    put("version2_stream.csv", good_stream.replace("# libsection-stream 1", "# libsection-stream 2"))
    put("no_version_stream.csv", good_stream.split("\n", 1)[1])
    put("missing_column_stream.csv", stream([("points", ["section", "loop", "index", "u"],
                                              [r[:4] for r in sec0])]))
    lines = good_stream.splitlines(True)
    put("text_in_number_stream.csv", "".join(lines[:10] + ["0,0,7,1.5,abc,0,1\n"] + lines[11:]))
    put("truncated_stream.csv", good_stream[:-25])
    put("nan_stream.csv", "".join(lines[:10] + ["0,0,7,nan,1,0,1\n"] + lines[11:]))
    put("huge_id_stream.csv", "".join(lines[:10] + ["1e12,0,7,1,1,0,1\n"] + lines[11:]))
    put("fraction_id_stream.csv", "".join(lines[:10] + ["0,0.5,7,1,1,0,1\n"] + lines[11:]))
    put("bom_stream.csv", "\ufeff" + good_stream)
    put("utf16_stream.csv", ("\ufeff" + good_stream).encode("utf-16-le"))
    put("no_header_stream.csv", "# libsection-stream 1\n# table points\n")
    put("row_outside_table_stream.csv", "# libsection-stream 1\n1,2,3\n")
    put("giant_stream.csv", stream([("points", POINT_COLS,
                                     [(s, l, i, u * 1e300, v * 1e300, nu, nv)
                                      for s, l, i, u, v, nu, nv in sec0])]))
    # One bad section between good ones: the bad one fails alone.
    put("figure_eight_stream.csv", stream([("points", POINT_COLS, sec0 +
                                            points_rows(1, figure_eight()) +
                                            points_rows(2, ellipse2d(a=16)))]))
    put("three_points_stream.csv", stream([("points", POINT_COLS, sec0 +
                                            points_rows(1, [(0, 0), (1, 0), (0, 1)]) +
                                            points_rows(2, ellipse2d(a=16)))]))
    put("repeated_point_stream.csv", stream([("points", POINT_COLS, sec0 +
                                              points_rows(1, [(1, 1)] * 50) +
                                              points_rows(2, ellipse2d(a=16)))]))
    put("collinear_stream.csv", stream([("points", POINT_COLS, sec0 +
                                         points_rows(1, [(i * 0.1, 0) for i in range(100)]) +
                                         points_rows(2, ellipse2d(a=16)))]))

    spline_streams()

    # ---- 2D profiles (camber reads them)
    put("good_profile.dat", "ellipse\n" + "".join("%.12g %.12g\n" % p for p in ellipse2d()))
    put("empty_profile.dat", "")
    put("text_profile.dat", "title\n1 2\n3 four\n")
    put("nan_profile.dat", "1 2\nnan 3\n")

    # ---- planes for slice --planes
    put("planes_missing_column.csv", "origin_x,origin_y,origin_z,normal_x,normal_y\n0,0,5,0,0\n")
    put("planes_zero_normal.csv",
        "origin_x,origin_y,origin_z,normal_x,normal_y,normal_z\n0,0,5,0,0,0\n")
    put("planes_good.csv", "origin_x,origin_y,origin_z,normal_x,normal_y,normal_z\n0,0,5,0,0,1\n0,0,10,0,0.1,1\n")

    # ---- a stream split into parts (a seed of fuzz_parts): section 1 failed at slice
    parts = ["# libsection-stream 1", "# units mm", "# history slice --at 0,5 blade.ply"]
    for s in range(2):
        parts += ["# part %d" % s] + (["# issue section=1 loop=-1 stage=slice message=no points in the slab"]
                                      if s == 1 else [])
        parts += ["# table frames", "section,origin_x,origin_y,origin_z,u_x,u_y,u_z,v_x,v_y,v_z,n_x,n_y,n_z",
                  "%d,0,0,%d,1,0,0,0,1,0,0,0,1" % (s, 5 * s), "# table points", "section,loop,index,u,v,nu,nv,offset"]
        for i in range(12 if s == 0 else 0):
            t = 2 * math.pi * i / 12
            parts.append("0,0,%d,%.6g,%.6g,%.6g,%.6g,0" % (i, 20 * math.cos(t), 3 * math.sin(t), math.cos(t), math.sin(t)))
    put("parts_stream.csv", "\n".join(parts + ["# end"]) + "\n")


if __name__ == "__main__":
    main()
