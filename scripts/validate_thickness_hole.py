#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A hole in the scan at the thickest circle: generated scans (bladegen, exact truth) with
the points within L/2 of a contact of the thickest inscribed circle removed over the whole
scanned height (no point beside the plane can fill it), each through
`slice | smooth | fitspline | camber`, the max thickness against the truth and its flags.

Usage: scripts/validate_thickness_hole.py [--bin DIR] [--kinds turbine,compressor,thick-root]
           [--heights 10,25,50] [--seeds 5,7] [--holes 1.5,2.5,3,3.5,4.5] [--spacing 0.08]

Prints a line per case and, per hole size, the thickness errors over 5 um, those flagged
by thickness_measured, and those off with no flag covering max_thickness (docs/FORMAT.md).
Then the thickness stations (table thickness) of the same runs, apart those beside the
hole (a contact within its radius and half the 5 % chord limit of its centre) and the
others: each against the same station of the scan without the hole (the stations have no
exact truth: what the hole moved it by, and elsewhere what removing points moves a run by),
those moved by over 5 um, those whose row's flags hold thickness_measured, and those moved
with no flag in their row. Exits 1 when a max thickness is off, or a station beside the
hole moved, with no flag.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

from check_bits import check_bits, flagged_by
from stream_tables import table

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOLERANCE = 0.005  # mm: the max thickness target (docs/ACCURACY.md)


def run(cmd, env):
    return subprocess.run(cmd, shell=True, env=env, capture_output=True, text=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "tools"))
    ap.add_argument("--kinds", default="turbine,compressor,thick-root")
    ap.add_argument("--heights", default="10,25,50")
    ap.add_argument("--seeds", default="5,7")
    ap.add_argument("--holes", default="1.5,2.5,3,3.5,4.5")
    ap.add_argument("--spacing", type=float, default=0.08)
    a = ap.parse_args()
    lib = os.path.join(os.path.dirname(os.path.abspath(a.bin)), "libsection")
    env = dict(os.environ, LD_LIBRARY_PATH=f"{lib}:{lib}/extras:" + os.environ.get("LD_LIBRARY_PATH", ""))
    t = a.bin
    pipe = f"{t}/smooth | {t}/fitspline | {t}/camber"
    bits = check_bits()
    holes = [float(x) for x in a.holes.split(",")]
    tally = {h: [0, 0, 0, 0, 0] for h in holes}  # cases, off, flagged by thickness_measured, silent, refused
    # stations beside the hole (True) and elsewhere: count, moved, flagged by thickness_measured, moved silent
    moved = {(h, near): [0, 0, 0, 0] for h in holes for near in (True, False)}
    measured_bit = next(b for b, (name, _) in bits.items() if name == "thickness_measured")
    with tempfile.TemporaryDirectory() as work:
        for kind in a.kinds.split(","):
            for z in [float(x) for x in a.heights.split(",")]:
                for seed in [int(x) for x in a.seeds.split(",")]:
                    scan, truth = f"{work}/scan.xyz", f"{work}/truth.csv"
                    r = run(f"{t}/bladegen --kind {kind} --points --spacing {a.spacing} --noise 0.005 "
                            f"--seed {seed} --z-min {z - 4} --z-max {z + 4} -o {scan} --truth {truth} --at {z}",
                            env)
                    if r.returncode:
                        sys.exit(f"bladegen failed: {r.stderr}")
                    true_thickness = float(next(csv.DictReader(open(truth)))["max_thickness"])
                    r = run(f"{t}/slice {scan} --at {z} | {pipe} > {work}/whole.csv", env)
                    whole = f"{work}/whole.csv"
                    frame = table(whole, "frames")[0]
                    at = table(whole, "params")[0]["max_thickness_pos"]
                    station = min(table(whole, "thickness"), key=lambda s: abs(s["fraction"] - at))
                    origin = (frame["origin_x"], frame["origin_y"])
                    u = (frame["u_x"], frame["u_y"])
                    v = (frame["v_x"], frame["v_y"])
                    points = [line.split() for line in open(scan)]
                    for side in ("pressure", "suction"):
                        cu, cv = station[side + "_u"], station[side + "_v"]
                        cx = origin[0] + cu * u[0] + cv * v[0]
                        cy = origin[1] + cu * u[1] + cv * v[1]
                        for hole in holes:
                            with open(f"{work}/holed.xyz", "w") as f:
                                for p in points:
                                    if (float(p[0]) - cx) ** 2 + (float(p[1]) - cy) ** 2 >= (hole / 2) ** 2:
                                        f.write(" ".join(p) + "\n")
                            run(f"{t}/slice {work}/holed.xyz --at {z} | {pipe} > {work}/holed.csv", env)
                            tally[hole][0] += 1
                            rows = table(f"{work}/holed.csv", "params")
                            if not rows:
                                tally[hole][4] += 1
                                print(f"{kind:10s} z {z:4.0f} seed {seed} {side:8s} hole {hole} mm: refused")
                                continue
                            row = rows[0]
                            beside = hole / 2 + 0.025 * row["chord"]
                            for before, after in zip(table(whole, "thickness"), table(f"{work}/holed.csv", "thickness")):
                                near = min(math.hypot(after[c + "_u"] - cu, after[c + "_v"] - cv)
                                           for c in ("pressure", "suction")) <= beside
                                shift = abs(after["thickness"] - before["thickness"]) > TOLERANCE
                                silent = shift and not int(after["flags"])
                                tallied = moved[(hole, near)]
                                tallied[0] += 1
                                tallied[1] += shift
                                tallied[2] += bool(int(after["flags"]) & measured_bit)
                                tallied[3] += silent
                                if silent:
                                    print(f"{kind:10s} z {z:4.0f} seed {seed} {side:8s} hole {hole} mm: station "
                                          f"{after['fraction']:.2f} {'beside the hole' if near else 'elsewhere'} "
                                          f"moved {(after['thickness'] - before['thickness']) * 1e3:+6.1f} um, no flag")
                            names = flagged_by(row["flags"], "max_thickness", bits)
                            error = row["max_thickness"] - true_thickness
                            off = abs(error) > TOLERANCE
                            tally[hole][1] += off
                            tally[hole][2] += "thickness_measured" in names
                            tally[hole][3] += off and not names
                            print(f"{kind:10s} z {z:4.0f} seed {seed} {side:8s} hole {hole} mm: max thickness "
                                  f"{error * 1e3:+6.1f} um, flagged by {','.join(names) or '-'}", flush=True)
    print("hole mm  cases  off>5um  thickness_measured  off-unflagged  refused")
    for hole in holes:
        n, off, measured, silent, refused = tally[hole]
        print(f"{hole:7.1f} {n:6d} {off:8d} {measured:19d} {silent:14d} {refused:8d}")
    print("stations   hole mm  stations  moved>5um  thickness_measured  moved-unflagged")
    for near in (True, False):
        for hole in holes:
            n, shifted, measured, silent = moved[(hole, near)]
            where = "beside" if near else "elsewhere"
            print(f"{where:9s} {hole:7.1f} {n:9d} {shifted:10d} {measured:19d} {silent:16d}")
    # Holes under the limit are bridged by design (docs/CAMBER.md): not counted against it.
    limit_holes = [h for h in holes if h >= 2.5]
    beside_silent = any(moved[(h, True)][3] for h in limit_holes)
    return 1 if any(x[3] for x in tally.values()) or beside_silent else 0


if __name__ == "__main__":
    sys.exit(main())
