#!/usr/bin/env python3
"""Compares our fitspline with scipy's periodic smoothing spline on the same slab points.

scipy gets the points ordered perfectly by their true arc length (an advantage ours does
not have) and splprep(per=1) with the smoothing condition s = m sigma^2 (sigma = 5 um, the
scan noise); both curves are scored against the dense true profile: RMS over the curve,
max where a measured point lies within 0.3 mm, and the largest error elsewhere (hole
bridging), as bench/evaluate_pipeline does.

Usage:
  build/bench/evaluate_pipeline --seeds 1 --no-camber --export DIR
  python3 scripts/compare_scipy.py DIR
Not done yet: the camber comparison (engeom, scipy Voronoi medial axis).
"""
import csv
import sys
import time

import numpy as np
from scipy.interpolate import splev, splprep
from scipy.spatial import cKDTree

SIGMA = 0.005  # mm, the scan noise of evaluate_pipeline


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def score(curve, truth_tree, data_tree):
    d_truth, _ = truth_tree.query(curve)
    d_data, _ = data_tree.query(curve)
    near = d_data <= 0.3
    rms = np.sqrt(np.mean(d_truth ** 2))
    mx = d_truth[near].max() if near.any() else 0.0
    gap = d_truth[~near].max() if (~near).any() else 0.0
    return rms * 1e3, mx * 1e3, gap * 1e3


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    folder = sys.argv[1]
    scores = read(f"{folder}/scores.csv")
    print(f"{'blade':10s} {'seed':>4s} {'sec':>3s} | {'ours rms':>8s} {'max':>7s} {'gap':>7s} {'ms':>6s} |"
          f" {'scipy rms':>9s} {'max':>7s} {'gap':>7s} {'ms':>6s}")
    for row in scores:
        key = f"{folder}/{row['blade']}_{row['seed']}_{row['section']}"
        pts = read(key + "_points.csv")
        truth = np.array([[float(r["u"]), float(r["v"])] for r in read(key + "_truth.csv")])
        order = np.argsort([float(r["true_s"]) for r in pts])
        xy = np.array([[float(pts[i]["u"]), float(pts[i]["v"])] for i in order])
        t0 = time.perf_counter()
        # splprep needs distinct consecutive points and a closed loop for per=1
        loop = np.vstack([xy, xy[:1]])
        try:
            tck, _ = splprep(loop.T, s=len(xy) * SIGMA ** 2, per=1, k=3, quiet=2)
            curve = np.array(splev(np.linspace(0, 1, 20000, endpoint=False), tck)).T
            ms = (time.perf_counter() - t0) * 1e3
            rms, mx, gap = score(curve, cKDTree(truth), cKDTree(xy))
            theirs = f"{rms:9.2f} {mx:7.2f} {gap:7.2f} {ms:6.1f}"
        except Exception as e:  # scipy may fail on a loop; report and go on
            theirs = f"failed: {e}"
        print(f"{row['blade']:10s} {row['seed']:>4s} {row['section']:>3s} | {float(row['rms_um']):8.2f} "
              f"{float(row['max_um']):7.2f} {float(row['gap_um']):7.2f} {float(row['ms_per_section']):6.0f} | {theirs}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
