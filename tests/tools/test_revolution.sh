#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box test of slice --axis (docs/REVOLUTION.md): a generated rotor's rows at constant
# radius cut on their cylinders and measured, usage and data errors, a mesh on a cone.
source "$(dirname "$0")/lib.sh"
G="$BIN/bladegen"
S="$BIN/slice"

expect 0 "rotor rows" -- "$G" --kind compressor --rotor cylinder --rows 3 --spacing 0.05 -o "$TMP/rows.xyz" \
  --truth "$TMP/truth.csv"
expect 2 "--radius without --axis" -- "$S" "$TMP/rows.xyz" --radius 230
expect 2 "a zero axis" -- "$S" "$TMP/rows.xyz" --axis 0,0,0,0,0,0
expect 2 "--cone with three numbers" -- "$S" "$TMP/rows.xyz" --axis 0,0,0,1,0,0 --cone 1,2,3
expect 2 "--axis with --at" -- "$S" "$TMP/rows.xyz" --axis 0,0,0,1,0,0 --at 3
printf '0 200\nfoo bar\n' > "$TMP/bad.txt"
expect 1 "a bad streamline file" -- "$S" "$TMP/rows.xyz" --axis 0,0,0,1,0,0 --streamline "$TMP/bad.txt"
check "the error names the file and line" -- grep -q "bad.txt:2" "$TMP/err"
expect 1 "a cylinder between rows" -- "$S" "$TMP/rows.xyz" --axis 0,0,0,1,0,0 --radius 225
check "it names the rows beside it" -- grep -q "between the rows at r = 218 and r = 230" "$TMP/err"

# With --axis alone each row at constant radius is cut on its cylinder.
run_pipe() { "$S" "$TMP/rows.xyz" --axis 0,0,0,1,0,0 | "$BIN/smooth" | "$BIN/fitspline" | "$BIN/camber" --params "$TMP/p.csv"; }
expect 0 "the rows through the pipe" -- run_pipe
check "the frames say cylinder, cylinder unrolling" -- \
  awk -F, '/^# table frames/ { t = 1; getline; next } /^#/ { t = 0 } t && ($14 != 1 || $15 != 1) { exit 1 }' "$TMP/out"
check "the meridians table is written" -- grep -q "^# table meridians" "$TMP/out"
check "three sections, chords within 1 um of the truth" -- \
  awk -F, 'FNR == 1 { next } NR == FNR { c[FNR - 2] = $2; next } { n++; d = $2 - c[$1]; if (d < -0.001 || d > 0.001) exit 1 }
           END { exit n != 3 }' "$TMP/truth.csv" "$TMP/p.csv"

# A cone rotor's mesh, cut exactly on a cone.
expect 0 "a cone rotor mesh" -- "$G" --kind compressor --rotor cone --mesh --profile-points 200 --layers 7 \
  -o "$TMP/cone.stl"
expect 0 "the mesh on a cone" -- "$S" "$TMP/cone.stl" --axis 0,0,0,1,0,0 --cone 0,230,1,230.3639702342662 --r-ref 230
check "one section with points" -- grep -q "^0,0,0," "$TMP/out"
