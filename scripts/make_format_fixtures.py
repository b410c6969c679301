#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the input-format fixtures under tests/data/formats/ with writers independent of
libsection: laspy (LAS), pypcd4 (PCD), Python's csv module and numpy (PTS, ';' and tab
text). Run once by hand; the files are committed and CI does not run this script.

    python3 -m venv /tmp/v && /tmp/v/bin/pip install laspy pypcd4
    /tmp/v/bin/python scripts/make_format_fixtures.py build/tools/bladegen

The points are a bladegen scan (turbine, seed 3, 1.2 mm spacing) rounded to 0.1 um and
written as blade.xyz; every other file holds the same points (to its format's precision).
"""
import csv
import subprocess
import sys
from pathlib import Path

import laspy
import numpy as np
from pypcd4 import Encoding, PointCloud

OUT = Path(__file__).resolve().parent.parent / "tests" / "data" / "formats"


def blade(bladegen):
    raw = OUT / "raw.xyz"
    subprocess.run([bladegen, "--kind", "turbine", "--points", "--spacing", "1.2", "--seed", "3",
                    "-o", str(raw)], check=True)
    pts = np.round(np.loadtxt(raw), 4)
    raw.unlink()
    np.savetxt(OUT / "blade.xyz", pts, fmt="%.4f")
    return pts


def write_las(pts, path, version, point_format, offset, extra):
    header = laspy.LasHeader(version=version, point_format=point_format)
    header.scales = np.array([1e-4, 1e-4, 1e-4])
    header.offsets = np.array(offset)
    if extra:  # extra bytes: the record is longer than the format's own fields
        header.add_extra_dim(laspy.ExtraBytesParams(name="deviation", type=np.float32))
    las = laspy.LasData(header)
    las.x, las.y, las.z = pts[:, 0], pts[:, 1], pts[:, 2]
    if extra:
        las.deviation = np.linspace(-1, 1, len(pts)).astype(np.float32)
    las.write(str(path))


def write_pcd(pts):
    n = len(pts)
    rgb = PointCloud.encode_rgb(np.tile(np.array([[200, 100, 50]], np.uint8), (n, 1)))
    cols = (pts[:, 0], pts[:, 1], pts[:, 2], rgb)
    ascii_cloud = PointCloud.from_points(np.column_stack(cols), ("x", "y", "z", "rgb"),
                                         (np.float64, np.float64, np.float64, np.float32))
    ascii_cloud.save(OUT / "blade_ascii.pcd", encoding=Encoding.ASCII)
    # Binary float32 with intensity first and NaN points (an organised scan's holes) mixed in.
    f = pts.astype(np.float32)
    nan = np.full((5, 3), np.nan, np.float32)
    xyz = np.vstack([f[:1000], nan, f[1000:]])
    inten = np.arange(len(xyz), dtype=np.float32)
    binary = PointCloud.from_points(np.column_stack([inten, xyz]), ("intensity", "x", "y", "z"),
                                    (np.float32, np.float32, np.float32, np.float32))
    binary.save(OUT / "blade_binary.pcd", encoding=Encoding.BINARY)
    small = PointCloud.from_xyz_points(f[:100])
    small.save(OUT / "compressed.pcd", encoding=Encoding.BINARY_COMPRESSED)


def write_text(pts):
    n = len(pts)
    half = n // 2
    with open(OUT / "blade.pts", "w") as out:  # Leica PTS: two scans, each after its count
        for part in (pts[:half], pts[half:]):
            out.write(f"{len(part)}\n")
            extra = np.tile([[-1200, 128, 64, 32]], (len(part), 1))
            np.savetxt(out, np.column_stack([part, extra]), fmt=["%.4f"] * 3 + ["%d"] * 4)
    comma = [[f"{v:.4f}".replace(".", ",") for v in p] for p in pts]
    with open(OUT / "blade_semicolon.csv", "w", newline="") as out:
        w = csv.writer(out, delimiter=";")
        w.writerow(["X", "Y", "Z"])
        w.writerows(comma)
    with open(OUT / "blade_semicolon.txt", "w", newline="") as out:
        csv.writer(out, delimiter=";").writerows(comma)
    with open(OUT / "blade_tab.txt", "w", newline="") as out:
        csv.writer(out, delimiter="\t").writerows([[f"{v:.4f}" for v in p] for p in pts])


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    pts = blade(sys.argv[1] if len(sys.argv) > 1 else "build/tools/bladegen")
    write_las(pts, OUT / "blade_12_f3.las", "1.2", 3, [0, 0, 0], False)
    write_las(pts, OUT / "blade_14_f6.las", "1.4", 6, [10, -5, 30], True)
    write_pcd(pts)
    write_text(pts)
    for p in sorted(OUT.iterdir()):
        print(f"{p.name}: {p.stat().st_size} bytes")


if __name__ == "__main__":
    main()
