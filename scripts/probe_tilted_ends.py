# SPDX-License-Identifier: GPL-3.0-or-later
"""Tilted planes near a blade's hub and tip: a generated scan and the exact mesh of the same
blade cut by the same planes (tilted about the x or the y axis, some running off the
scanned span), the scan's values scored against the mesh's. Prints the values off their
target and whether a check flags them (SILENT: none does), the sections refused, then a
summary line. Numpy is not needed.

    python3 scripts/probe_tilted_ends.py --seeds 1,2
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from check_bits import check_bits, flagged_by, score_row  # noqa: E402

# Targets: lengths in mm, radii and the area relative, angles in degrees.
TARGETS = {"chord": ("abs", 0.010), "max_thickness": ("abs", 0.005),
           "le_radius": ("rel", 0.03), "te_radius": ("rel", 0.10), "inlet_angle": ("abs", 0.5),
           "outlet_angle": ("abs", 0.5), "stagger": ("abs", 0.5), "area": ("rel", 0.002)}


def footprint(b, kind, d):
    """The blade's x and y extent at the hub and at the tip (edge circles included), from the
    generator's truth."""
    subprocess.run([f"{b}/bladegen", "--kind", kind, "--points", "--spacing", "2", "-o", f"{d}/f.xyz", "--truth",
                    f"{d}/f.csv", "--at", "0,60"], check=True, capture_output=True)
    out = []
    for r in csv.DictReader(open(f"{d}/f.csv")):
        xs, ys = [], []
        for e in ("le", "te"):
            rad = float(r[f"{e}_radius"])
            xs += [float(r[f"{e}_center_x"]) - rad, float(r[f"{e}_center_x"]) + rad, float(r[f"{e}_x"])]
            ys += [float(r[f"{e}_center_y"]) - rad, float(r[f"{e}_center_y"]) + rad, float(r[f"{e}_y"])]
        out.append((min(xs), max(xs), min(ys), max(ys)))
    return out


def plane_z_range(z, n, box):
    """The plane's heights over a box (x0, x1, y0, y1): the plane through (0, 0, z), normal n."""
    zs = [z - (n[0] * x + n[1] * y) / n[2] for x in box[:2] for y in box[2:]]
    return min(zs), max(zs)


def params(cmd):
    run = subprocess.run(cmd, shell=True, capture_output=True, text=True)
    return {int(r["section"]): r for r in csv.DictReader(run.stdout.splitlines())}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "build", "tools"))
    ap.add_argument("--kinds", default="turbine,compressor,sharp-te")
    ap.add_argument("--seeds", default="1")
    ap.add_argument("--tilts", default="4,8", help="degrees")
    ap.add_argument("--noise", default="0.005")
    args = ap.parse_args()
    bits, b = check_bits(), args.bin
    heights = [0.5, 1.5, 3, 5, 55, 57, 58.5, 59.5]
    runs = measured = refused = silent = off = unflagged = jumped = 0
    with tempfile.TemporaryDirectory() as d:
        for kind in args.kinds.split(","):
            subprocess.run([f"{b}/bladegen", "--kind", kind, "--mesh", "--profile-points", "2000", "--layers",
                            "241", "-o", f"{d}/m.stl"], check=True, capture_output=True)
            for seed in args.seeds.split(","):
                subprocess.run([f"{b}/bladegen", "--kind", kind, "--points", "--noise", args.noise, "--seed", seed,
                                "-o", f"{d}/s.ply"], check=True, capture_output=True)
                hub, tip = footprint(b, kind, d)
                for tilt in [float(t) for t in args.tilts.split(",")]:
                    for axis in "xy":
                        a = math.radians(tilt)
                        n = (math.sin(a), 0, math.cos(a)) if axis == "y" else (0, math.sin(a), math.cos(a))
                        with open(f"{d}/p.csv", "w") as f:
                            f.write("origin_x,origin_y,origin_z,normal_x,normal_y,normal_z\n")
                            for z in heights:
                                f.write(f"0,0,{z},{n[0]},{n[1]},{n[2]}\n")
                        tail = f"| {b}/smooth | {b}/fitspline | {b}/camber --format csv --allow-partial"
                        exact = params(f"{b}/slice {d}/m.stl --planes {d}/p.csv {tail}")
                        scan = params(f"{b}/slice {d}/s.ply --planes {d}/p.csv {tail}")
                        for k, z in enumerate(heights):
                            runs += 1
                            label = f"{kind:10s} seed {seed} tilt {tilt} about {axis} z {z}"
                            if k not in scan:
                                refused += 1
                                print(f"{label}: scan refused{' (mesh too)' if k not in exact else ''}")
                                continue
                            low, high = plane_z_range(z, n, hub if z < 30 else tip)
                            if low < 0 or high > 60:
                                # The plane may leave the scanned span (the footprint's box is
                                # wider than the profile): the solid's section holds the end
                                # face's cut, the scan has no point there. The chord, which
                                # rests on both edges, must be refused or flagged.
                                off += 1
                                names = flagged_by(scan[k]["flags"], "chord", bits)
                                unflagged += not names
                                print(f"{label}: the plane runs off the span (z {low:.2f} to {high:.2f}): "
                                      f"{'flagged ' + ','.join(names) if names else 'NOT FLAGGED'}")
                                continue
                            if k not in exact:
                                print(f"{label}: mesh refused, scan measured with flags {scan[k]['flags']}")
                                continue
                            measured += 1
                            off_target = score_row(label, kind, scan[k], exact[k], TARGETS, bits, quiet=True)
                            silent += score_row(label, kind, scan[k], exact[k], TARGETS, bits)
                            jumps = [bits[v][0] for v in bits if int(float(scan[k]["flags"])) & v
                                     and bits[v][0].startswith("jump_")]
                            if jumps and not off_target:
                                jumped += 1
                                print(f"{label}: every value on target, flagged {','.join(jumps)}")
    print(f"tilted ends: {runs} sections, {refused} refused, {measured} within the span scored against "
          f"the mesh ({silent} values off with no flag, {jumped} on target flagged by a jump), {off} running off "
          f"the span measured "
          f"({unflagged} with the chord not flagged)")


if __name__ == "__main__":
    main()
