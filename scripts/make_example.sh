#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates the bundled example blade and its ground truth with bladegen:
#   data/example_blade.ply  noisy turbine scan, z 10..30 (binary little-endian PLY)
#   data/example_truth.csv  exact section parameters at z = 12, 20, 28
# Usage: scripts/make_example.sh [BLADEGEN]   (default: build/tools/bladegen)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bladegen="${1:-$here/build/tools/bladegen}"
"$bladegen" --kind turbine --points --spacing 0.08 --z-min 10 --z-max 30 \
  --noise 0.005 --holes 6 --density-min 0.25 --misregistration 0.015 --outliers 0.0002 \
  --seed 1 -o "$here/data/example_blade.ply" \
  --truth "$here/data/example_truth.csv" --at 12,20,28
ls -l "$here/data/example_blade.ply" "$here/data/example_truth.csv"
