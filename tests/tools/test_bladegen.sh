#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box test of bladegen: help, usage errors, a small scan, a mesh and a truth table.
source "$(dirname "$0")/lib.sh"
G="$BIN/bladegen"

expect 0 "--help" -- "$G" --help
check "--help documents the truth columns" -- grep -q "max_thickness_pos" "$TMP/out"
expect 2 "a bad flag" -- "$G" --bogus
expect 2 "no output" -- "$G" --points
expect 2 "a bad kind" -- "$G" --kind fan --points -o "$TMP/x.ply"
expect 2 "--truth without --at" -- "$G" --truth "$TMP/t.csv"
expect 1 "a z range outside the span" -- "$G" --points --z-min 50 --z-max 70 -o "$TMP/x.xyz"
expect 1 "--at outside the span" -- "$G" --truth "$TMP/t.csv" --at 80

# A small noisy scan, twice with the same seed: identical files.
args=(--kind compressor --points --spacing 0.2 --z-min 10 --z-max 12 --noise 0.005 --holes 2
      --density-min 0.5 --misregistration 0.01 --outliers 0.001 --seed 3)
expect 0 "a small scan" -- "$G" "${args[@]}" -o "$TMP/a.xyz"
expect 0 "the same scan again" -- "$G" "${args[@]}" -o "$TMP/b.xyz"
check "same seed, same points" -- cmp -s "$TMP/a.xyz" "$TMP/b.xyz"
check "the scan has points" -- test "$(wc -l < "$TMP/a.xyz")" -gt 1000
check "every row has three numbers" -- awk 'NF != 3 { exit 1 }' "$TMP/a.xyz"
expect 0 "binary PLY" -- "$G" "${args[@]}" -o "$TMP/a.ply"
check "PLY header" -- grep -aq "format binary_little_endian" "$TMP/a.ply"

expect 0 "a mesh" -- "$G" --mesh --profile-points 100 --layers 5 -o "$TMP/m.stl"
check "the mesh file is written" -- test -s "$TMP/m.stl"

expect 0 "truth" -- "$G" --kind turbine --truth "$TMP/t.csv" --at 12,20,28
check "truth: header and three rows of 22 columns" -- \
  awk -F, 'NR == 1 && $1 != "z" { exit 1 } NF != 22 { exit 1 } END { exit NR != 4 }' "$TMP/t.csv"
check "truth: turbine chord about 40 mm" -- awk -F, 'NR > 1 && ($2 < 38 || $2 > 43) { exit 1 }' "$TMP/t.csv"

# The data kinds (issue 21): presets, grids, rows, units.
expect 0 "sharp-te truth" -- "$G" --kind sharp-te --truth "$TMP/s.csv" --at 10,50
check "sharp-te: TE radius 0" -- awk -F, 'NR > 1 && $10 != 0 { exit 1 }' "$TMP/s.csv"
expect 0 "a chordwise grid" -- "$G" --grid chordwise --lines 10 --line-points 20 -o "$TMP/g.xyz"
check "grid: 10 lines of 20 points" -- test "$(wc -l < "$TMP/g.xyz")" -eq 200
check "grid: a chordwise line at one height" -- awk 'NR <= 20 && $3 != 0 { exit 1 }' "$TMP/g.xyz"
expect 0 "rows in mm" -- "$G" --kind compressor --rows 3 --row-pitch 15 -o "$TMP/r.xyz" --truth "$TMP/r.csv"
check "rows: the truth at the 3 rows' heights without --at" -- \
  awk -F, 'NR == 2 && $1 != 15 { exit 1 } END { exit NR != 4 }' "$TMP/r.csv"
expect 0 "the same rows in metres" -- "$G" --kind compressor --rows 3 --row-pitch 15 --units m -o "$TMP/rm.xyz"
check "metres: every coordinate 1/1000 of the mm one" -- \
  awk 'NR == FNR { x[FNR] = $1; z[FNR] = $3; next }
       { if (($1 * 1000 - x[FNR])^2 > 1e-18 || ($3 * 1000 - z[FNR])^2 > 1e-18) exit 1 }' "$TMP/r.xyz" "$TMP/rm.xyz"
expect 2 "--holes with --grid" -- "$G" --grid spanwise --holes 3 -o "$TMP/x.xyz"
expect 2 "--row-pitch without --rows" -- "$G" --points --row-pitch 10 -o "$TMP/x.xyz"
expect 2 "two outputs at once" -- "$G" --points --rows 3 -o "$TMP/x.xyz"
expect 2 "a bad unit" -- "$G" --points --units furlong -o "$TMP/x.xyz"
expect 1 "rows beyond the span" -- "$G" --rows 8 --row-pitch 10 -o "$TMP/x.xyz"
check "the error says why" -- grep -q "outside the span" "$TMP/err"
finish
