#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""engeom's camber line on the cases bench_compare exported: what a user would run instead of
libsection.camber (scripts/peers/python_speed.sh).

For each case, 2000 points of the exact nominal polyline DIR/<case>_nominal.csv (every 10th
of its 20000) become an engeom Curve2, and AfGeometry.from_geometric_analysis finds its camber
line, edges forced to "full_round" (as scripts/compare_scipy.py calls it). Writes
DIR/engeom_camber.csv (case, method, CPU ms per section: the median of 3 runs).

Usage: engeom_camber.py DIR
"""
import glob
import os
import sys
import time

import numpy as np
import engeom.airfoil2 as af
from engeom.geom2 import Curve2


def main(directory):
    rows = ["case,method,ms"]
    for nominal_path in sorted(glob.glob(os.path.join(directory, "*_nominal.csv"))):
        case = os.path.basename(nominal_path)[: -len("_nominal.csv")]
        points = np.loadtxt(nominal_path, delimiter=",", skiprows=1)[::10]
        times = []
        for _ in range(3):
            t0 = time.process_time()
            af.AfGeometry.from_geometric_analysis(Curve2(points, force_closed=True, hull_ccw=True), 1e-4,
                                                  af.OrientFwdAft.tmax_fwd(), af.OrientUpperLower.curvature(),
                                                  "full_round", "full_round")
            times.append(1e3 * (time.process_time() - t0))
        rows.append(f"{case},engeom_camber,{sorted(times)[1]!r}")
        print(case, rows[-1].split(",")[-1], flush=True)
    with open(os.path.join(directory, "engeom_camber.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
