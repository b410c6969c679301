#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the blade tool: help, usage errors, bad data (an empty stream, one
# section, no params table), and the full pipe on a generated blade with a known stacking
# law against bladegen's truth (docs/BLADE.md).
source "$(dirname "$0")/lib.sh"
blade="$BIN/blade"

expect 0 "blade --help" -- "$blade" --help
check "--help describes the tool" -- grep -q "stacking line" "$TMP/out"
expect 2 "blade --axis 1,2,3" -- "$blade" --axis 1,2,3
expect 2 "blade --format xml" -- "$blade" --format xml
expect 2 "blade --samples 1" -- "$blade" --samples 1
expect 2 "blade --reference -1" -- "$blade" --reference -1

# Bad data: an empty file, a stream without params, a stream cut short.
: > "$TMP/empty.txt"
expect 1 "blade on an empty file" -- "$blade" "$TMP/empty.txt"
check "the empty file is named" -- grep -q "empty.txt" "$TMP/err"
printf '# libsection-stream 1\n# units mm\n' > "$TMP/bare.txt"
expect 1 "blade on a stream without params" -- "$blade" "$TMP/bare.txt"
check "the missing table is named" -- grep -q "params" "$TMP/err"

for tool in bladegen slice smooth fitspline camber; do
  [ -x "$BIN/$tool" ] || { echo "skipping the pipe: $tool not built"; finish; exit $?; }
done

# A turbine blade with lean 1.2 mm, sweep -0.6 mm and bow 0.35 mm, scanned with noise 5 um.
"$BIN/bladegen" --kind turbine --points --noise 0.005 --lean 1.2 --sweep -0.6 --bow 0.35 --seed 4 \
  -o "$TMP/blade.ply" --truth "$TMP/truth.csv" --at 12,24,36,48 >/dev/null 2>&1
"$BIN/slice" "$TMP/blade.ply" --at 12,24,36,48 2>/dev/null | "$BIN/smooth" | "$BIN/fitspline" |
  "$BIN/camber" -o "$TMP/camber.txt" 2>/dev/null
expect 0 "blade on four sections" -- "$blade" "$TMP/camber.txt" -o "$TMP/blade.csv" --plot "$TMP/blade.svg" \
  --lines "$TMP/lines.csv"
check "the blade table has a header and 4 rows" -- test "$(wc -l < "$TMP/blade.csv")" = 5
check "the stacking lines have 41 rows" -- test "$(wc -l < "$TMP/lines.csv")" = 42
check "the plot is an SVG" -- grep -q "<svg" "$TMP/blade.svg"
check "the plot shows the blade seen along the span" -- grep -q 'class="top-view"' "$TMP/blade.svg"
# The truth by the definitions (docs/BLADE.md): twist, lean, sweep against z = 12, bow
# against the line through z = 12 and z = 48.
check "twist within 0.05 deg, lean, sweep and bow within 10 um of the truth" -- awk -F, '
  FNR == 1 { for (i = 1; i <= NF; ++i) c[FILENAME, $i] = i; next }
  FILENAME ~ /truth/ { n++; z[n] = $c[FILENAME, "z"]; st[n] = $c[FILENAME, "stagger"];
    x[n] = $c[FILENAME, "centroid_x"]; y[n] = $c[FILENAME, "centroid_y"]; next }
  { m++; tw[m] = $c[FILENAME, "twist"]; le[m] = $c[FILENAME, "lean"]; sw[m] = $c[FILENAME, "sweep"];
    bo[m] = $c[FILENAME, "bow"] }
  function abs(v) { return v < 0 ? -v : v }
  END { if (m != 4 || n != 4) exit 1
    for (k = 1; k <= 4; ++k) { w = (z[k] - z[1]) / (z[4] - z[1]); b = y[k] - (y[1] + w * (y[4] - y[1]))
      if (abs(tw[k] - (st[k] - st[1])) > 0.05 || abs(le[k] - (y[k] - y[1])) > 0.01 ||
          abs(sw[k] - (x[k] - x[1])) > 0.01 || abs(bo[k] - b) > 0.01) {
        print "section " k ": twist " tw[k] " lean " le[k] " sweep " sw[k] " bow " bo[k]; exit 1 } } }' \
  "$TMP/truth.csv" "$TMP/blade.csv"
