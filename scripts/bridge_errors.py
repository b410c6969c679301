#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""How far the fitted curve bridging a hole near an edge strays from the blade, against how
far that bridge bends (its sagitta): the measurement behind camber's `edge_bridge`
(docs/CAMBER.md, "A short hole on a large edge's arc").

For every exported section (bench/evaluate_pipeline --export DIR), each hole of the
measured points (a stretch of the true profile longer than 4 median spacings without one)
beginning within `--reach` (1.2) edge radii of our LE or TE point: its length, the exact
profile's sagitta over it (mean curvature x length^2 / 8), and the fit's largest distance
from the exact profile there (um, the points' noise included). Prints, per band of
sagitta, the share of the sagitta the bridge strayed (its error less the noise floor
`--floor`, 5 um) at the median, 90 % and 99 %.

Needs numpy and scipy (the peers' environment: docs/PERFORMANCE.md).
Usage:
  build/bench/evaluate_pipeline --seeds 81 --preset both --export DIR
  /tmp/peers/bin/python scripts/bridge_errors.py DIR [--reach 1.2] [--floor 5]
"""
import argparse
import glob
import os

import numpy as np
from scipy.spatial import cKDTree


def load(path):
    return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def section_holes(prefix, reach):
    """(sagitta um, bridge error um) of each hole near an edge of one exported section."""
    pts, truth, fit = load(prefix + "points.csv"), load(prefix + "truth.csv"), load(prefix + "fit.csv")
    edges = load(prefix + "edges.csv")[0]
    seg = np.linalg.norm(np.diff(np.vstack([truth, truth[:1]]), axis=0), axis=1)
    perimeter = seg.sum()
    s = np.concatenate([[0], np.cumsum(seg)[:-1]])
    nxt, prv = np.roll(truth, -1, 0), np.roll(truth, 1, 0)
    cross = np.abs((truth - prv)[:, 0] * (nxt - prv)[:, 1] - (truth - prv)[:, 1] * (nxt - prv)[:, 0])
    sides = (np.linalg.norm(nxt - truth, axis=1) * np.linalg.norm(truth - prv, axis=1) *
             np.linalg.norm(nxt - prv, axis=1))
    curvature = 2 * cross / (sides + 1e-30)
    dist, nearest = cKDTree(truth).query(fit)
    fit_s = s[nearest]
    along = np.sort(pts[:, 2] % perimeter)
    gaps = np.diff(np.concatenate([along, [along[0] + perimeter]]))
    spacing = np.median(gaps)
    out = []
    for u, v, radius in ((edges[0], edges[1], edges[6]), (edges[2], edges[3], edges[9])):
        if not radius > 0:
            continue
        at = s[np.argmin(np.hypot(truth[:, 0] - u, truth[:, 1] - v))]
        for i in np.where(gaps > 4 * spacing)[0]:
            start, length = along[i], gaps[i]
            rel = ((start - at + perimeter / 2) % perimeter) - perimeter / 2
            away = 0 if rel <= 0 <= rel + length else min(abs(rel), abs(rel + length))
            on_fit = ((fit_s - start) % perimeter) < length
            on_truth = ((s - start) % perimeter) < length
            if away > reach * radius or not on_fit.any() or not on_truth.any():
                continue
            out.append((1e3 * curvature[on_truth].mean() * length ** 2 / 8, 1e3 * dist[on_fit].max()))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--reach", type=float, default=1.2)
    ap.add_argument("--floor", type=float, default=5.0)
    a = ap.parse_args()
    rows = []
    for f in sorted(glob.glob(os.path.join(a.dir, "*_points.csv"))):
        prefix = f[: -len("points.csv")]
        if os.path.exists(prefix + "edges.csv") and os.path.exists(prefix + "fit.csv"):
            rows += section_holes(prefix, a.reach)
    if not rows:
        raise SystemExit("bridge_errors: no exported section with edges in " + a.dir)
    r = np.array(rows)
    print("sagitta um   holes  error um p50  p90   share of the sagitta strayed p50  p90  p99")
    for lo, hi in ((0, 10), (10, 20), (20, 40), (40, 80), (80, 160), (160, 400)):
        m = (r[:, 0] >= lo) & (r[:, 0] < hi)
        if not m.any():
            continue
        share = np.maximum(r[m, 1] - a.floor, 0) / np.maximum(r[m, 0], 1e-9)
        e50, e90 = np.percentile(r[m, 1], [50, 90])
        print("%4g-%-4g    %6d  %12.1f %5.1f   %31.3f %5.3f %5.3f" % (lo, hi, m.sum(), e50, e90,
              *np.percentile(share, [50, 90, 99])))


if __name__ == "__main__":
    main()
