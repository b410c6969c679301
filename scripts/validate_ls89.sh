#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs the camber tool on the VKI LS89 vane section (../shared/data/real/ls89, not part of
# the repository) and prints our parameters next to the published reference values
# (Mueller and Verstraete 2016, Table 1; see /work/shared/data/real/README.md).
# Usage: scripts/validate_ls89.sh [camber binary] [data file]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
camber="${1:-${SECTION_BIN:-$here/../build/tools}/camber}"
data="${2:-$here/../../shared/data/real/ls89/point_cloud_LS89.txt}"
[ -x "$camber" ] || { echo "validate_ls89: no camber binary at $camber" >&2; exit 2; }
[ -r "$data" ] || { echo "validate_ls89: cannot read $data" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# Columns: id span y x (metres). Points 1-206 run LE -> TE on one side, 207-405 LE -> TE
# on the other: one closed loop = first side forward, second side backward without its
# repeated LE and TE points; x, y in mm.
awk 'NF >= 4 && $1 <= 206 { printf "%.6f %.6f\n", $4 * 1000, $3 * 1000 }' "$data" > "$tmp/profile.txt"
awk 'NF >= 4 && $1 > 207 && $1 < 405 { printf "%.6f %.6f\n", $4 * 1000, $3 * 1000 }' "$data" | tac >> "$tmp/profile.txt"

"$camber" "$tmp/profile.txt" --params "$tmp/params.csv" -o "$tmp/stream.txt"

awk -F, '
NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
NR == 2 {
  v = "%-26s %12s %12s\n"; w = "%-26s %12.3f %12s\n"
  printf v, "parameter (mm, deg)", "ours", "reference"
  printf w, "caliper chord", $col["caliper_chord"], "67.647"
  printf w, "caliper stagger", $col["caliper_stagger"], "55 (abs)"
  printf w, "chord (LE-TE points)", $col["chord"], "-"
  printf w, "stagger (LE-TE points)", $col["stagger"], "-"
  printf w, "LE radius (fitted)", $col["le_radius"], "4.127"
  printf w, "LE curvature radius", $col["le_curvature_radius"], "-"
  printf w, "TE radius (fitted)", $col["te_radius"], "0.710"
  printf w, "TE curvature radius", $col["te_curvature_radius"], "-"
  printf w, "TE centre x", $col["te_center_u"], "36.245"
  printf w, "TE centre y", $col["te_center_v"], "-51.620"
  printf w, "max thickness", $col["max_thickness"], "-"
  printf w, "inlet angle", $col["inlet_angle"], "-"
  printf w, "outlet angle", $col["outlet_angle"], "-"
  printf w, "area", $col["area"], "-"
}' "$tmp/params.csv"
