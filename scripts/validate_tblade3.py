#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs the camber tool on the 21 sections of the T-Blade3 compressor rotor Case7-28-8
(../shared/data/real/tblade3-case7-28-8, not part of the repository) and compares our
camber lines and edge points with the generator's exact mean lines.

The sections lie on surfaces of revolution, not planes: each is projected onto its
least-squares plane, and the exact mean line with it. The projection distorts the hub
sections most (0.9 mm out of plane at the hub, 0.3-0.8 mm elsewhere); unwrapping
(x, r_mean * theta) instead was worse at the hub (3x the camber error on section 0). The
tip section's projection crosses itself (camber refuses it, rightly): it is unwrapped.

Usage: scripts/validate_tblade3.py [--camber BIN] [--data DIR] [-- extra camber options]
Prints per section: distance of the edge points (ours against the loop's points 121 = LE
and 1 = TE), RMS and max distance of our camber points to the exact mean line, and our
edge radii; run once as is (the LE chosen by thickness) and once with the LE direction
given (upstream, -x).
"""
import argparse, csv, os, subprocess, sys, tempfile

import numpy as np

from stream_tables import table

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--camber", default=os.path.join(here, "..", "build", "tools", "camber"))
ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "real", "tblade3-case7-28-8"))
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


with tempfile.TemporaryDirectory() as tmp:
    run(list(args.extra), tmp, False)
    run(list(args.extra), tmp, True)
