#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs the camber tool on the 21 sections of the T-Blade3 compressor rotor Case7-28-8
(../shared/data/real/tblade3-case7-28-8, not part of the repository) and compares our
camber lines and edge points with the generator's exact mean lines.

First, the sections are cut from the 3D blade on their own surfaces of revolution (slice
--axis 0,0,0,1,0,0 --streamline: the 21 streamlines of 3dbgbinput.2.dat, scaled by its
152.4 mm and densified by a cubic spline in chord length, as T-Blade3 builds them), unrolled
conformally as T-Blade3 designs them, measured, and the camber lines mapped back to 3D
(the stream's x, y, z) and compared with the exact 3D mean lines; the edge points against
the loop's points 121 (LE) and 1 (TE). Then, as before, each section is projected onto its
least-squares plane (or unwrapped), and the exact mean line with it. The projection distorts the hub
sections most (0.9 mm out of plane at the hub, 0.3-0.8 mm elsewhere); unwrapping
(x, r_mean * theta) instead was worse at the hub (3x the camber error on section 0). The
tip section's projection crosses itself (camber refuses it, rightly): it is unwrapped.

Usage: scripts/validate_tblade3.py [--camber BIN] [--data DIR] [--surfaces-only] [-- extra camber options]
Prints per section: distance of the edge points (ours against the loop's points 121 = LE
and 1 = TE), RMS and max distance of our camber points to the exact mean line, and our
edge radii; run once as is (the LE chosen by thickness) and once with the LE direction
given (upstream, -x).
"""
import argparse, csv, os, subprocess, sys, tempfile

import numpy as np

from stream_tables import table
from surface_pipe import surface_pipe

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--camber", default=os.path.join(here, "..", "build", "tools", "camber"))
ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "real", "tblade3-case7-28-8"))
ap.add_argument("--surfaces-only", action="store_true", help="only the cut on the surfaces of revolution")
ap.add_argument("extra", nargs="*")
args = ap.parse_args()
blade_file = os.path.join(args.data, "blade3d.Case7-28-8.dat")
if not os.access(args.camber, os.X_OK) or not os.path.exists(blade_file):
    sys.exit(f"validate_tblade3: need {args.camber} and {blade_file}")

data = np.loadtxt(blade_file, skiprows=1)
per_section = 241


def distance_to_polyline(q, p):
    a, b = p[:-1], p[1:]
    ab = b - a
    t = np.clip(((q - a) * ab).sum(1) / (ab * ab).sum(1), 0, 1)
    return np.min(np.linalg.norm(a + ab * t[:, None] - q, axis=1))


def run(options, tmp, le_direction):
    print(f"camber {' '.join(options) or '(defaults)'}{', LE direction upstream' if le_direction else ', LE by thickness'}")
    print(f"{'sec':>3} {'off mm':>7} {'LE pt um':>9} {'TE pt um':>9} {'camber rms':>11} {'max um':>7}"
          f" {'LE r':>7} {'TE r':>7}  {'map':6s} orientation")
    for s in range(data.shape[0] // per_section):
        sec = data[s * per_section:(s + 1) * per_section]
        mean3 = np.loadtxt(os.path.join(args.data, f"meanline.sec{s + 1}.Case7-28-8.dat"))
        centre = sec.mean(0)
        e1, e2, normal = np.linalg.svd(sec - centre)[2]
        off = np.abs((sec - centre) @ normal).max()
        out = os.path.join(tmp, "c.txt")
        profile = os.path.join(tmp, f"p{s}.txt")
        for mapping in ("plane", "unwrap"):
            if mapping == "plane":
                to2d = lambda q: np.c_[(q - centre) @ e1, (q - centre) @ e2]
                upstream = (-e1[0], -e2[0])  # -x of the blade's frame, in the section's plane
            else:
                r_mean = np.hypot(sec[:, 1], sec[:, 2]).mean()
                to2d = lambda q: np.c_[q[:, 0], r_mean * np.arctan2(q[:, 1], q[:, 2])]
                upstream = (-1.0, 0.0)
            pts = to2d(sec)
            if np.allclose(pts[0], pts[-1]):
                pts = pts[:-1]
            np.savetxt(profile, pts, fmt="%.9f")
            mean = to2d(mean3)
            direction = [f"--le-direction={upstream[0]:.9f},{upstream[1]:.9f}"] if le_direction else []
            p = subprocess.run([args.camber, profile, "-o", out] + options + direction, capture_output=True, text=True)
            if p.returncode == 0:
                break
            # The projection of a thin, curved tip section can cross itself: camber refuses it.
            print(f"{s:3d} {mapping}: camber refused it: {p.stderr.strip()}")
        if p.returncode != 0:
            continue
        par = table(out, "params")[0]
        le = np.array([par["le_u"], par["le_v"]])
        te = np.array([par["te_u"], par["te_v"]])
        true_le, true_te = pts[120], pts[0]
        swapped = np.linalg.norm(le - true_te) + np.linalg.norm(te - true_le) < \
            np.linalg.norm(le - true_le) + np.linalg.norm(te - true_te)
        if swapped:
            true_le, true_te = true_te, true_le
        cam = np.array([[c["u"], c["v"]] for c in table(out, "camber")])
        d = np.array([distance_to_polyline(q, mean) for q in cam])
        print(f"{s:3d} {off:7.2f} {np.linalg.norm(le - true_le) * 1e3:9.1f} {np.linalg.norm(te - true_te) * 1e3:9.1f}"
              f" {np.sqrt((d ** 2).mean()) * 1e3:11.1f} {d.max() * 1e3:7.1f} {par['le_radius']:7.3f}"
              f" {par['te_radius']:7.3f}  {mapping:6s} {'LE and TE swapped' if swapped else 'right'}"
              f" (max thickness at {par['max_thickness_pos']:.2f})")
    print()


def streamlines():
    """The 21 streamlines (x, r) of 3dbgbinput.2.dat in mm (blocks ended by a `0 0` line)."""
    lines = open(os.path.join(args.data, "3dbgbinput.2.dat")).read().splitlines()
    start = next(k for k, l in enumerate(lines) if "Streamline Data" in l) + 2
    blocks = [[]]
    for l in lines[start:]:
        v = l.split()
        if len(v) != 2:
            continue
        x, r = float(v[0]), float(v[1])
        if x == 0 and r == 0:
            blocks.append([])
        else:
            blocks[-1].append((x, r))
    return [np.array(b) * 152.4 for b in blocks if b]


def densified(meridian, a_range, points=2000):
    """The streamline through a cubic spline in chord length, over the blade's axial range."""
    from scipy.interpolate import CubicSpline
    t = np.r_[0, np.cumsum(np.linalg.norm(np.diff(meridian, axis=0), axis=1))]
    q = CubicSpline(t, meridian)(np.linspace(0, t[-1], 40 * points))
    keep = (q[:, 0] > a_range[0]) & (q[:, 0] < a_range[1])
    q = q[keep]
    return q[np.linspace(0, len(q) - 1, points).round().astype(int)]


def run_surfaces(tmp, extra):
    cloud = os.path.join(tmp, "blade.xyz")
    np.savetxt(cloud, data, fmt="%.12f")
    files = []
    margin = 10
    for s, m in enumerate(streamlines()):
        sec = data[s * per_section:(s + 1) * per_section]
        name = os.path.join(tmp, f"streamline{s}.txt")
        np.savetxt(name, densified(m, (sec[:, 0].min() - margin, sec[:, 0].max() + margin)), fmt="%.12f")
        files.append(name)
    out = os.path.join(tmp, "surfaces.stream")
    surface_pipe("validate_tblade3", args.camber, cloud, files, out, extra)
    print("sections cut on their own streamline surfaces (slice --streamline, conformal), camber in 3D:")
    print(f"{'sec':>3} {'LE pt um':>9} {'TE pt um':>9} {'camber rms um':>14} {'max um':>7} {'LE r':>7} {'TE r':>7}")
    params = {int(r["section"]): r for r in table(out, "params")}
    camber = table(out, "camber")
    worst = []
    for s in range(data.shape[0] // per_section):
        sec = data[s * per_section:(s + 1) * per_section]
        mean3 = np.loadtxt(os.path.join(args.data, f"meanline.sec{s + 1}.Case7-28-8.dat"))
        if s not in params:
            print(f"{s:3d} not measured")
            continue
        par = params[s]
        le = np.array([par["le_x"], par["le_y"], par["le_z"]])
        te = np.array([par["te_x"], par["te_y"], par["te_z"]])
        cam = np.array([[c["x"], c["y"], c["z"]] for c in camber if int(c["section"]) == s])
        d = np.array([distance_to_polyline(q, mean3) for q in cam])
        worst.append((np.sqrt((d ** 2).mean()), d.max()))
        print(f"{s:3d} {np.linalg.norm(le - sec[120]) * 1e3:9.1f} {np.linalg.norm(te - sec[0]) * 1e3:9.1f}"
              f" {np.sqrt((d ** 2).mean()) * 1e3:14.2f} {d.max() * 1e3:7.2f} {par['le_radius']:7.3f}"
              f" {par['te_radius']:7.3f}")
    w = np.array(worst)
    print(f"camber to the exact mean line over {len(w)} sections: rms median {np.median(w[:, 0]) * 1e3:.2f} um,"
          f" worst {w[:, 0].max() * 1e3:.2f} um; max median {np.median(w[:, 1]) * 1e3:.2f} um,"
          f" worst {w[:, 1].max() * 1e3:.2f} um")
    print()


with tempfile.TemporaryDirectory() as tmp:
    run_surfaces(tmp, list(args.extra))
    if args.surfaces_only:
        sys.exit(0)
    run(list(args.extra), tmp, False)
    run(list(args.extra), tmp, True)
