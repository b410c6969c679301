#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the input-format fixtures under tests/data/formats/ with writers independent of
libsection: laspy (LAS; LAZ through lazrs), pypcd4 (PCD), pye57 (E57, through its bindings
of libE57Format), Python's csv module and numpy (PTS, ';' and tab text). Run once by hand;
the files are committed and CI does not run this script.

    python3 -m venv /tmp/v && /tmp/v/bin/pip install laspy lazrs pypcd4 pye57
    /tmp/v/bin/python scripts/make_format_fixtures.py build/tools/bladegen [FORMAT...]

The points are a bladegen scan (turbine, seed 3, 1.2 mm spacing) rounded to 0.1 um and
written as blade.xyz; every other file holds the same points (to its format's precision).
With FORMATs (las laz pcd text e57) only those files are written, from the committed
blade.xyz.
"""
import csv
import re
import struct
import subprocess
import sys
from pathlib import Path

import laspy
import numpy as np

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
    from pypcd4 import Encoding, PointCloud

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


def quaternion(axis, degrees):
    """The unit quaternion (w, x, y, z) of a rotation by `degrees` about `axis`."""
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    half = np.radians(degrees) / 2
    return np.concatenate([[np.cos(half)], np.sin(half) * axis])


def rotation_matrix(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def e57_scan(e57, name, fields, pose):
    """Adds a scan to pye57's E57 `e57`: `fields` maps a point field's name to (its values,
    its prototype node); `pose` is (quaternion w x y z, translation) or None (no pose)."""
    from pye57 import libe57
    imf = e57.image_file
    scan = libe57.StructureNode(imf)
    scan.set("guid", libe57.StringNode(imf, "{%s}" % name))
    scan.set("name", libe57.StringNode(imf, name))
    if pose is not None:
        q, t = pose
        node, rot, tra = (libe57.StructureNode(imf) for _ in range(3))
        for k, v in zip("wxyz", q):
            rot.set(k, libe57.FloatNode(imf, float(v)))
        for k, v in zip("xyz", t):
            tra.set(k, libe57.FloatNode(imf, float(v)))
        node.set("rotation", rot)
        node.set("translation", tra)
        scan.set("pose", node)
    prototype = libe57.StructureNode(imf)
    for field, (_, node) in fields.items():
        prototype.set(field, node)
    points = libe57.CompressedVectorNode(imf, prototype, libe57.VectorNode(imf, True))
    scan.set("points", points)
    e57.data3d.append(scan)
    buffers = libe57.VectorSourceDestBuffer()
    arrays = {f: np.ascontiguousarray(v) for f, (v, _) in fields.items()}
    for field, values in arrays.items():
        buffers.append(libe57.SourceDestBuffer(imf, field, values, len(values), True, True))
    writer = points.writer(buffers)
    writer.write(len(next(iter(arrays.values()))))
    writer.close()


def write_e57(pts):
    """blade_scaled.e57: one scan, no pose, ScaledInteger coordinates on the 0.1 um grid (the
    points exactly). blade_metres.e57: the points in metres, E2807's unit (the other files
    hold millimetres, as blade.xyz). blade_scans.e57: the points in four scans, each in its own frame with a
    pose (rotation and translation) taking it to the file's: double coordinates with invalid
    points (cartesianInvalidState 2) among them, single floats, ScaledInteger (scale 1e-6
    mm, an offset), and spherical coordinates (range, azimuth, elevation)."""
    import pye57
    from pye57 import libe57

    def scaled(imf, values, scale, offset):
        raw = np.round((values - offset) / scale)
        return libe57.ScaledIntegerNode(imf, int(raw.min()), int(raw.min()), int(raw.max()), scale, offset)

    path = OUT / "blade_scaled.e57"
    e57 = pye57.E57(str(path), mode="w")
    imf = e57.image_file
    e57_scan(e57, "scaled", {f"cartesian{a}": (pts[:, k], scaled(imf, pts[:, k], 1e-4, 0.0))
                             for k, a in enumerate("XYZ")}, None)
    e57.close()

    # E2807's unit, metres: one scan of doubles, pose a translation.
    path = OUT / "blade_metres.e57"
    e57 = pye57.E57(str(path), mode="w")
    imf = e57.image_file
    m = pts / 1000 - [0.001, 0.002, 0.003]
    e57_scan(e57, "metres", {f"cartesian{c}": (m[:, k].copy(), libe57.FloatNode(imf, 0.0))
                             for k, c in enumerate("XYZ")}, ((1, 0, 0, 0), (0.001, 0.002, 0.003)))
    e57.close()

    path = OUT / "blade_scans.e57"
    e57 = pye57.E57(str(path), mode="w")
    imf = e57.image_file
    parts = np.array_split(pts, 4)
    poses = [(quaternion([0, 0, 1], 30), [100, -20, 5]), (quaternion([1, 1, 0], -75), [-3, 4, 25]),
             (quaternion([0.2, -1, 0.5], 140), [0.5, 0.25, -12]), (quaternion([1, 0, 0], 90), [0, 0, 300])]
    local = [(p - t) @ rotation_matrix(q) for p, (q, t) in zip(parts, poses)]  # R^T (p - t), row by row
    a = np.vstack([local[0][:700], np.zeros((5, 3)), local[0][700:]])  # 5 invalid points
    state = np.zeros(len(a), np.int8)
    state[700:705] = 2
    d = {f"cartesian{c}": (a[:, k], libe57.FloatNode(imf, 0.0, libe57.E57_DOUBLE)) for k, c in enumerate("XYZ")}
    d["cartesianInvalidState"] = (state, libe57.IntegerNode(imf, 0, 0, 2))
    e57_scan(e57, "double", d, poses[0])
    b = local[1]
    e57_scan(e57, "single", {f"cartesian{c}": (b[:, k].astype(np.float32), libe57.FloatNode(
        imf, 0.0, libe57.E57_SINGLE)) for k, c in enumerate("XYZ")}, poses[1])
    c = local[2]
    e57_scan(e57, "scaled", {f"cartesian{x}": (c[:, k], scaled(imf, c[:, k], 1e-6, -50.0))
                             for k, x in enumerate("XYZ")}, poses[2])
    s = local[3]
    r = np.linalg.norm(s, axis=1)
    sph = np.column_stack([r, np.arctan2(s[:, 1], s[:, 0]), np.arcsin(s[:, 2] / r)])
    e57_scan(e57, "spherical", {n: (sph[:, k], libe57.FloatNode(imf, 0.0, libe57.E57_DOUBLE)) for k, n in
                                enumerate(["sphericalRange", "sphericalAzimuth", "sphericalElevation"])},
             poses[3])
    e57.close()


def crc32c(data):
    crc = 0xFFFFFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ (0x82F63B78 if crc & 1 else 0)
    return crc ^ 0xFFFFFFFF


def e57_edit(src, dst, edit_xml=None, edit_logical=None):
    """Copies the E57 file `src` to `dst` with its XML section changed by `edit_xml` (text in,
    text out; the XML is the file's last section, as libE57Format writes it) or its logical
    bytes by `edit_logical` (bytearray, edited in place), the page checksums made anew."""
    raw = Path(src).read_bytes()
    logical = bytearray(b"".join(raw[i:i + 1020] for i in range(0, len(raw), 1024)))
    xml_at, xml_len = struct.unpack_from("<QQ", logical, 24)
    xml_log = xml_at // 1024 * 1020 + xml_at % 1024
    if edit_xml:
        xml = edit_xml(logical[xml_log:xml_log + xml_len].decode()).encode()
        logical = logical[:xml_log] + xml
        struct.pack_into("<Q", logical, 32, len(xml))
    if edit_logical:
        edit_logical(logical)
    logical += bytes(-len(logical) % 1020)
    struct.pack_into("<Q", logical, 16, len(logical) // 1020 * 1024)
    out = bytearray()
    for i in range(0, len(logical), 1020):
        page = logical[i:i + 1020]
        out += page + crc32c(page).to_bytes(4, "big")
    Path(dst).write_bytes(bytes(out))


def write_bad_e57(pts):
    """Small E57 files a reader must refuse: a codec other than bitPackCodec (codec.e57), no
    z coordinate (no_z.e57), a data packet whose bytestream count is not its prototype's
    (packet.e57). Each is pye57's file of 10 points edited, its checksums made anew."""
    import pye57
    from pye57 import libe57
    tiny = OUT / "tiny.e57"
    e57 = pye57.E57(str(tiny), mode="w")
    e57_scan(e57, "tiny", {f"cartesian{c}": (pts[:10, k].copy(), libe57.FloatNode(e57.image_file, 0.0))
                           for k, c in enumerate("XYZ")}, None)
    e57.close()
    codec = ('<codecs type="Vector" allowHeterogeneousChildren="1"><vectorChild type="Structure">'
             '<inputs type="Vector" allowHeterogeneousChildren="1"/><zLibCodec type="Structure"/>'
             '</vectorChild></codecs>')
    e57_edit(tiny, OUT / "codec.e57",
             edit_xml=lambda x: re.sub(r'<codecs type="Vector" allowHeterogeneousChildren="1">\s*</codecs>',
                                       codec, x))
    e57_edit(tiny, OUT / "no_z.e57", edit_xml=lambda x: x.replace("cartesianZ", "cartesianW"))

    def packet(logical):
        xml_at = struct.unpack_from("<Q", logical, 24)[0]
        xml = logical[xml_at // 1024 * 1020 + xml_at % 1024:].decode(errors="replace")
        offset = int(re.search(r'fileOffset="(\d+)"', xml).group(1))
        data = struct.unpack_from("<Q", logical, offset // 1024 * 1020 + offset % 1024 + 16)[0]
        logical[data // 1024 * 1020 + data % 1024 + 4] = 7  # 7 bytestreams, not 3
    e57_edit(tiny, OUT / "packet.e57", edit_logical=packet)
    tiny.unlink()


def write_laz(pts):
    """The blade's points compressed by lazrs (LASzip's format). blade_12_f3.laz: point format
    3 (LAS 1.2) with 4 extra bytes a record, in chunks of 1000 points (lazrs's VLR edited: its
    default is 50000), intensity, returns, classification, scan angle, GPS time (steps and
    jumps) and colour varying, so that every item's decoder and each chunk's restart is
    exercised. blade_14_f6.laz: point format 6 (LAS 1.4, LASzip's layered compression)."""
    import lazrs
    rng = np.random.default_rng(24)
    n = len(pts)
    new_vlr = lazrs.LazVlr.new_for_compression

    def chunks_of_1000(point_format, extra_bytes):
        data = bytearray(new_vlr(point_format, extra_bytes).record_data())
        struct.pack_into("<I", data, 12, 1000)
        return lazrs.LazVlr(bytes(data))

    header = laspy.LasHeader(version="1.2", point_format=3)
    header.scales = np.array([1e-4, 1e-4, 1e-4])
    header.offsets = np.array([0.0, 0.0, 0.0])
    header.add_extra_dim(laspy.ExtraBytesParams(name="deviation", type=np.float32))
    las = laspy.LasData(header)
    las.x, las.y, las.z = pts[:, 0], pts[:, 1], pts[:, 2]
    las.intensity = (rng.random(n) * 65535).astype(np.uint16) * (rng.random(n) < 0.5)
    las.return_number = rng.integers(1, 4, n)
    las.number_of_returns = np.maximum(las.return_number, rng.integers(1, 6, n))
    las.classification = rng.integers(0, 10, n) * (rng.random(n) < 0.3)
    las.scan_angle_rank = rng.integers(-90, 90, n) * (rng.random(n) < 0.2)
    las.scan_direction_flag = rng.random(n) < 0.5
    las.gps_time = 4e5 + np.cumsum(rng.choice([0, 1e-5, 2e-5, 1.0, 1e6, -3e-5], n, p=[.3, .3, .2, .1, .05, .05]))
    las.red = rng.integers(0, 65535, n) * (rng.random(n) < 0.3)
    las.green = las.red // 2
    las.blue = rng.integers(0, 65535, n)
    las.deviation = rng.normal(0, 1, n).astype(np.float32)
    lazrs.LazVlr.new_for_compression = chunks_of_1000
    try:
        las.write(str(OUT / "blade_12_f3.laz"), laz_backend=laspy.LazBackend.Lazrs)
    finally:
        lazrs.LazVlr.new_for_compression = new_vlr
    header = laspy.LasHeader(version="1.4", point_format=6)
    header.scales = np.array([1e-4, 1e-4, 1e-4])
    header.offsets = np.array([0.0, 0.0, 0.0])
    las = laspy.LasData(header)
    las.x, las.y, las.z = pts[:, 0], pts[:, 1], pts[:, 2]
    las.intensity = np.arange(n) % 65536
    las.write(str(OUT / "blade_14_f6.laz"), laz_backend=laspy.LazBackend.Lazrs)


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    only = set(sys.argv[2:])
    if only:
        pts = np.loadtxt(OUT / "blade.xyz")
    else:
        pts = blade(sys.argv[1] if len(sys.argv) > 1 else "build/tools/bladegen")
    if not only or "las" in only:
        write_las(pts, OUT / "blade_12_f3.las", "1.2", 3, [0, 0, 0], False)
        write_las(pts, OUT / "blade_14_f6.las", "1.4", 6, [10, -5, 30], True)
    if not only or "laz" in only:
        write_laz(pts)
    if not only or "pcd" in only:
        write_pcd(pts)
    if not only or "text" in only:
        write_text(pts)
    if not only or "e57" in only:
        write_e57(pts)
        write_bad_e57(pts)
    for p in sorted(OUT.iterdir()):
        print(f"{p.name}: {p.stat().st_size} bytes")


if __name__ == "__main__":
    main()
