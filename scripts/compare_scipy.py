#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compares our pipe with what a user could do without it, on the same slab points.

Fit: our fitspline against scipy's periodic smoothing spline. scipy gets the points
ordered perfectly by their true arc length (an advantage ours does not have) and
splprep(per=1) with the smoothing condition s = m sigma^2 (sigma = 5 um, the scan noise);
both curves are scored against the dense true profile: RMS over the curve, max where a
measured point lies within 0.3 mm, and the largest error elsewhere (hole bridging), as
bench/evaluate_pipeline does.

Camber (when the export holds our camber scores): on that scipy curve (2000 samples),
  engeom  AfGeometry.from_geometric_analysis, edges forced to "full_round", LE at the
          thicker end (tmax_fwd), upper/lower by curvature;
  voronoi scipy.spatial.Voronoi of the curve samples, the vertices inside the profile,
          main branch = the longest path of their ridge graph (its ends: LE/TE points);
  split   the split-and-average camber of airfoil tools: the curve split at its u
          extremes, the two sides averaged at equal u (LE/TE: the u extremes);
and ours (slice | smooth | fitspline | camber, from scores.csv). Per method: camber RMS
and max distance of its camber points to the true camber line (extensions included),
LE/TE radius error (%), LE/TE point error (um), time per section (ms; ours: camber stage
only, wall time on the loaded machine; the others: their camber step only, not the fit).

Usage (one command, given a build directory; default build):
  python3 scripts/compare_scipy.py --build build-camber [--seeds 1] [--keep DIR]
  python3 scripts/compare_scipy.py DIR        # an existing export:
      build/bench/evaluate_pipeline --seeds 1 --export DIR
