#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs the camber tool on the 13 sections of NASA Rotor 37 (NASA TP-1337 Table IV, in
../shared/data/real/rotor37, not part of the repository) and prints the section
parameters, once with the leading edge chosen by thickness (the default) and once with
the upstream direction given (the blade's Z axis points downstream).

Each section lies on a surface of revolution (J = 1..100 along both surfaces, J = 1 the
leading edge); its closed loop (surface 1 forward, surface 2 back) is written in 3D as
x = Z, y = R sin(theta), z = R cos(theta) (mm), projected onto its least-squares plane
(0.75-1.03 mm out of plane) and given to camber as a plain profile; the upstream
direction (-1, 0, 0) goes with it, projected onto the same plane (as camber's
--le-direction x,y,z does with the frames of a sliced stream).

Usage: scripts/validate_rotor37.py [--camber BIN] [--data FILE]
"""
import argparse, os, subprocess, sys, tempfile

import numpy as np

from stream_tables import table

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--camber", default=os.path.join(here, "..", "build", "tools", "camber"))
ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "real", "rotor37",
                                               "rotor37geometry.dat"))
args = ap.parse_args()
if not os.access(args.camber, os.X_OK) or not os.path.exists(args.data):
    sys.exit(f"validate_rotor37: need {args.camber} and {args.data}")

sections, current = [], None
for line in open(args.data):
    if "SURFACE NUMBER" in line:
        current = []
        sections.append(current)
        continue
    f = line.split()
    if current is not None and len(f) == 5 and f[0].isdigit():
        current.append([float(x) for x in f[1:]])


with tempfile.TemporaryDirectory() as tmp:
    for upstream in (False, True):
        print("camber, LE " + ("upstream" if upstream else "by thickness (the default)"))
        print(f"{'sec':>3} {'off mm':>6} {'LE at J':>7} {'chord':>7} {'t max':>6} {'at':>5} {'LE r':>6} {'TE r':>6}"
              f" {'inlet':>6} {'outlet':>6}")
        for k, rows in enumerate(sections):
            a = np.array(rows)
            z, r, t1, t2 = a[:, 0] * 10, a[:, 1] * 10, a[:, 2], a[:, 3]
            side1 = np.c_[z, r * np.sin(t1), r * np.cos(t1)]
            side2 = np.c_[z, r * np.sin(t2), r * np.cos(t2)]
            loop = np.r_[side1, side2[-2:0:-1]]
            centre = loop.mean(0)
            e1, e2, normal = np.linalg.svd(loop - centre)[2]
            if np.cross(e1, e2) @ normal < 0:
                normal = -normal
            off = np.abs((loop - centre) @ normal).max()
            uv = np.c_[(loop - centre) @ e1, (loop - centre) @ e2]
            profile = os.path.join(tmp, f"p{k}.txt")
            np.savetxt(profile, uv, fmt="%.9f")
            out = os.path.join(tmp, "c.txt")
            direction = []
            if upstream:
                d = np.array([-1.0, 0.0, 0.0])
                direction = [f"--le-direction={d @ e1:.9f},{d @ e2:.9f}"]
            p = subprocess.run([args.camber, profile, "-o", out] + direction, capture_output=True, text=True)
            if p.returncode != 0:
                print(f"{k:3d} camber failed: {p.stderr.strip()}")
                continue
            par = table(out, "params")[0]
            le = np.array([par["le_u"], par["le_v"]])
            at_j1 = np.linalg.norm(le - uv[0]) < np.linalg.norm(le - uv[99])
            print(f"{k:3d} {off:6.2f} {('1' if at_j1 else '100'):>7} {par['chord']:7.3f} {par['max_thickness']:6.3f}"
                  f" {par['max_thickness_pos']:5.2f} {par['le_radius']:6.3f} {par['te_radius']:6.3f}"
                  f" {par['inlet_angle']:6.1f} {par['outlet_angle']:6.1f}")
        print()
