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

Then the sections are cut on their own surfaces of revolution instead (slice --axis
0,0,0,1,0,0 --streamline: each section's meridian is its (Z, R) points), unrolled
conformally (r_ref m', r_ref theta: true angles), measured with the upstream direction
given, and compared with the published section in the same plane: its mean line (theta1 +
theta2) / 2 against m', the metal angles from its slope over 2-6 % and 94-98 % of its extent along m', and its
normal thickness r_ref (theta1 - theta2) cos(beta) at each J.

Usage: scripts/validate_rotor37.py [--camber BIN] [--data FILE] [--surfaces-only]
"""
import argparse, os, subprocess, sys, tempfile

import numpy as np

from stream_tables import table
from surface_pipe import surface_pipe

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--camber", default=os.path.join(here, "..", "build", "tools", "camber"))
ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "real", "rotor37",
                                               "rotor37geometry.dat"))
ap.add_argument("--surfaces-only", action="store_true", help="only the cut on the surfaces of revolution")
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


def m_prime(z, r):
    """m' = integral dm / r along the meridian (z, r), exact on each straight piece."""
    dm = np.hypot(np.diff(z), np.diff(r))
    dr = np.diff(r)
    with np.errstate(divide="ignore", invalid="ignore"):
        piece = np.where(np.abs(dr) > 1e-12 * dm, dm / dr * np.log(r[1:] / r[:-1]), dm / r[:-1])
    return np.r_[0, np.cumsum(piece)]


def run_surfaces(tmp):
    points, files = [], []
    for k, rows in enumerate(sections):
        a = np.array(rows)
        z, r, t1, t2 = a[:, 0] * 10, a[:, 1] * 10, a[:, 2], a[:, 3]
        points += [np.c_[z, r * np.sin(t1), r * np.cos(t1)], np.c_[z, r * np.sin(t2), r * np.cos(t2)][1:-1]]
        name = os.path.join(tmp, f"meridian{k}.txt")
        np.savetxt(name, np.c_[z, r], fmt="%.9f")
        files.append(name)
    cloud = os.path.join(tmp, "rotor37.xyz")
    np.savetxt(cloud, np.vstack(points), fmt="%.9f")
    out = os.path.join(tmp, "surfaces.stream")
    surface_pipe("validate_rotor37", args.camber, cloud, files, out)
    params = {int(r["section"]): r for r in table(out, "params")}
    r_ref = {int(f["section"]): f["r_ref"] for f in table(out, "frames")}
    print("sections cut on their own surfaces (slice --streamline, conformal), against the published section:")
    print(f"{'sec':>3} {'t max':>6} {'pub':>6} {'diff um':>8} {'inlet':>7} {'pub':>7} {'diff':>6}"
          f" {'outlet':>7} {'pub':>7} {'diff':>6} {'chord':>7}")
    for k, rows in enumerate(sections):
        if k not in params:
            print(f"{k:3d} not measured")
            continue
        par, a = params[k], np.array(rows)
        z, r, t1, t2 = a[:, 0] * 10, a[:, 1] * 10, a[:, 2], a[:, 3]
        # The table's theta turns from +z towards +y, about -x: ours turns about +x (the axis).
        u, v = r_ref[k] * m_prime(z, r), -r_ref[k] * (t1 + t2) / 2
        beta = np.arctan(np.gradient(v, u))
        thickness = (r_ref[k] * np.abs(t1 - t2) * np.cos(beta)).max()
        f = (u - u[0]) / (u[-1] - u[0])  # fraction of the axial-meridional extent
        fit = lambda j: np.degrees(np.arctan(np.polyfit(u[j], v[j], 1)[0]))
        inlet, outlet = fit((f > 0.02) & (f < 0.06)), fit((f > 0.94) & (f < 0.98))
        print(f"{k:3d} {par['max_thickness']:6.3f} {thickness:6.3f} {(par['max_thickness'] - thickness) * 1e3:8.1f}"
              f" {par['inlet_angle']:7.2f} {inlet:7.2f} {par['inlet_angle'] - inlet:6.2f}"
              f" {par['outlet_angle']:7.2f} {outlet:7.2f} {par['outlet_angle'] - outlet:6.2f} {par['chord']:7.3f}")
    print()


with tempfile.TemporaryDirectory() as tmp:
    run_surfaces(tmp)
    if args.surfaces_only:
        sys.exit(0)
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
