# SPDX-License-Identifier: GPL-3.0-or-later
"""slice | smooth | fitspline | camber in Python: each section's parameters of a scan.

    python3 examples/pipe.py [CLOUD] (default: the example blade; needs scripts/python.sh install)
"""
import sys

import pandas as pd

import libsection as ls

cloud = ls.read_cloud(sys.argv[1] if len(sys.argv) > 1 else "data/example_blade.ply")  # (N, 3) array, mm
sections = ls.slice(cloud, normal=(0, 0, 1), at=[12, 20, 28])  # the slice tool's flags as keywords
measured = ls.camber(ls.fit_spline(ls.smooth(sections)))
params = pd.DataFrame(measured.params).astype({"section": int})  # a row per section: mm, degrees
print(params[["section", "chord", "max_thickness", "le_radius", "te_radius", "stagger"]].to_string(index=False))
