#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# compare against engeom's 2D alignment (docs/ACCURACY.md, docs/PERFORMANCE.md): the same
# generated sections, moved by known rigid motions with 5 um of noise, fitted by
# `compare_section` (least squares, minimum zone) and by engeom.align2.points_to_curve
# (plain least squares, and its default robust fit); each scored by how far it leaves the
# true move, the exact distances of the fitted points to the true profile, and the CPU
# time per section.
# Usage: scripts/compare_engeom.sh [BUILD_DIR] [SEEDS]   (default build, 3 seeds)
# engeom and numpy are installed from PyPI into a virtual environment (ENGEOM_VENV, default
# ~/.cache/libsection-engeom) on the first run.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
seeds="${2:-3}"
engeom="$(bash "$here/scripts/peers/engeom_venv.sh")"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
"$build/bench/bench_compare" --export "$dir" --seeds "$seeds" > /dev/null
"$engeom" "$here/scripts/peers/compare_peer.py" "$dir" > /dev/null
"$build/bench/bench_compare" --score "$dir" --seeds "$seeds"
