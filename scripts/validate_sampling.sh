#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs the whole pipe with default options, as a user would, on the real data of other
# projects in ../shared/data/real (not part of the repository; README there): sparse rows
# (NASA Rotor 37, 13 rows on surfaces of revolution; T-Blade3 Case7-28-8, 21 rows), single
# 2D profiles in metres, unordered (parablade Aachen_2D, Impulse_2D, STD10_2D). Prints per
# data set what slice took the points for, how many sections gave params, and per
# section: chord, max thickness, stagger, inlet and outlet angles (mm, degrees).
# This is a census of the sampling; the parablade values against references (and APU_rotor)
# are checked by scripts/validate_parablade.py.
# Usage: scripts/validate_sampling.sh [tool directory] [data directory]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-${SECTION_BIN:-$here/../build/tools}}" data="${2:-$here/../../shared/data/real}"
if [ ! -x "$bin/slice" ] || [ ! -d "$data" ]; then
  echo "validate_sampling: need the tools in $bin and the data in $data" >&2
  exit 2
fi
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT

# Rotor 37: columns J, Z [cm], R [cm], THETA1, THETA2; x = Z, y = R sin, z = R cos (mm).
awk '$1 ~ /^[0-9]+$/ && NF == 5 { z = $2 * 10; r = $3 * 10;
  printf "%.6f %.6f %.6f\n", z, r * sin($4), r * cos($4);
  if ($5 != $4) printf "%.6f %.6f %.6f\n", z, r * sin($5), r * cos($5) }' \
  "$data/rotor37/rotor37geometry.dat" > "$tmp/rotor37.xyz"
# T-Blade3: a header line `241 21`, then x y z (mm).
awk 'NR > 1' "$data/tblade3-case7-28-8/blade3d.Case7-28-8.dat" > "$tmp/tblade3.xyz"
# parablade 2D cases: `id x y` in metres, unordered: the id column stripped.
for c in Aachen_2D Impulse_2D STD10_2D; do
  f=$(ls "$data/parablade/$c"/MoveSurface*.txt)
  awk '{ print $2, $3 }' "$f" > "$tmp/$c.xy"
done

for name in rotor37.xyz tblade3.xyz Aachen_2D.xy Impulse_2D.xy STD10_2D.xy; do
  echo "== $name"
  "$bin/slice" "$tmp/$name" 2> "$tmp/slice.err" > "$tmp/slice.txt" || true
  grep "the points are" "$tmp/slice.err" | sed 's/^slice: /  /'
  "$bin/smooth" "$tmp/slice.txt" 2>/dev/null | "$bin/fitspline" 2>/dev/null |
    "$bin/camber" --params "$tmp/params.csv" > /dev/null 2> "$tmp/camber.err" || true
  sliced=$(grep -c "^# row section=" "$tmp/slice.txt" || true)
  measured=$(($(wc -l < "$tmp/params.csv") - 1))
  echo "  sections sliced: $sliced, with params: $measured"
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i;
                     printf "  %7s %9s %9s %9s %9s %9s\n", "section", "chord", "t_max", "stagger", "inlet", "outlet"; next }
           { printf "  %7d %9.3f %9.3f %9.2f %9.2f %9.2f\n", $col["section"], $col["chord"], $col["max_thickness"],
             $col["stagger"], $col["inlet_angle"], $col["outlet_angle"] }' "$tmp/params.csv"
done
