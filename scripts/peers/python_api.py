#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The libsection Python module on the cases bench_compare exported, timed as a user would
call it (scripts/peers/python_speed.sh runs the whole comparison with engeom).

  python_api.py DIR            writes DIR/python.csv (compare) and DIR/python_camber.csv
  python_api.py --summary DIR  prints the speed table of ours and engeom's

For each case the nominal is the spline fit_spline makes of DIR/<case>_nominal.csv (as
bench_compare's nominal) with the edge points of DIR/<case>_edges.csv. compare: the measured
DIR/<case>_points.csv fitted by libsection.compare on the nominal prepared once
(prepare_nominal; "py_ls" least squares, "py_mz" minimum zone) and on the spline with its
preparation in each call ("py_ls_once"). camber: libsection.camber(spline) ("py_camber").
Times: CPU ms per call, the median of 5 runs (as bench_compare's and compare_peer.py's),
each including the conversions from and to numpy arrays.
"""
import glob
import math
import os
import sys
import time

import numpy as np


def median_ms(f, runs=5):
    times, out = [], None
    for _ in range(runs):
        t0 = time.process_time()
        out = f()
        times.append(1e3 * (time.process_time() - t0))
    return sorted(times)[runs // 2], out


def run(directory):
    import libsection as ls
    rows, camber_rows = ["case,method,angle,tx,ty,ms"], ["case,method,ms,prepare_ms"]
    for nominal_path in sorted(glob.glob(os.path.join(directory, "*_nominal.csv"))):
        case = os.path.basename(nominal_path)[: -len("_nominal.csv")]
        polyline = np.loadtxt(nominal_path, delimiter=",", skiprows=1)
        points = np.loadtxt(os.path.join(directory, case + "_points.csv"), delimiter=",", skiprows=1)
        le_u, le_v, te_u, te_v, side = np.loadtxt(os.path.join(directory, case + "_edges.csv"), delimiter=",",
                                                  skiprows=1)
        spline = ls.fit_spline(polyline)
        edges = ((le_u, le_v), (te_u, te_v), int(side))
        prepare_ms, nominal = median_ms(lambda: ls.Nominal(spline, *edges))
        minimum_zone = ls.Nominal(spline, *edges, fit="minimum-zone")
        for method, call in (("py_ls", lambda: ls.compare(nominal, points)),
                             ("py_mz", lambda: ls.compare(minimum_zone, points)),
                             ("py_ls_once", lambda: ls.compare(ls.Nominal(spline, *edges), points))):
            ms, r = median_ms(call)
            tx, ty = r["translation"]
            rows.append(f"{case},{method},{r['angle']!r},{float(tx)!r},{float(ty)!r},{ms!r}")
        ms, _ = median_ms(lambda: ls.camber(spline))
        camber_rows.append(f"{case},py_camber,{ms!r},{prepare_ms!r}")
        print(case, rows[-3].split(",")[-1], rows[-1].split(",")[-1], camber_rows[-1].split(",")[2], flush=True)
    with open(os.path.join(directory, "python.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")
    with open(os.path.join(directory, "python_camber.csv"), "w") as f:
        f.write("\n".join(camber_rows) + "\n")


def summary(directory):
    ms = {}
    for name in ("ours.csv", "python.csv", "engeom.csv", "python_camber.csv", "engeom_camber.csv"):
        path = os.path.join(directory, name)
        if not os.path.exists(path):
            continue
        with open(path) as f:
            header = f.readline().strip().split(",")
            for line in f:
                row = dict(zip(header, line.strip().split(",")))
                ms.setdefault(row["method"], []).append(float(row["ms"]))
    median = {m: sorted(v)[len(v) // 2] for m, v in ms.items()}
    print(f"{'method':<14} {'ms median':>10} {'ms worst':>10}   (CPU ms per section, {len(ms.get('py_ls', []))} sections)")
    for m, v in ms.items():
        print(f"{m:<14} {median[m]:10.3f} {max(v):10.3f}")
    print()
    for ours, theirs in (("py_ls", "engeom_ls"), ("py_ls", "engeom_rob"), ("py_ls_once", "engeom_ls"),
                         ("py_ls_once", "engeom_rob"), ("py_camber", "engeom_camber")):
        if ours in median and theirs in median:
            ratio = [t / o for o, t in zip(ms[ours], ms[theirs])]
            print(f"{theirs} / {ours}: {median[theirs] / median[ours]:5.1f}x at the medians "
                  f"(per section {min(ratio):.1f}x to {max(ratio):.1f}x)")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--summary":
        summary(sys.argv[2])
    elif len(sys.argv) == 2:
        run(sys.argv[1])
    else:
        sys.exit(__doc__)