expect 0 "blade --format table" -- "$blade" "$TMP/camber.txt" --format table
check "the table names the reference" -- grep -q "reference section 0" "$TMP/out"
expect 0 "blade --format json" -- "$blade" "$TMP/camber.txt" --format json
check "json holds the blade rows" -- grep -q '"twist"' "$TMP/out"
expect 0 "blade --format stream" -- "$blade" "$TMP/camber.txt" --format stream -o "$TMP/stream.txt"
check "the stream holds the blade and stacking tables" -- grep -q "^# table stacking$" "$TMP/stream.txt"
expect 0 "blade from standard input" -- sh -c "\"$blade\" < \"$TMP/camber.txt\""

# A rotor: sparse rows on cylinders about the x axis moved to z = -150; --axis takes the
# span as the radius (the rows' 160..200 mm), axial along x. The rows do not resolve the
# compressor's thin edges (1 mm apart): camber flags them, and so the blade's values are.
"$BIN/bladegen" --kind compressor --rows 5 --row-pitch 10 --hub-radius 150 -o "$TMP/rows.xyz" >/dev/null 2>&1
"$BIN/slice" "$TMP/rows.xyz" 2>/dev/null | "$BIN/smooth" | "$BIN/fitspline" | "$BIN/camber" -o "$TMP/rows.txt" 2>/dev/null
expect 0 "blade --axis on rotor rows" -- "$blade" "$TMP/rows.txt" --axis 0,0,-150,1,0,0 --format csv
check "rotor: the span is the radius" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { r = 150 + 10 * (NR - 2) + 10; d = $c["span"] - r; if (d < -0.5 || d > 0.5) exit 1 }' "$TMP/out"
check "rotor: unresolved edges flag the twist" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { if ($c["flags"] % 2 != 1) exit 1 }' "$TMP/out"

# One section: no stacking line (exit 1, says why).
"$BIN/slice" "$TMP/blade.ply" --at 30 2>/dev/null | "$BIN/smooth" | "$BIN/fitspline" |
  "$BIN/camber" -o "$TMP/one.txt" 2>/dev/null
expect 1 "blade on one section" -- "$blade" "$TMP/one.txt"
check "one section: the message says 2 are needed" -- grep -q "at least 2 are needed" "$TMP/err"

# Two sections: a line, the bow flagged (never bare) and named in a warning.
"$BIN/slice" "$TMP/blade.ply" --at 12,48 2>/dev/null | "$BIN/smooth" | "$BIN/fitspline" |
  "$BIN/camber" -o "$TMP/two.txt" 2>/dev/null
expect 0 "blade on two sections" -- "$blade" "$TMP/two.txt" --format table --plot "$TMP/two.svg"
check "two sections: the bow is flagged" -- grep -q "bow" <(grep -E "^ +[01]\*? " "$TMP/out" | awk '{ print $NF }')
check "two sections: a warning names the check" -- grep -q "blade check" "$TMP/err"
check "two sections: the plot rings the flagged bows" -- grep -q 'class="flagged"' "$TMP/two.svg"

# A section without params (its plane misses the blade): exit 3, 0 with --allow-partial.
"$BIN/slice" "$TMP/blade.ply" --at 12,36,48,80 2>/dev/null | "$BIN/smooth" 2>/dev/null |
  "$BIN/fitspline" 2>/dev/null | "$BIN/camber" -o "$TMP/partial.txt" --allow-partial 2>/dev/null
expect 3 "blade with a section missing" -- "$blade" "$TMP/partial.txt" -o "$TMP/partial.csv"
check "the others are written" -- test "$(wc -l < "$TMP/partial.csv")" = 4
expect 0 "blade --allow-partial" -- "$blade" "$TMP/partial.txt" --allow-partial -o /dev/null

finish