"""
import csv
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.interpolate import splev, splprep
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra
from scipy.spatial import Voronoi, cKDTree

try:
    import engeom.airfoil2 as engeom_af
    from engeom.geom2 import Curve2
except ImportError:  # the camber comparison then leaves engeom out
    engeom_af = None

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


def inside(poly, q):
    """Even-odd point-in-polygon test of the points q against the closed polyline poly."""
    x, y = q[:, 0][:, None], q[:, 1][:, None]
    a, b = poly, np.roll(poly, -1, axis=0)
    cond = (a[:, 1] > y) != (b[:, 1] > y)
    xi = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / np.where(b[:, 1] == a[:, 1], 1e-300, b[:, 1] - a[:, 1])
    return (np.sum(cond & (x < xi), axis=1) % 2) == 1


def voronoi_camber(curve):
    """Main branch of the Voronoi medial axis of the closed polyline `curve`."""
    vor = Voronoi(curve)
    keep = inside(curve, vor.vertices)
    idx = -np.ones(len(vor.vertices), dtype=int)
    idx[keep] = np.arange(keep.sum())
    verts = vor.vertices[keep]
    rows, cols, w = [], [], []
    for r in vor.ridge_vertices:
        if -1 in r or idx[r[0]] < 0 or idx[r[1]] < 0:
            continue
        i, j = idx[r[0]], idx[r[1]]
        rows += [i, j]
        cols += [j, i]
        w += [np.linalg.norm(verts[i] - verts[j])] * 2
    g = coo_matrix((w, (rows, cols)), shape=(len(verts), len(verts))).tocsr()
    d0 = dijkstra(g, indices=0)
    a = int(np.argmax(np.where(np.isfinite(d0), d0, -1)))
    da, pred = dijkstra(g, indices=a, return_predecessors=True)
    b = int(np.argmax(np.where(np.isfinite(da), da, -1)))
    path = [b]
    while path[-1] != a:
        path.append(pred[path[-1]])
    return verts[path[::-1]]


def split_camber(curve):
    """Split at the u extremes, average the two sides at equal u."""
    i0, i1 = int(np.argmin(curve[:, 0])), int(np.argmax(curve[:, 0]))
    if i0 < i1:
        side_a, side_b = curve[i0:i1 + 1], np.vstack([curve[i1:], curve[:i0 + 1]])[::-1]
    else:
        side_a, side_b = np.vstack([curve[i0:], curve[:i1 + 1]]), curve[i1:i0 + 1][::-1]
    u = np.linspace(curve[i0, 0], curve[i1, 0], 400)

    def at(side):
        o = np.argsort(side[:, 0])
        return np.interp(u, side[o, 0], side[o, 1])

    return np.c_[u, 0.5 * (at(side_a) + at(side_b))]


def camber_scores(points, truth_camber_tree, le, te, ends):
    """RMS/max (um) of the camber points to the truth, and LE/TE point errors (um)."""
    d, _ = truth_camber_tree.query(points)
    if ends is None:
        return np.sqrt(np.mean(d ** 2)) * 1e3, d.max() * 1e3, np.nan, np.nan
    e0, e1 = ends
    # Orientation-free: the better of the two assignments of the ends.
    a = np.linalg.norm(e0 - le) + np.linalg.norm(e1 - te)
    b = np.linalg.norm(e1 - le) + np.linalg.norm(e0 - te)
    if b < a:
        e0, e1 = e1, e0
    return np.sqrt(np.mean(d ** 2)) * 1e3, d.max() * 1e3, np.linalg.norm(e0 - le) * 1e3, np.linalg.norm(e1 - te) * 1e3


def camber_methods(curve, truth_camber, edges):
    """engeom, voronoi and split on the scipy curve: name -> (rms, max, le_r%, te_r%, le_um, te_um, ms)."""
    tree = cKDTree(densify(truth_camber))
    le = np.array([edges["le_u"], edges["le_v"]])
    te = np.array([edges["te_u"], edges["te_v"]])
    out = {}
    if engeom_af is not None:
        t0 = time.perf_counter()
        try:
            g = engeom_af.AfGeometry.from_geometric_analysis(
                Curve2(curve, force_closed=True, hull_ccw=True), 1e-4, engeom_af.OrientFwdAft.tmax_fwd(),
                engeom_af.OrientUpperLower.curvature(), "full_round", "full_round")
            ms = (time.perf_counter() - t0) * 1e3
            lp, tp = g.leading.point, g.trailing.point
            rms, mx, le_e, te_e = camber_scores(np.asarray(g.camber.points), tree, le, te,
                                                (np.array([lp.x, lp.y]), np.array([tp.x, tp.y])))
            rl = (g.leading.geometry.radius / edges["le_radius"] - 1) * 100
            rt = (g.trailing.geometry.radius / edges["te_radius"] - 1) * 100
            out["engeom"] = (rms, mx, rl, rt, le_e, te_e, ms)
        except Exception as e:  # engeom raises ValueError when an analysis step fails
            out["engeom"] = f"failed: {e}"
    t0 = time.perf_counter()
    path = voronoi_camber(curve)
    ms = (time.perf_counter() - t0) * 1e3
    out["voronoi"] = camber_scores(path, tree, le, te, (path[0], path[-1]))[:2] + (np.nan, np.nan) + \
        camber_scores(path, tree, le, te, (path[0], path[-1]))[2:] + (ms,)
    t0 = time.perf_counter()
    mean = split_camber(curve)
    ms = (time.perf_counter() - t0) * 1e3
    sc = camber_scores(mean, tree, le, te, (mean[0], mean[-1]))
    out["split"] = sc[:2] + (np.nan, np.nan) + sc[2:] + (ms,)
    return out


def densify(poly, step=0.002):
    out = [poly[:1]]
    for a, b in zip(poly[:-1], poly[1:]):
        n = max(1, int(np.ceil(np.linalg.norm(b - a) / step)))
        out.append(a + (b - a) * (np.arange(1, n + 1) / n)[:, None])
    return np.vstack(out)


def export(build, seeds, folder):
    exe = os.path.join(build, "bench", "evaluate_pipeline")
    if not os.access(exe, os.X_OK):
        sys.exit(f"compare_scipy: no {exe}; build it: cmake --build {build} --target evaluate_pipeline")
    subprocess.run([exe, "--seeds", str(seeds), "--export", folder, "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)


def fmt(v, w=7, p=2):
    return f"{v:{w}.{p}f}" if isinstance(v, (int, float, np.floating)) and np.isfinite(v) else f"{'-':>{w}s}"


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if args else 2
    if args[0] == "--build":
        build = args[1]
        seeds = int(args[args.index("--seeds") + 1]) if "--seeds" in args else 1
        folder = args[args.index("--keep") + 1] if "--keep" in args else tempfile.mkdtemp(prefix="compare_")
        os.makedirs(folder, exist_ok=True)
        if os.path.exists(f"{folder}/scores.csv"):
            os.remove(f"{folder}/scores.csv")
        export(build, seeds, folder)
    else:
        folder = args[0]
    scores = read(f"{folder}/scores.csv")
    print(f"{'blade':10s} {'seed':>4s} {'sec':>3s} | {'ours rms':>8s} {'max':>7s} {'gap':>7s} {'ms':>6s} |"
          f" {'scipy rms':>9s} {'max':>7s} {'gap':>7s} {'ms':>6s}")
    camber_rows = []
    for row in scores:
        key = f"{folder}/{row['blade']}_{row['seed']}_{row['section']}"
        pts = read(key + "_points.csv")
        truth = np.array([[float(r["u"]), float(r["v"])] for r in read(key + "_truth.csv")])
        order = np.argsort([float(r["true_s"]) for r in pts])
        xy = np.array([[float(pts[i]["u"]), float(pts[i]["v"])] for i in order])
        t0 = time.perf_counter()
        # splprep needs distinct consecutive points and a closed loop for per=1
        loop = np.vstack([xy, xy[:1]])
        curve = None
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
        if curve is not None and "cam_rms_um" in row and os.path.exists(key + "_camber.csv"):
            tc = np.array([[float(r["u"]), float(r["v"])] for r in read(key + "_camber.csv")])
            edges = {k: float(v) for k, v in read(key + "_edges.csv")[0].items()}
            m = camber_methods(curve[::10], tc, edges)
            m["ours"] = tuple(float(row[c]) for c in ("cam_rms_um", "cam_max_um", "le_radius_err_pct",
                                                      "te_radius_err_pct", "le_point_um", "te_point_um", "camber_ms"))
            camber_rows.append((row["blade"], row["seed"], row["section"], m))
    if camber_rows:
        print("\ncamber: RMS / max to the true camber line (um), LE / TE radius error (%), "
              "LE / TE point error (um), ms per section")
        methods = ["ours", "engeom", "voronoi", "split"]
        print(f"{'blade':10s} {'seed':>4s} {'sec':>3s} {'method':8s} {'rms':>7s} {'max':>8s} {'le_r%':>7s} "
              f"{'te_r%':>7s} {'le_um':>7s} {'te_um':>7s} {'ms':>7s}")
        for blade, seed, sec, m in camber_rows:
            for name in methods:
                v = m.get(name)
                if v is None:
                    continue
                if isinstance(v, str):
                    print(f"{blade:10s} {seed:>4s} {sec:>3s} {name:8s} {v}")
                    continue
                print(f"{blade:10s} {seed:>4s} {sec:>3s} {name:8s} {fmt(v[0])} {fmt(v[1], 8, 1)} {fmt(v[2])} "
                      f"{fmt(v[3])} {fmt(v[4], 7, 1)} {fmt(v[5], 7, 1)} {fmt(v[6], 7, 1)}")
        print("\nsummary per preset and method: median / worst (abs); ms median")
        for blade in sorted({r[0] for r in camber_rows}):
            for name in methods:
                vals = [r[3][name] for r in camber_rows if r[0] == blade and not isinstance(r[3].get(name, ""), str)]
                if not vals:
                    continue
                a = np.abs(np.array(vals, dtype=float))

                def mw(i):
                    col = a[:, i][np.isfinite(a[:, i])]
                    return f"{np.median(col):.2f} / {col.max():.2f}" if len(col) else "-"

                failed = sum(1 for r in camber_rows if r[0] == blade and isinstance(r[3].get(name, ""), str))
                print(f"{blade:10s} {name:8s} rms {mw(0)} | max {mw(1)} | le_r% {mw(2)} | te_r% {mw(3)} | "
                      f"le_um {mw(4)} | te_um {mw(5)} | ms {np.median(a[:, 6]):.1f}" + (f" | {failed} failed" if failed else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
