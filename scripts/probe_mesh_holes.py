# SPDX-License-Identifier: GPL-3.0-or-later
"""Holes in a scan's mesh: generated blade meshes with the triangles near one plane removed
about each of 16 places along the profile, run through the pipe, every value scored against
the generator's exact truth. Prints the values off their target and whether a check flags
them (SILENT: none does), then a summary line. Needs numpy (the peers' venv).

    /tmp/peers/bin/python scripts/probe_mesh_holes.py --sizes 1,2,4,6,8
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from check_bits import check_bits, score_row  # noqa: E402

# Targets: lengths in mm, radii and the area relative, angles in degrees.
TARGETS = {"chord": ("abs", 0.010), "max_thickness": ("abs", 0.005),
           "le_radius": ("rel", 0.03), "te_radius": ("rel", 0.10), "inlet_angle": ("abs", 0.5),
           "outlet_angle": ("abs", 0.5), "stagger": ("abs", 0.5), "area": ("rel", 0.002)}


def read_obj(path):
    lines = open(path).read().split("\n")
    vertices = np.array([list(map(float, l.split()[1:4])) for l in lines if l.startswith("v ")])
    faces = [(i, [int(x.split("/")[0]) - 1 for x in l.split()[1:4]]) for i, l in enumerate(lines)
             if l.startswith("f ")]
    return lines, vertices, faces


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "build", "tools"))
    ap.add_argument("--sizes", default="1,2,4", help="hole widths, mm")
    ap.add_argument("--kinds", default="turbine,compressor,thick-root,sharp-te")
    ap.add_argument("--z", type=float, default=30, help="the plane's height, mm")
    args = ap.parse_args()
    bits, b, z0 = check_bits(), args.bin, args.z
    runs = measured = refused = silent = 0
    with tempfile.TemporaryDirectory() as d:
        for kind in args.kinds.split(","):
            subprocess.run([f"{b}/bladegen", "--kind", kind, "--mesh", "--profile-points", "600", "--layers", "61",
                            "-o", f"{d}/m.obj", "--truth", f"{d}/t.csv", "--at", str(z0)],
                           check=True, capture_output=True)
            truth = list(csv.DictReader(open(f"{d}/t.csv")))[0]
            lines, v, faces = read_obj(f"{d}/m.obj")
            centroids = np.array([v[f].mean(0) for _, f in faces])
            # The profile: the vertices of the mesh layer nearest the plane, in file order.
            layer = v[np.abs(v[:, 2] - v[np.argmin(np.abs(v[:, 2] - z0)), 2]) < 1e-9]
            along = np.r_[0, np.cumsum(np.linalg.norm(np.diff(layer[:, :2], axis=0), axis=1))]
            for size in [float(s) for s in args.sizes.split(",")]:
                for k in range(16):
                    centre = layer[min(np.searchsorted(along, along[-1] * k / 16), len(layer) - 1)][:2]
                    hole = (np.abs(centroids[:, 2] - z0) < 1.5) & \
                        (np.hypot(centroids[:, 0] - centre[0], centroids[:, 1] - centre[1]) < size / 2)
                    drop = {faces[i][0] for i in np.nonzero(hole)[0]}
                    open(f"{d}/h.obj", "w").write("\n".join(l for i, l in enumerate(lines) if i not in drop))
                    run = subprocess.run(f"{b}/slice {d}/h.obj --at {z0} | {b}/smooth | {b}/fitspline | "
                                         f"{b}/camber --format csv", shell=True, capture_output=True, text=True)
                    rows = list(csv.DictReader(run.stdout.splitlines()))
                    runs += 1
                    if not rows:
                        refused += 1
                        print(f"{kind:10s} hole {size} at {k}: refused: {run.stderr.strip()[-200:]}")
                        continue
                    measured += 1
                    silent += score_row(f"{kind:10s} hole {size} at {k}", kind, rows[0], truth, TARGETS, bits)
    print(f"mesh holes {args.sizes} mm: {runs} runs, {measured} measured, {refused} refused, "
          f"{silent} values off with no flag")


if __name__ == "__main__":
    main()
