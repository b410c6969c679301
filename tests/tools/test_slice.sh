#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the slice tool.
source "$(dirname "$0")/lib.sh"

expect 0 "help" -- "$BIN/slice" --help
check "help names the options" -- grep -q -- "--normal" "$TMP/out"
expect 0 "version" -- "$BIN/slice" --version
expect 2 "bad flag" -- "$BIN/slice" --no-such-flag x.xyz
expect 2 "rows and planes" -- "$BIN/slice" x.xyz --rows --at 1
expect 2 "bad normal" -- "$BIN/slice" x.xyz --normal 0,1 --at 1
expect 1 "missing file" -- "$BIN/slice" "$TMP/none.xyz" --at 1
check "missing file named" -- grep -q "none.xyz" "$TMP/err"
check "no partial output" -- test ! -s "$TMP/out"
expect 2 "fill gap not positive" -- "$BIN/slice" x.xyz --at 1 --fill-gap 0
check "says what a fill gap must be" -- grep -q -- "--fill-gap: must be a number above 0, got '0'" "$TMP/err"

printf '0 0 0\n1 2 abc\n' > "$TMP/bad.xyz"
expect 1 "malformed row" -- "$BIN/slice" "$TMP/bad.xyz" --at 0
check "malformed row names file and line" -- grep -q "bad.xyz:2" "$TMP/err"
check "no partial output on bad row" -- test ! -s "$TMP/out"
: > "$TMP/empty.xyz"
expect 1 "empty file" -- "$BIN/slice" "$TMP/empty.xyz" --at 0
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\nproperty float y\nproperty float z\nend_header\n' > "$TMP/trunc.ply"
expect 1 "truncated ply" -- "$BIN/slice" "$TMP/trunc.ply" --at 0
check "truncated named" -- grep -q "trunc.ply" "$TMP/err"

# A ring of points: one loop, read from a file and from stdin alike.
awk 'BEGIN { for (z = -0.2; z <= 0.2; z += 0.05) for (i = 0; i < 400; i++) { a = 6.283185307179586 * i / 400; printf "%.9f %.9f %.3f\n", 10*cos(a), 5*sin(a), z } }' > "$TMP/ring.xyz"
expect 0 "ring from a file" -- "$BIN/slice" "$TMP/ring.xyz" --at 0,5 --slab 0.1
check "stream header" -- grep -q "^# libsection-stream 1" "$TMP/out"
check "points table" -- grep -q "^# table points" "$TMP/out"
check "missed plane reported as an issue" -- grep -q "^# issue section=1" "$TMP/out"
check "missed plane warned" -- grep -q "section 1" "$TMP/err"
cp "$TMP/out" "$TMP/from_file.csv"
# A ring leaning 0.2 mm per mm of height, with a hole across the plane: the slab's gap is
# filled from the rows above and below.
awk 'BEGIN { for (z = -0.6; z <= 0.6; z += 0.05) for (i = 0; i < 1200; i++) { a = 6.283185307179586 * i / 1200; if (a > 1 && a < 1.2 && z > -0.3 && z < 0.3) continue; printf "%.9f %.9f %.3f\n", 10*cos(a), 5*sin(a) + 0.2*z, z } }' > "$TMP/holed.xyz"
expect 0 "holed ring" -- "$BIN/slice" "$TMP/holed.xyz" --at 0 --slab 0.05
check "gap filled and noted" -- grep -q "^# fill section=0 gaps=1 filled=1" "$TMP/out"
# One row in the slab (24 points per mm): dense enough for the default band spacing
# (0.03 mm); at 0.02 mm the band takes the rows at +-0.05 too.
check "no band at the default spacing" -- sh -c "! grep -q '^# band' '$TMP/out'"
expect 0 "holed ring, band every 0.02 mm" -- "$BIN/slice" "$TMP/holed.xyz" --at 0 --slab 0.05 --band-spacing 0.02
check "band of three rows noted" -- grep -q "^# band section=0 half_width=0.05[0-9]* points=34[0-9][0-9] slab_points=11[0-9][0-9]" "$TMP/out"
expect 0 "holed ring, slab alone" -- "$BIN/slice" "$TMP/holed.xyz" --at 0 --slab 0.05 --band-spacing 0
check "no band note without a band" -- sh -c "! grep -q '^# band' '$TMP/out'"
expect 2 "band max below half a slab" -- "$BIN/slice" "$TMP/holed.xyz" --at 0 --band-max 0.2
expect 2 "negative band spacing" -- "$BIN/slice" "$TMP/holed.xyz" --at 0 --band-spacing -1
expect 2 "negative sparse band width" -- "$BIN/slice" "$TMP/holed.xyz" --at 0 --band-sparse-max -1
# Beside the hole's ends the slab is sparse: --band-sparse-max reaches farther there only.
expect 0 "holed ring, band widened beside sparse stretches" -- "$BIN/slice" "$TMP/holed.xyz" --at 0 --slab 0.05 --band-spacing 0.02 --band-sparse-max 4
check "wider band noted" -- grep -q "^# band section=0 half_width=0.05[0-9]* points=35[0-9][0-9] slab_points=11[0-9][0-9]" "$TMP/out"
expect 0 "holed ring, no fill" -- "$BIN/slice" "$TMP/holed.xyz" --at 0 --slab 0.05 --no-fill
check "no fill note without filling" -- sh -c "! grep -q '^# fill' '$TMP/out'"
"$BIN/slice" --at 0,5 --slab 0.1 < "$TMP/ring.xyz" > "$TMP/from_stdin.csv" 2>/dev/null
check "stdin gives the same rows" -- cmp -s <(grep -v '^# history' "$TMP/from_file.csv") <(grep -v '^# history' "$TMP/from_stdin.csv")
expect 1 "all planes miss" -- "$BIN/slice" "$TMP/ring.xyz" --at 50 --slab 0.1
check "nothing on stdout when all fail" -- test ! -s "$TMP/out"

