#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Python API against engeom on the same sections (docs/PERFORMANCE.md, "Python API"):
# bench_compare's 5 designs x SEEDS cases (nominal, edge points, measured points moved by a
# known rigid motion with 5 um of noise); compare through libsection.compare (nominal
# prepared once, and prepared in each call) against engeom.align2.points_to_curve (plain
# least squares and its robust default: compare_peer.py), camber through libsection.camber
# against engeom's AfGeometry.from_geometric_analysis (compare_peer.py too). Prints
# bench_compare's score table (the Python fit must match ours: same move, rms, max) and
# the CPU ms per section of each, with the ratios.
# Usage: scripts/peers/python_speed.sh [BUILD_DIR] [SEEDS]   (default build, 3 seeds)
# Ours runs in Debian's python3 with the module of BUILD_DIR/python (configure with
# -DSECTION_BUILD_PYTHON=ON); engeom in its virtual environment (ENGEOM_VENV, default
# ~/.cache/libsection-engeom, made on the first run: scripts/peers/engeom_venv.sh).
set -euo pipefail
here="$(cd "$(dirname "$0")/../.." && pwd)"
build="$(cd "${1:-$here/build}" && pwd)"
seeds="${2:-3}"
python="${PYTHON:-$(command -v /usr/bin/python3 || command -v python3)}"
[ -d "$build/python/libsection" ] || { echo "python_speed: no module in $build/python (-DSECTION_BUILD_PYTHON=ON)" >&2; exit 2; }
engeom="$(bash "$here/scripts/peers/engeom_venv.sh")"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
"$build/bench/bench_compare" --export "$dir" --seeds "$seeds" > /dev/null
PYTHONPATH="$build/python" "$python" "$here/scripts/peers/python_api.py" "$dir" > /dev/null
"$engeom" "$here/scripts/peers/compare_peer.py" "$dir" > /dev/null
"$build/bench/bench_compare" --score "$dir" --seeds "$seeds" | sed -n '/^median/,$p'
echo
"$python" "$here/scripts/peers/python_api.py" --summary "$dir"
