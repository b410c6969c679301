#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""engeom's 2D alignment on the cases bench_compare exported: what a user would run instead of
`compare` to fit measured section points onto a nominal profile.

For each case DIR/<case>_nominal.csv (the exact profile, 20000 points, closed) becomes an
engeom Curve2 and DIR/<case>_points.csv (the measured points) is aligned to it with
engeom.align2.points_to_curve, all three degrees of freedom, rotation about the points'
centroid: plain least squares (refinement_steps=0, "engeom_ls") and engeom's default robust
fit (4 rounds of MAGSAC++ reweighting, "engeom_rob"). Writes DIR/engeom.csv (case, method,
angle in degrees, tx, ty: p -> R p + t moving the points onto the nominal, and the CPU time
per section in ms: the median of 5 runs of the alignment alone, which also returns each
point's residual; CPU time, as bench_compare's, since wall time on a shared machine
measures the neighbours). bench_compare --score DIR then scores ours and engeom's alike.

Also engeom's camber line on the same nominals (scripts/peers/python_speed.sh compares it
with libsection.camber): 2000 points of each exact nominal polyline (every 10th) as a Curve2,
AfGeometry.from_geometric_analysis with the edges forced to "full_round" (as
scripts/compare_scipy.py calls it); DIR/engeom_camber.csv holds the CPU ms per section (the
median of 3 runs).

Usage: compare_peer.py DIR   (scripts/compare_engeom.sh runs the whole comparison)
"""
import glob
import math
import os
import sys
import time

import numpy as np
import engeom.airfoil2 as af
from engeom.align2 import AlignParams2, Dof3, points_to_curve
from engeom.geom2 import Curve2, Point2


def load(path):
    return np.loadtxt(path, delimiter=",", skiprows=1)


def median_ms(f, runs=5):
    times = []
    out = None
    for _ in range(runs):
        t0 = time.process_time()
        out = f()
        times.append(1e3 * (time.process_time() - t0))
    return sorted(times)[runs // 2], out


def camber_line(polyline):
    curve = Curve2(polyline[::10], force_closed=True, hull_ccw=True)
    return af.AfGeometry.from_geometric_analysis(curve, 1e-4, af.OrientFwdAft.tmax_fwd(),
                                                 af.OrientUpperLower.curvature(), "full_round", "full_round")


def main(directory):
    rows, camber_rows = ["case,method,angle,tx,ty,ms"], ["case,method,ms"]
    for nominal_path in sorted(glob.glob(os.path.join(directory, "*_nominal.csv"))):
        case = os.path.basename(nominal_path)[: -len("_nominal.csv")]
        polyline = load(nominal_path)
        nominal = Curve2(polyline, force_closed=True)
        points = load(os.path.join(directory, case + "_points.csv"))
        centre = points.mean(axis=0)
        params = AlignParams2(center=Point2(centre[0], centre[1]), dof=Dof3.all())
        for method, steps in (("engeom_ls", 0), ("engeom_rob", 4)):
            ms, outcome = median_ms(lambda: points_to_curve(points, nominal, params, refinement_steps=steps))
            m = outcome.alignment.full_transform.as_numpy()
            angle = math.degrees(math.atan2(m[1, 0], m[0, 0]))
            rows.append(f"{case},{method},{float(angle)!r},{float(m[0, 2])!r},{float(m[1, 2])!r},{float(ms)!r}")
        ms, _ = median_ms(lambda: camber_line(polyline), runs=3)
        camber_rows.append(f"{case},engeom_camber,{float(ms)!r}")
        print(case, rows[-2].split(",")[-1], rows[-1].split(",")[-1], ms, flush=True)
    for name, table in (("engeom.csv", rows), ("engeom_camber.csv", camber_rows)):
        with open(os.path.join(directory, name), "w") as f:
            f.write("\n".join(table) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
