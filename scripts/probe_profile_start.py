#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Does `camber PROFILE` measure a plain profile the same whichever point its file starts at
and whichever way it runs? A CMM writes a section from wherever its probe began; an airfoil
file from its TE; a design tool from its LE.

Generated sections (bladegen --rows: a row is a plain profile, its truth from bladegen
--truth), every kind at two point spacings, each given from 6 starts in both directions (12
runs a section); the VKI LS89 profile of scripts/validate_ls89.sh (all its points, and every
other one) too when --ls89 (default ../shared/data/real/ls89) is there. Prints, per value,
the widest spread over a section's 12 runs, the values off their target (docs/ACCURACY.md)
with no flag in their row, and the runs the start check (le_start, te_start) flags.

Usage: scripts/probe_profile_start.py [--bin DIR] [--seed N] [--ls89 FILE]
"""
import argparse, csv, os, subprocess, sys, tempfile

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--bin", default=os.path.join(here, "..", "build", "tools"))
ap.add_argument("--seed", default="7", help="bladegen's noise seed")
ap.add_argument("--ls89", default=os.path.join(here, "..", "..", "shared", "data", "real", "ls89",
                                               "point_cloud_LS89.txt"))
args = ap.parse_args()
KEYS = ["chord", "max_thickness", "le_radius", "te_radius", "inlet_angle", "outlet_angle"]
# Targets: mm, mm, fraction, fraction, deg, deg.
TARGET = {"chord": 0.010, "max_thickness": 0.005, "le_radius": 0.03, "te_radius": 0.10,
          "inlet_angle": 0.5, "outlet_angle": 0.5}


def camber(points, tmp):
    path = os.path.join(tmp, "p.txt")
    with open(path, "w") as f:
        f.writelines(f"{x:.6f} {y:.6f}\n" for x, y in points)
    params = os.path.join(tmp, "params.csv")
    if os.path.exists(params):
        os.remove(params)
    subprocess.run([os.path.join(args.bin, "camber"), path, "--params", params, "-o", os.devnull],
                   capture_output=True, text=True)
    rows = list(csv.DictReader(open(params))) if os.path.exists(params) else []
    return rows[0] if rows and rows[0].get("chord") else None


def off(key, value, truth):
    d = abs(value - truth)
    if key.endswith("radius"):  # a sharp edge's radius 0: off when reported round
        return d > TARGET[key] * truth if truth > 0 else d > 0.005
    return d > TARGET[key]


def study(name, points, truth, tmp, totals):
    runs = []
    n = len(points)
    for reverse in (False, True):
        p = points[::-1] if reverse else points
        for j in range(6):
            k = j * n // 6
            runs.append(camber(p[k:] + p[:k], tmp))
    got = [r for r in runs if r]
    spread = {k: max(float(r[k]) for r in got) - min(float(r[k]) for r in got) for k in KEYS} if got else {}
    silent = 0
    start_bits = (1 << 35) | (1 << 36)  # le_start, te_start
    for r in got:
        flags = int(float(r["flags"]))
        wrong = sum(off(k, float(r[k]), truth[k]) for k in KEYS if k in truth) if truth else 0
        if flags == 0:
            silent += wrong
        totals["start"] += bool(flags & start_bits)
        totals["start only"] += bool(flags & start_bits) and not flags & ~start_bits
        totals["caught by start"] += wrong if flags & start_bits and not flags & ~start_bits else 0
    totals["sections"] += 1
    totals["refused"] += len(runs) - len(got)
    totals["silent"] += silent
    for k, v in spread.items():
        totals["spread"][k] = max(totals["spread"].get(k, 0), v)
    print(f"{name:34s} {len(got):2d}/12 measured, spread: " +
          " ".join(f"{k} {spread[k]:.4f}" for k in KEYS if k in spread) + f"; off with no flag: {silent}")


def rows_of(kind, spacing, tmp):
    xyz, truth_csv = os.path.join(tmp, "rows.xyz"), os.path.join(tmp, "truth.csv")
    heights = [8, 22, 36, 50]
    subprocess.run([os.path.join(args.bin, "bladegen"), "--kind", kind, "--rows", "4", "--row-pitch", "14",
                    "--first-row", "8", "--spacing", str(spacing), "--noise", "0.002", "--seed", args.seed, "-o", xyz],
                   check=True, capture_output=True)
    subprocess.run([os.path.join(args.bin, "bladegen"), "--kind", kind, "--truth", truth_csv, "--at",
                    ",".join(map(str, heights))], check=True, capture_output=True)
    rows = {}
    for line in open(xyz):
        x, y, z = map(float, line.split())
        rows.setdefault(round(z, 6), []).append((x, y))
    truth = {round(float(r["z"]), 6): {k: float(r[k]) for k in KEYS} for r in csv.DictReader(open(truth_csv))}
    return [(z, rows[z], truth[z]) for z in sorted(rows)]


totals = {"sections": 0, "refused": 0, "silent": 0, "spread": {}, "start": 0, "start only": 0, "caught by start": 0}
with tempfile.TemporaryDirectory() as tmp:
    for kind in ("turbine", "compressor", "sharp-te", "impulse", "thick-root"):
        for spacing in (0.2, 0.4):
            for z, points, truth in rows_of(kind, spacing, tmp):
                if kind == "impulse":  # symmetric: its LE is a near tie (le_choice), the angles swap
                    truth = {k: v for k, v in truth.items() if not k.endswith("angle")}
                study(f"{kind} z {z:g}, {spacing} mm", points, truth, tmp, totals)
    if os.path.exists(args.ls89):
        # Columns: id span y x (m); points 1-206 one side LE -> TE, 207-405 the other.
        data = [l.split() for l in open(args.ls89) if len(l.split()) >= 4]
        first = [(float(r[3]) * 1000, float(r[2]) * 1000) for r in data if float(r[0]) <= 206]
        second = [(float(r[3]) * 1000, float(r[2]) * 1000) for r in data if 207 < float(r[0]) < 405]
        loop = first + second[::-1]
        study("LS89, 403 points", loop, None, tmp, totals)
        study("LS89, every other point", loop[::2], None, tmp, totals)
print(f"{totals['sections']} sections, {12 * totals['sections']} runs: {totals['refused']} refused, "
      f"{totals['silent']} values off with no flag; widest spread: " +
      " ".join(f"{k} {v:.4f}" for k, v in totals["spread"].items()))
print(f"runs flagged le_start or te_start: {totals['start']}, by nothing else: {totals['start only']} "
      f"(values off in those: {totals['caught by start']})")
