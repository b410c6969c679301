#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""How much the VKI LS89 points say about the leading-edge radius (reference 4.127 mm).

Reads ../shared/data/real/ls89/point_cloud_LS89.txt (not part of the repository) and
prints:
  1. circles fitted (geometric least squares) to the raw points near the leading edge,
     by angular window around the nose and by axial window x <= X: the spread of radii
     the data support, with the fit rms;
  2. our camber tool's LE radius on the same points for a range of its edge options
     (grown-arc core and residual, fixed arcs), to show how the estimate moves with
     choices the data cannot settle.

Usage: scripts/ls89_leading_edge.py [--camber build/tools/camber] [--data FILE]
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.optimize import least_squares

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--camber", default=os.path.join(here, "..", "build", "tools", "camber"))
ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "real", "ls89",
                                               "point_cloud_LS89.txt"))
args = ap.parse_args()
if not os.access(args.data, os.R_OK):
    sys.exit(f"ls89_leading_edge: cannot read {args.data}")

d = np.loadtxt(args.data)
ids, x, y = d[:, 0], d[:, 3] * 1000, d[:, 2] * 1000  # columns: id span y x (metres)
first = ids <= 206
second = (ids > 207) & (ids < 405)
profile = np.vstack([np.c_[x[first], y[first]], np.c_[x[second], y[second]][::-1]])


def circle(p):
    a = np.c_[2 * p, np.ones(len(p))]
    s = np.linalg.lstsq(a, (p ** 2).sum(1), rcond=None)[0]
    start = [s[0], s[1], np.sqrt(s[2] + s[:2] @ s[:2])]
    f = lambda v: np.hypot(p[:, 0] - v[0], p[:, 1] - v[1]) - v[2]
    v = least_squares(f, start).x
    return v, np.sqrt(np.mean(f(v) ** 2))


print("LS89 leading edge: reference radius 4.127 mm (Mueller and Verstraete 2016)")
print("points are spaced evenly in x (0.185 mm): near the nose, where the profile runs along y,")
print("consecutive points lie up to %.2f mm apart" %
      max(np.hypot(*(profile[i] - profile[i - 1])) for i in range(len(profile))
          if abs(profile[i][0]) < 0.5 and abs(profile[i - 1][0]) < 0.5))
nose, _ = circle(profile[np.hypot(profile[:, 0], profile[:, 1]) < 2.5])
c = nose[:2]
toward = -c / np.linalg.norm(c)
q = profile - c
angle = np.degrees(np.abs(np.arctan2(toward[0] * q[:, 1] - toward[1] * q[:, 0], q @ toward)))
print("\n1a. circle through the raw points within +-A degrees of the nose (seen from its centre)")
print("   A  points  radius mm  rms um")
for half in (25, 30, 35, 40, 45, 50, 60):
    sel = (angle < half) & (np.hypot(q[:, 0], q[:, 1]) < 3 * nose[2])
    v, rms = circle(profile[sel])
    print(f"  {half:3d}  {sel.sum():6d}  {v[2]:9.3f}  {rms * 1e3:6.1f}")
print("\n1b. circle through the raw points with x <= X mm (the axial window)")
print("    X  points  radius mm  rms um")
for xmax in (0.4, 0.6, 0.8, 1.0, 1.5, 2.0):
    sel = (profile[:, 0] <= xmax + 1e-9) & (np.abs(profile[:, 1]) < 10)
    v, rms = circle(profile[sel])
    print(f"  {xmax:3.1f}  {sel.sum():6d}  {v[2]:9.3f}  {rms * 1e3:6.1f}")

if not os.access(args.camber, os.X_OK):
    sys.exit(0)
print("\n2. camber on the same points (plain profile input), LE radius by edge option")
with tempfile.TemporaryDirectory() as tmp:
    path = os.path.join(tmp, "ls89.txt")
    np.savetxt(path, profile, fmt="%.6f")
    params = os.path.join(tmp, "p.csv")
    runs = [("default (grown arc)", [])]
    runs += [(f"--edge-core {c_}", ["--edge-core", str(c_)]) for c_ in (20, 25, 30, 35, 40)]
    runs += [(f"--tangent-span {t}", ["--tangent-span", str(t)]) for t in (0.1, 0.2)]
    runs += [(f"--edge-residual {r}", ["--edge-residual", str(r)]) for r in (2, 5)]
    runs += [(f"--edge-arc {a}", ["--edge-arc", str(a)]) for a in (40, 80, 120)]
    for name, extra in runs:
        run = subprocess.run([args.camber, path, "--params", params, "-o", os.devnull] + extra,
                             capture_output=True, text=True)
        rows = list(csv.DictReader(open(params))) if run.returncode == 0 and os.path.exists(params) else []
        if os.path.exists(params):
            os.remove(params)
        if not rows:
            print(f"  {name:22s} failed: {run.stderr.strip().splitlines()[-1] if run.stderr.strip() else run.returncode}")
            continue
        row = rows[0]
        r = float(row["le_radius"])
        print(f"  {name:22s} le_radius {r:7.3f} mm ({(r / 4.127 - 1) * 100:+6.1f} %), arc {float(row['le_arc']):5.1f} deg,"
              f" fit rms {float(row['le_fit_rms']) * 1e3:5.1f} um")