# What the points are (docs/SAMPLING.md). A 2D profile (two columns, any extension, in
# any order) is one section at z = 0 with no plane flags, through the whole pipe.
awk 'BEGIN { print "# an ellipse"; for (i = 0; i < 300; i++) { a = 6.283185307179586 * ((i * 7) % 300) / 300; printf "%.9f %.9f\n", 20*cos(a), 3*sin(a) } }' > "$TMP/profile.xy"
expect 0 "a 2D profile needs no planes" -- "$BIN/slice" "$TMP/profile.xy"
check "one row, one section" -- grep -q "^# row section=0 row=0 height=0 spread=0 points=300" "$TMP/out"
check "the sampling noted" -- grep -q "^# sampling kind=rows .* rows=1 " "$TMP/out"
check "said on stderr" -- grep -q "one row of points, a single section" "$TMP/err"
"$BIN/slice" "$TMP/profile.xy" 2>/dev/null | "$BIN/smooth" 2>/dev/null | "$BIN/fitspline" 2>/dev/null |
  "$BIN/camber" --params "$TMP/profile.csv" >/dev/null 2>&1
check "the pipe measures the profile: chord 40" -- awk -F, 'NR == 2 { exit !($2 > 39.99 && $2 < 40.01) }' "$TMP/profile.csv"
"$BIN/slice" < "$TMP/profile.xy" > "$TMP/profile_stdin.txt" 2>/dev/null
check "a 2D profile on stdin too" -- grep -q "^# row section=0 row=0 height=0" "$TMP/profile_stdin.txt"
# Sparse rows (three ellipses 10 mm apart): one section per row with no planes; a plane
# between rows says which rows lie beside it; a dense ring with no planes asks for planes.
awk 'BEGIN { for (z = 0; z <= 20; z += 10) for (i = 0; i < 200; i++) { a = 6.283185307179586 * i / 200; printf "%.9f %.9f %g\n", 20*cos(a), 3*sin(a), z } }' > "$TMP/rows.xyz"
expect 0 "rows need no planes" -- "$BIN/slice" "$TMP/rows.xyz"
check "a section per row" -- test "$(grep -c '^# row section=' "$TMP/out")" -eq 3
check "said so" -- grep -q "3 rows of points 10 mm apart, each a section" "$TMP/err"
expect 0 "a plane through a row takes it" -- "$BIN/slice" "$TMP/rows.xyz" --at 10,15
check "the row taken" -- grep -q "^# row section=0 row=1 height=10 " "$TMP/out"
check "between rows: the rows named" -- grep -q "section 1: the plane at height 15 falls between the rows at heights 10 and 20" "$TMP/err"
check "between rows: an issue" -- grep -q "^# issue section=1" "$TMP/out"
expect 1 "a dense ring with no planes" -- "$BIN/slice" "$TMP/ring.xyz"
check "asks for planes, naming them" -- grep -q "give planes (--at, --count or --planes)" "$TMP/err"
check "nothing written" -- test ! -s "$TMP/out"
# (ring.xyz lies on 9 levels: lines, which --rows takes; a ring at every height is dense)
awk 'BEGIN { for (i = 0; i < 3600; i++) { a = 6.283185307179586 * i / 400; printf "%.9f %.9f %.4f\n", 10*cos(a), 5*sin(a), -0.2 + 0.4 * ((i * 7919) % 3600) / 3600 } }' > "$TMP/dense_ring.xyz"
expect 1 "--rows on a dense ring" -- "$BIN/slice" "$TMP/dense_ring.xyz" --rows --slab 0.1
check "not rows, said" -- grep -q -- "--rows: the points hold no rows or lines to take as sections, they are a dense scan" "$TMP/err"

