# SPDX-License-Identifier: GPL-3.0-or-later
"""Scan defects of real data on generated scans, run through the pipe, every value scored
against the generator's exact truth: patches of points doubled (ghost: a reflection) or
moved (bump) beside the surface near each plane, points scattered off it (spray: a laser's
mixed pixels), or the edges scanned sparser than the flanks (thin-edges: 1 point in
--patches kept within --radius of the LE and TE points). Prints the values off their
target and whether a check flags them (SILENT: none does), then a summary line. Needs
numpy and scipy (the peers' venv).

    /tmp/peers/bin/python scripts/probe_scan_defects.py --mode ghost --offset 0.03 \\
        --radius 0.5 --patches 2 --seeds 5,6
    /tmp/peers/bin/python scripts/probe_scan_defects.py --mode thin-edges --patches 8 --radius 3
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from check_bits import check_bits, score_row  # noqa: E402

TARGETS = {"chord": ("abs", 0.010), "max_thickness": ("abs", 0.005), "le_radius": ("rel", 0.03),
           "te_radius": ("rel", 0.10), "inlet_angle": ("abs", 0.5), "outlet_angle": ("abs", 0.5),
           "stagger": ("abs", 0.5)}
HEIGHTS = [10, 20, 30, 40, 50]


def sprayed(points, args, rng):
    """The scan with a share `patches` / 100 of its points moved off the surface by up to
    `offset` (uniform, along the local normal, out or in at random): a laser's mixed pixels."""
    tree = cKDTree(points)
    chosen = rng.choice(len(points), int(len(points) * args.patches / 100), replace=False)
    for c in chosen:
        nb = points[tree.query(points[c], k=12)[1]]
        normal = np.linalg.eigh(np.cov((nb - nb.mean(0)).T))[1][:, 0]
        points[c] = points[c] + rng.uniform(-args.offset, args.offset) * normal
    return points


def thinned(points, truth, args, rng):
    """The scan with 1 point in `patches` kept within `radius` of the LE and TE points (each
    height's edge points interpolated from the truth's)."""
    z = np.array([float(t["z"]) for t in truth])
    near = np.zeros(len(points), dtype=bool)
    for edge in ("le", "te"):
        x = np.interp(points[:, 2], z, [float(t[edge + "_x"]) for t in truth])
        y = np.interp(points[:, 2], z, [float(t[edge + "_y"]) for t in truth])
        near |= np.hypot(points[:, 0] - x, points[:, 1] - y) < args.radius
    return points[~near | (rng.random(len(points)) < 1.0 / args.patches)]


def patched(points, heights, args, rng):
    """The scan with `patches` patches of `radius` near each plane doubled (ghost) or moved
    (bump) by `offset` along the local normal, out or in at random."""
    if args.mode == "spray":
        return sprayed(points, args, rng)
    tree = cKDTree(points)
    extra = []
    for z in heights:
        candidates = np.where(np.abs(points[:, 2] - z) < 0.3)[0]
        for c in rng.choice(candidates, args.patches, replace=False):
            near = tree.query_ball_point(points[c], args.radius)
            nb = points[tree.query(points[c], k=20)[1]]
            normal = np.linalg.eigh(np.cov((nb - nb.mean(0)).T))[1][:, 0]
            ring = points[np.abs(points[:, 2] - points[c, 2]) < 0.2]
            if np.dot(normal, points[c] - ring.mean(0)) < 0:
                normal = -normal
            shift = args.offset * (1 if rng.random() < 0.5 else -1) * normal
            if args.mode == "ghost":
                extra.append(points[near] + shift)
            else:
                points[near] += shift
    return np.vstack([points] + extra) if extra else points


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "build", "tools"))
    ap.add_argument("--mode", choices=["ghost", "bump", "spray", "thin-edges"], default="ghost")
    ap.add_argument("--offset", type=float, default=0.03, help="mm off the surface")
    ap.add_argument("--radius", type=float, default=0.5, help="patch radius, mm")
    ap.add_argument("--patches", type=int, default=2,
                    help="patches near each plane (spray: per cent of the points moved; thin-edges: "
                         "1 point in this many kept)")
    ap.add_argument("--seeds", default="5,6")
    ap.add_argument("--kinds", default="turbine,compressor,thick-root,sharp-te")
    args = ap.parse_args()
    bits = check_bits()
    b = args.bin
    sections = refused = silent = 0
    with tempfile.TemporaryDirectory() as d:
        for kind in args.kinds.split(","):
            for seed in [int(s) for s in args.seeds.split(",")]:
                at = ",".join(map(str, HEIGHTS))
                subprocess.run([f"{b}/bladegen", "--kind", kind, "--points", "--noise", "0.005", "--seed",
                                str(seed), "-o", f"{d}/s.xyz", "--truth", f"{d}/t.csv", "--at", at],
                               check=True, capture_output=True)
                rng = np.random.default_rng(seed * 100 + int(args.offset * 1000))
                truth = list(csv.DictReader(open(f"{d}/t.csv")))
                points = np.loadtxt(f"{d}/s.xyz")
                if args.mode == "thin-edges":
                    points = thinned(points, truth, args, np.random.default_rng(seed))
                else:
                    points = patched(points, HEIGHTS, args, rng)
                np.savetxt(f"{d}/g.xyz", points, fmt="%.5f")
                run = subprocess.run(f"{b}/slice {d}/g.xyz --at {at} | {b}/smooth | {b}/fitspline | "
                                     f"{b}/camber --format csv", shell=True, capture_output=True, text=True)
                rows = {int(r["section"]): r for r in csv.DictReader(run.stdout.splitlines())}
                for k, z in enumerate(HEIGHTS):
                    if k not in rows:
                        refused += 1
                        print(f"{kind:10s} seed {seed} z {z}: refused: {run.stderr.strip()[-300:]}")
                        continue
                    sections += 1
                    silent += score_row(f"{kind:10s} seed {seed} z {z}", kind, rows[k], truth[k], TARGETS, bits)
    print(f"{args.mode} {args.offset} mm, {args.patches} patches of {args.radius} mm a plane: "
          f"{sections} sections, {refused} refused, {silent} values off with no flag")


if __name__ == "__main__":
    main()
