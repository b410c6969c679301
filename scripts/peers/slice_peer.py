#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python pipeline a user would write instead of `slice | smooth | fitspline`:
numpy slab mask per plane, nearest-neighbour chaining (scipy cKDTree) to order the
section, scipy.interpolate.splprep periodic smoothing spline per section.

Usage: slice_peer.py CLOUD.ply|CLOUD.xyz --count N [--normal-z]
       slice_peer.py ROWS.ply --rows   (a scan in rows: each row, heights more than 1 mm
                                        from the next, is one section)
Prints one line: points, sections fitted, and the wall time of read / slab / order / fit.
"""
import argparse
import sys
import time

import numpy as np
from scipy.interpolate import splev, splprep
from scipy.spatial import cKDTree


def read_cloud(path):
    if path.endswith(".ply"):
        from plyfile import PlyData
        v = PlyData.read(path)["vertex"]
        return np.column_stack([np.asarray(v["x"], float), np.asarray(v["y"], float), np.asarray(v["z"], float)])
    return np.loadtxt(path, usecols=(0, 1, 2))


def spacing(points, sample=50000, seed=1):
    # Median nearest-neighbour distance of a random subset, scaled back to the full density.
    rng = np.random.default_rng(seed)
    n = len(points)
    m = min(n, sample)
    sub = points[rng.choice(n, m, replace=False)] if m < n else points
    d, _ = cKDTree(sub).query(sub[:5000], k=2)
    s = float(np.median(d[:, 1]))
    return s * np.sqrt(m / n) / 0.47 if m < n else s


def chain(uv):
    # Greedy nearest-neighbour ordering: from a point, go to the nearest unvisited one.
    tree = cKDTree(uv)
    n = len(uv)
    visited = np.zeros(n, bool)
    order = [0]
    visited[0] = True
    cur = 0
    for _ in range(n - 1):
        k = 16
        nxt = -1
        while nxt < 0:
            _, idx = tree.query(uv[cur], k=min(k, n))
            for j in np.atleast_1d(idx):
                if not visited[j]:
                    nxt = j
                    break
            if k >= n:
                break
            k *= 4
        if nxt < 0:
            break
        visited[nxt] = True
        order.append(nxt)
        cur = nxt
    return uv[order]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cloud")
    ap.add_argument("--count", type=int, default=20)
    ap.add_argument("--rows", action="store_true", help="each row of points (a height level) is a section")
    ap.add_argument("--noise", type=float, default=0.005, help="sigma for the splprep smoothing factor, mm")
    a = ap.parse_args()
    t0 = time.perf_counter()
    p = read_cloud(a.cloud)
    t1 = time.perf_counter()
    z = p[:, 2]
    lo, hi = z.min(), z.max()
    heights = lo + (hi - lo) * (np.arange(a.count) + 1) / (a.count + 1)
    slab = spacing(p)
    if a.rows:
        # The rows' heights: sorted heights split where they jump by more than 1 mm; the
        # slab takes a whole row.
        zs = np.sort(z)
        cut = np.flatnonzero(np.diff(zs) > 1.0)
        starts, ends = np.r_[0, cut + 1], np.r_[cut, len(zs) - 1]
        heights = 0.5 * (zs[starts] + zs[ends])
        slab = 2 * float(np.max(zs[ends] - zs[starts])) + 1e-9
    t_slab = t_order = t_fit = 0.0
    fitted = 0
    for h in heights:
        s0 = time.perf_counter()
        uv = p[np.abs(z - h) <= slab / 2][:, :2]
        s1 = time.perf_counter()
        t_slab += s1 - s0
        if len(uv) < 16:
            continue
        ordered = chain(uv)
        s2 = time.perf_counter()
        t_order += s2 - s1
        try:
            tck, _ = splprep([ordered[:, 0], ordered[:, 1]], per=1, s=len(ordered) * a.noise ** 2, quiet=2)
            splev(np.linspace(0, 1, 1000), tck)
            fitted += 1
        except Exception as e:  # a failed section does not stop the others
            print(f"slice_peer: section at z={h:.3f}: {e}", file=sys.stderr)
        t_fit += time.perf_counter() - s2
    total = time.perf_counter() - t0
    print(f"points={len(p)} sections={fitted} slab={slab:.5f} read_s={t1 - t0:.3f} slab_s={t_slab:.3f} "
          f"order_s={t_order:.3f} fit_s={t_fit:.3f} total_s={total:.3f}")


if __name__ == "__main__":
    main()
