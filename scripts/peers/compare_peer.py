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

Usage: compare_peer.py DIR   (scripts/compare_engeom.sh runs the whole comparison)
"""
import glob
import math
import os
import sys
import time

import numpy as np
from engeom.align2 import AlignParams2, Dof3, points_to_curve
from engeom.geom2 import Curve2, Point2


def load(path):
    return np.loadtxt(path, delimiter=",", skiprows=1)


def median_ms(f):
    times = []
    out = None
    for _ in range(5):
        t0 = time.process_time()
        out = f()
        times.append(1e3 * (time.process_time() - t0))
    return sorted(times)[2], out


def main(directory):
    rows = ["case,method,angle,tx,ty,ms"]
    for nominal_path in sorted(glob.glob(os.path.join(directory, "*_nominal.csv"))):
        case = os.path.basename(nominal_path)[: -len("_nominal.csv")]
        nominal = Curve2(load(nominal_path), force_closed=True)
        points = load(os.path.join(directory, case + "_points.csv"))
        centre = points.mean(axis=0)
        params = AlignParams2(center=Point2(centre[0], centre[1]), dof=Dof3.all())
        for method, steps in (("engeom_ls", 0), ("engeom_rob", 4)):
            ms, outcome = median_ms(lambda: points_to_curve(points, nominal, params, refinement_steps=steps))
            m = outcome.alignment.full_transform.as_numpy()
            angle = math.degrees(math.atan2(m[1, 0], m[0, 0]))
            rows.append(f"{case},{method},{float(angle)!r},{float(m[0, 2])!r},{float(m[1, 2])!r},{float(ms)!r}")
        print(case, rows[-2].split(",")[-1], rows[-1].split(",")[-1], flush=True)
    with open(os.path.join(directory, "engeom.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
