#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The edge radii of the T-Blade3 rotor's thin sections (../shared/data/real, not part of
the repository) measured from noisy points, against the same tool's radii of the exact
points: how many are off their tolerance (LE 3 %, TE 10 %) with no flag covering them.

Sections 8-19 (0.6-1.5 mm thick, TE radii 10-200 um), each projected onto its
least-squares plane (240 points, dense at the edges), Gaussian noise of 0.5, 1 and 2 um
added to x and y, 4 seeds each: 144 noisy profiles, measured as plain profiles
(`camber PROFILE`) or through the pipe (`slice PROFILE | smooth | fitspline | camber`).
A value counts as flagged when its row's `flags` hold a check whose columns list it
(docs/FORMAT.md's table; `noise` and the whole-row checks too).

Usage: scripts/validate_tblade3_noise.py [--bin DIR] [--route plain|pipe] [--data DIR]
Prints the unflagged values off their tolerance (each with its section, noise, seed and
standard error) and how many values within it are flagged.
"""
import argparse, os, re, subprocess, sys, tempfile

import numpy as np

from stream_tables import table

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--bin", default=os.path.join(here, "..", "build", "tools"))
ap.add_argument("--route", choices=("plain", "pipe"), default="plain")
ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data", "real", "tblade3-case7-28-8"))
args = ap.parse_args()
blade_file = os.path.join(args.data, "blade3d.Case7-28-8.dat")
if not os.path.exists(blade_file):
    sys.exit(f"validate_tblade3_noise: need {blade_file}")
data = np.loadtxt(blade_file, skiprows=1)
per_section = 241
tolerance = {"le_radius": 0.03, "te_radius": 0.10}


def covering_bits():
    """The flag bits whose checks flag each radius (docs/FORMAT.md's table of bits)."""
    text = open(os.path.join(here, "..", "docs", "FORMAT.md")).read()
    cover = {c: 0 for c in tolerance}
    for m in re.finditer(r"^  \| (\d+) \| (\d+) \| ([^|]*)\| ([^|]*)\|", text, re.M):
        value, check, columns = int(m.group(2)), m.group(3).strip(), m.group(4).strip()
        for c in cover:
            edge = c[:2]
            if (c in columns or columns.startswith("every") or check.startswith(f"{edge}_circle")
                    or check.startswith(f"{edge}_radius") or check.startswith("noise")):
                cover[c] |= value
    return cover


def measure(points, tmp, tag):
    profile, out = os.path.join(tmp, f"{tag}.txt"), os.path.join(tmp, f"{tag}.csv")
    np.savetxt(profile, points, fmt="%.9f")
    b = args.bin
    if args.route == "plain":
        p = subprocess.run([f"{b}/camber", profile, "-o", out], capture_output=True, text=True)
    else:
        p = subprocess.run(f"'{b}/slice' '{profile}' | '{b}/smooth' | '{b}/fitspline' | '{b}/camber' -o '{out}'",
                           shell=True, capture_output=True, text=True)
    return table(out, "params")[0] if p.returncode == 0 else None


def main():
    cover = covering_bits()
    off, flagged_right, inputs, refused = [], {c: 0 for c in tolerance}, 0, 0
    with tempfile.TemporaryDirectory() as tmp:
        for s in range(8, 20):
            sec = data[s * per_section:(s + 1) * per_section]
            centre = sec.mean(0)
            e1, e2, _ = np.linalg.svd(sec - centre)[2]
            pts = np.c_[(sec - centre) @ e1, (sec - centre) @ e2]
            if np.allclose(pts[0], pts[-1]):
                pts = pts[:-1]
            ref = measure(pts, tmp, f"exact{s}")
            if ref is None:
                print(f"section {s}: the exact profile was refused")
                continue
            for noise in (0.0005, 0.001, 0.002):
                for seed in range(1, 5):
                    rng = np.random.default_rng(seed * 1000 + s)
                    inputs += 1
                    par = measure(pts + rng.normal(0, noise, pts.shape), tmp, "noisy")
                    if par is None:
                        refused += 1
                        continue
                    flags = int(par["flags"])
                    for c, limit in tolerance.items():
                        rel = abs(par[c] - ref[c]) / ref[c] if ref[c] > 0 else 0
                        flagged = bool(flags & cover[c])
                        if rel > limit and not flagged:
                            off.append((s, noise, seed, c, ref[c], par[c], rel, par[c + "_sigma"]))
                        elif rel <= limit and flagged:
                            flagged_right[c] += 1
    print(f"{args.route}: {inputs} noisy profiles ({refused} refused); values off their tolerance with no flag: "
          f"{len(off)}; values within it but flagged: " +
          ", ".join(f"{c} {n}" for c, n in flagged_right.items()))
    for s, noise, seed, c, r0, r, rel, sigma in off:
        print(f"  section {s} noise {noise * 1e3:.1f} um seed {seed}: {c} {r * 1e3:.1f} um against {r0 * 1e3:.1f} "
              f"({rel * 100:+.1f} %), standard error {sigma * 1e3:.2f} um")


main()
