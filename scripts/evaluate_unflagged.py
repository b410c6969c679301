#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The values bench/evaluate_pipeline prints off their targets with no flag covering them,
counted per value: a value counts as flagged only when a check in its row's `flags:` list
flags its column (section/checks.h's check_names, as checks_flagging reads them: units,
registration and airfoil every column; le_choice every column that depends on the LE).

Targets as evaluate_pipeline states them: camber line max 15 um, chord 10 um, max thickness
5 um, LE radius 3 %, TE radius 10 %, inlet and outlet angles 0.5 deg. Also prints, per
value, the median |error| / sigma of the rows flagged by no check but the *_noise ones
(the columns `sigma C T I O` the rows carry: a normal error gives 0.67).

Usage:
  build/bench/evaluate_pipeline --seeds 81 --preset both > run.txt
  python3 scripts/evaluate_unflagged.py run.txt [more runs]
"""
import statistics
import sys

from check_bits import check_bits

# Each check's columns (None: every one), read from checks.h as the validation scripts read them.
columns = {name: cols for name, cols in check_bits().values()}
either_end = "chord camber_length max_thickness area caliper_chord centroid wall".split()
# The printed column (0-based field), its target, the params column it stands for.
targets = {"camber line": (8, 15, "camber_line"), "chord": (9, 10, "chord"), "max thickness": (10, 5, "max_thickness"),
           "LE radius": (11, 3, "le_radius"), "TE radius": (12, 10, "te_radius"),
           "inlet angle": (13, 0.5, "inlet_angle"), "outlet angle": (14, 0.5, "outlet_angle")}
sigma_of = {"chord": (9, 0, 1e-3), "max thickness": (10, 1, 1e-3), "inlet angle": (13, 2, 1), "outlet angle": (14, 3, 1)}


def covers(check, column):
    if check == "le_choice":  # "every column that depends on which end is the LE"
        return column not in either_end
    cols = columns.get(check, set())
    return cols is None or column in cols


for path in sys.argv[1:]:
    off, z, rows = {}, {}, 0
    for line in open(path):
        f = line.split()
        if len(f) < 16 or f[0] not in ("turbine", "compressor") or not f[1].isdigit():
            continue
        if f[4] == "FIT" or f[7] == "CAMBER":
            continue
        rows += 1
        flags = line.split("flags:")[1].split()[0].split(":") if "flags:" in line else []
        for name, (k, limit, column) in targets.items():
            if abs(float(f[k])) > limit and not any(covers(c, column) for c in flags):
                off[f"{f[0]} {name}"] = off.get(f"{f[0]} {name}", 0) + 1
        if "sigma" in f and all(c.endswith("_noise") for c in flags):
            at = f.index("sigma")
            for name, (k, s, unit) in sigma_of.items():
                sigma = float(f[at + 1 + s]) * unit
                if sigma > 0:
                    z.setdefault(f"{f[0]} {name}", []).append(abs(float(f[k])) * unit / sigma)
    print(f"{path}: {rows} sections; off target with no flag covering them: "
          + (", ".join(f"{k} {n}" for k, n in sorted(off.items())) or "none"))
    if z:
        print("  median |error| / sigma: " + ", ".join(f"{k} {statistics.median(v):.2f}" for k, v in sorted(z.items())))