# Views apart: the second view of a generated scan, misregistered by 15 um, is registered
# onto the first before slicing; the stream notes it. A view far off is refused, named.
"$BIN/bladegen" --kind compressor --points --noise 0.005 --misregistration 0.015 --z-min 25 --z-max 35 \
  --seed 4 -o "$TMP/view0.ply" --second-view "$TMP/view1.xyz" 2>/dev/null
expect 0 "views registered" -- "$BIN/slice" "$TMP/view0.ply" --view "$TMP/view1.xyz" --at 30
check "registration noted" -- grep -q "^# register view=$TMP/view1.xyz translation=" "$TMP/out"
check "a motion well within the reach: not said unconfirmed" -- bash -c "! grep -q unconfirmed '$TMP/out' '$TMP/err'"
# A registration kept unconfirmed (its note ends in unconfirmed=1) flags every params row.
sed '/^# register /s/$/ unconfirmed=1/' "$TMP/out" > "$TMP/unconfirmed.csv"
"$BIN/smooth" "$TMP/unconfirmed.csv" 2>/dev/null | "$BIN/fitspline" 2>/dev/null |
  "$BIN/camber" --params "$TMP/unconfirmed_params.csv" > "$TMP/unconfirmed_camber.csv" 2>"$TMP/unconfirmed.err"
check "unconfirmed registration: an issue" -- grep -q "fail check registration" "$TMP/unconfirmed_camber.csv"
check "unconfirmed registration: the row flagged" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "flags") c = i; next }
  { if (int($c / 2147483648) % 2 == 1) found = 1 } END { exit !found }' "$TMP/unconfirmed_params.csv"
# The view moved by about the misregistration (15 um) in the plane.
check "registration moved the view ~15 um" -- awk -F'[ =,]' '/^# register/ { d = sqrt($6*$6 + $7*$7); exit !(d > 0.013 && d < 0.017) }' "$TMP/out"
awk '{ printf "%.9f %s %s\n", $1 + 5, $2, $3 }' "$TMP/view1.xyz" > "$TMP/far.xyz"
expect 1 "a view 5 mm off" -- "$BIN/slice" "$TMP/view0.ply" --view "$TMP/far.xyz" --at 30
check "far view named" -- grep -q "far.xyz" "$TMP/err"
# A reach far wider than the misregistration pairs points with the blade's other side: the
# motion found slid the view 1.6-1.9 mm along the surface, and was taken (exit 0).
expect 1 "a reach that slides the view along the surface" -- "$BIN/slice" "$TMP/view0.ply" --view "$TMP/view1.xyz" --at 30 --view-reach 10
check "slid view named and refused" -- grep -q "view 1 is left off the reference surface.*give a reach a little above the misalignment.*view1.xyz" "$TMP/err"
check "nothing written for the slid view" -- test ! -s "$TMP/out"
expect 1 "a missing view" -- "$BIN/slice" "$TMP/view0.ply" --view "$TMP/none.ply" --at 30
check "missing view named" -- grep -q "none.ply" "$TMP/err"

# A blade scanned with its span along x: planes normal to z run along it, through open
# sheets, and each failed section says only that; slice says which normal would cut across.
"$BIN/bladegen" --points --spacing 0.08 --seed 3 --z-min 20 --z-max 40 -o "$TMP/upright.xyz"
awk '{ printf "%.9f %.9f %.9f\n", $3, $2, -$1 }' "$TMP/upright.xyz" > "$TMP/lying.xyz"
"$BIN/slice" "$TMP/lying.xyz" --count 5 > /dev/null 2> "$TMP/lying.err"
check "planes along the span: the normal is named" -- \
  grep -q "planes gave no profile: if they run along the part rather than across its span, give --normal along the span (now 0,0,1)" "$TMP/lying.err"
expect 0 "the normal along the span" -- "$BIN/slice" "$TMP/lying.xyz" --count 5 --normal 1,0,0
check "across the span: no word of the normal" -- sh -c "! grep -q 'give --normal' '$TMP/err'"

finish
