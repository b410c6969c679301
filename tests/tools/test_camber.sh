#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the camber tool: help, usage errors, bad data, a plain profile, a
# non-blade section, and the full pipe when the other tools are built.
source "$(dirname "$0")/lib.sh"
camber="$BIN/camber"

expect 0 "camber --help" -- "$camber" --help
check "--help describes the tool" -- grep -q "mean-camber" "$TMP/out"
expect 2 "camber --edge square" -- "$camber" --edge square
expect 2 "camber --stations 0.5,abc" -- "$camber" --stations 0.5,abc

# An ellipse (a = 20, b = 3) as a plain profile with a title line: its camber line is
# the major axis, LE and TE points the vertices, chord 40.
awk 'BEGIN { print "ELLIPSE 20 x 3"; for (i = 0; i < 1000; ++i) { t = 2 * 3.14159265358979 * i / 1000; printf "%.9f %.9f\n", 20 * cos(t), 3 * sin(t) } }' > "$TMP/ellipse.dat"
expect 0 "camber on an ellipse profile" -- "$camber" "$TMP/ellipse.dat" --params "$TMP/params.csv" \
  --thickness "$TMP/thick.csv" --stations 0.25,0.5,0.75 -o "$TMP/stream.txt"
check "a stream is written" -- grep -q "^# libsection-stream 1" <(head -n 1 "$TMP/stream.txt")
for t in camber params thickness sides; do
  check "table $t is written" -- grep -q "^# table $t$" "$TMP/stream.txt"
done
check "the params CSV has a header and one row" -- test "$(wc -l < "$TMP/params.csv")" = 2
check "the thickness CSV has a header and 3 rows" -- test "$(wc -l < "$TMP/thick.csv")" = 4
check "ellipse chord 40 and max thickness 6 (1 um)" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { d = $c["chord"] - 40; if (d < 0) d = -d; if (d > 1e-3) { print "chord " $c["chord"]; exit 1 }
    t = $c["max_thickness"] - 6; if (t < 0) t = -t; if (t > 1e-3) { print "max_thickness " $c["max_thickness"]; exit 1 } }' \
  "$TMP/params.csv"
check "ellipse mid thickness 6 (1 um)" -- awk -F, 'NR > 1 && $3 == 0.5 { t = $7 - 6; if (t < 0) t = -t; if (t > 1e-3) exit 1 }' "$TMP/thick.csv"

# The stream itself is accepted as input (the spline tables are read back).
expect 0 "camber re-reads its stream" -- "$camber" "$TMP/stream.txt" -o "$TMP/again.txt"
check "re-reading the stream keeps the params" -- grep -q "^# table params$" "$TMP/again.txt"

# Forcing the LE direction swaps the ends: the LE point is now at +u.
expect 0 "camber --le-direction 1,0" -- "$camber" "$TMP/ellipse.dat" --le-direction 1,0 --params "$TMP/p2.csv" -o /dev/null
check "--le-direction sets the LE" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next } { if ($c["le_u"] < 19.9 || $c["le_by_direction"] != 1) exit 1 }' \
  "$TMP/p2.csv"

# A 3D direction is projected onto the section's plane (a plain profile's is x, y): -x
# puts the LE at -u, +x at +u; one along z cannot choose and the section gets an issue.
expect 0 "camber --le-direction 1,0,0.5" -- "$camber" "$TMP/ellipse.dat" --le-direction 1,0,0.5 --params "$TMP/p3.csv" -o /dev/null
check "a 3D --le-direction sets the LE" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next } { if ($c["le_u"] < 19.9 || $c["le_by_direction"] != 1) exit 1 }' \
  "$TMP/p3.csv"
expect 0 "camber --le-direction -1,0,0" -- "$camber" "$TMP/ellipse.dat" --le-direction=-1,0,0 --params "$TMP/p4.csv" -o /dev/null
check "a 3D --le-direction the other way" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next } { if ($c["le_u"] > -19.9 || $c["le_by_direction"] != 1) exit 1 }' \
  "$TMP/p4.csv"
expect 3 "camber --le-direction 0,0,1 (no params: exit 3)" -- "$camber" "$TMP/ellipse.dat" --le-direction 0,0,1 -o "$TMP/normal.txt"
check "a direction normal to the plane is an issue" -- grep -q "is normal to the plane of section 0" "$TMP/normal.txt"
check "the stream is still written whole" -- grep -q "^# table params$" "$TMP/normal.txt"
expect 2 "camber --le-direction 1,2,3,4" -- "$camber" "$TMP/ellipse.dat" --le-direction 1,2,3,4

# A circle is not a blade: an issue and a warning, no params row, exit 3 (a section asked
# about has no params; README "Exit status"), or 0 with --allow-partial.
awk 'BEGIN { for (i = 0; i < 500; ++i) { t = 2 * 3.14159265358979 * i / 500; printf "%.9f,%.9f\n", 5 * cos(t), 5 * sin(t) } }' > "$TMP/circle.csv"
expect 3 "camber on a circle" -- "$camber" "$TMP/circle.csv" -o "$TMP/circle.txt" --params "$TMP/circle_params.csv"
check "a warning for a circle" -- grep -q "not blade-like" "$TMP/err"
check "exit 3 is explained" -- grep -q "camber: incomplete: 1 of 1 sections have no params (section 0" "$TMP/err"
check "an issue recorded for a circle" -- grep -q "^# issue section=0 .*stage=camber" "$TMP/circle.txt"
check "the stream ends with # end or is whole" -- grep -q "^# table params$" "$TMP/circle.txt"
check "the params CSV has its header and no row" -- test "$(wc -l < "$TMP/circle_params.csv")" = 1
expect 0 "camber on a circle --allow-partial" -- "$camber" "$TMP/circle.csv" -o /dev/null --allow-partial
check "--help names exit status 3" -- sh -c "'$camber' --help | grep -q '3 the stream is written but some sections have no params'"

# A NACA 4412 whose trailing edge closes at one vertex, as a plain profile (Selig order,
# the TE point repeated): measured, the TE sharp with radius 0 at the vertex (100, 0),
# exit 0 (it failed with "end tangent does not meet the profile" and an empty params file).
awk 'BEGIN { pi = 3.14159265358979; m = 0.04; p = 0.4; t = 0.12; n = 150; print "NACA 4412 closed TE"
  for (k = 0; k < 2 * n - 1; ++k) {
    i = k < n ? n - 1 - k : k - n + 1; up = k < n ? 1 : -1
    x = (1 - cos(pi * i / (n - 1))) / 2
    yt = 5 * t * (0.2969 * sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1036 * x^4)
    if (x < p) { yc = m / p^2 * (2 * p * x - x^2); dy = 2 * m / p^2 * (p - x) }
    else { yc = m / (1 - p)^2 * (1 - 2 * p + 2 * p * x - x^2); dy = 2 * m / (1 - p)^2 * (p - x) }
    th = atan2(dy, 1)
    printf "%.6f %.6f\n", 100 * (x - up * yt * sin(th)), 100 * (yc + up * yt * cos(th)) } }' > "$TMP/naca4412.dat"
expect 0 "camber on a NACA 4412 with a closed TE" -- "$camber" "$TMP/naca4412.dat" --params "$TMP/naca.csv" -o /dev/null
check "its TE is sharp, radius 0, at the vertex (100, 0) within 10 um" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { du = $c["te_u"] - 100; dv = $c["te_v"]; if ($c["te_shape"] != 2 || $c["te_radius"] != 0 || du * du + dv * dv > 1e-4) exit 1 }' "$TMP/naca.csv"
check "the TE is named sharp in the issue" -- grep -q "trailing edge is sharp: the profile closes at a vertex" "$TMP/err"
check "the LE is the blunt end (by bluntness)" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { if ($c["le_u"] > 1 || $c["le_by_bluntness"] != 1) exit 1 }' "$TMP/naca.csv"

# The same points from another start and the other way round (a CMM starts wherever its
# probe began): the same params, to the byte.
tail -n +2 "$TMP/naca4412.dat" > "$TMP/naca_points.txt"
{ awk 'NR > 100' "$TMP/naca_points.txt"; awk 'NR <= 100' "$TMP/naca_points.txt"; } | tac > "$TMP/naca_turned.dat"
expect 0 "camber on the NACA 4412 from another start, reversed" -- "$camber" "$TMP/naca_turned.dat" \
  --params "$TMP/naca_turned.csv" -o /dev/null
check "the same params from any start" -- cmp -s "$TMP/naca.csv" "$TMP/naca_turned.csv"

# Bad data: a malformed row names the line and exits 1.
printf '1 2\n3 4\n5 x\n' > "$TMP/bad.txt"
expect 1 "camber on a malformed row" -- "$camber" "$TMP/bad.txt"
check "the error names line 3" -- grep -q "bad.txt:3" "$TMP/err"

# The full pipe on the example blade, when the other tools are built.
if [ -x "$BIN/bladegen" ] && [ -x "$BIN/slice" ] && [ -x "$BIN/smooth" ] && [ -x "$BIN/fitspline" ]; then
  expect 0 "bladegen --help" -- "$BIN/bladegen" --help
  expect 0 "bladegen writes a scan" -- "$BIN/bladegen" --kind compressor --points --spacing 0.1 -o "$TMP/blade.ply"
  "$BIN/slice" "$TMP/blade.ply" --count 3 2>/dev/null | "$BIN/smooth" | "$BIN/fitspline" | "$camber" --params "$TMP/pipe.csv" -o /dev/null
  st="${PIPESTATUS[*]}"
  check "the full pipe runs (exit statuses $st)" -- test "$st" = "0 0 0 0"
  check "the full pipe writes params for 3 sections" -- test "$(grep -c '^[0-9]' "$TMP/pipe.csv")" -eq 3
  check "no value of the generated blade is flagged (flags 0)" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next } { if ($c["flags"] != 0) exit 1 }' "$TMP/pipe.csv"
fi
# Two views merged 15 um apart: every section's fit finds the two layers. With them taken
# out of section 1's fit (its splines row's layers 0, as where the views overlap too little
# to tell them apart), camber's hold step still flags section 1 `layers` (bit 23): 3 of the
# 4 sections show them, and a view's shift moves every section.
if [ -x "$BIN/bladegen" ] && [ -x "$BIN/slice" ] && [ -x "$BIN/smooth" ] && [ -x "$BIN/fitspline" ]; then
  "$BIN/bladegen" --kind compressor --points --noise 0.005 --misregistration 0.015 --z-min 26 --z-max 34 \
    --seed 4 -o "$TMP/mis.ply" 2>/dev/null
  "$BIN/slice" "$TMP/mis.ply" --at 27,29,31,33 2>/dev/null | "$BIN/smooth" 2>/dev/null |
    "$BIN/fitspline" > "$TMP/mis_fit.txt" 2>/dev/null
  check "every misregistered section's fit shows layers" -- awk -F, '/^# table splines$/ { t = 1; h = 1; next }
    /^#/ { t = 0 } t && h { for (i = 1; i <= NF; ++i) c[$i] = i; h = 0; next }
    t && $c["loop"] == 0 { n++; if ($c["layers"] > 0) k++ } END { exit !(n == 4 && k == 4) }' "$TMP/mis_fit.txt"
  awk -F, -v OFS=, '/^# table splines$/ { t = 1; h = 1; print; next } /^#/ { t = 0 }
    t && h { for (i = 1; i <= NF; ++i) c[$i] = i; h = 0; print; next }
    t && $c["section"] == 1 { $c["layers"] = 0; $c["layers_length"] = 0 } { print }' "$TMP/mis_fit.txt" > "$TMP/mis_one.txt"
  expect 0 "camber on a misregistered scan, one section showing one layer" -- "$camber" "$TMP/mis_one.txt" \
    --params "$TMP/mis_params.csv" -o /dev/null
  check "that section is flagged layers by the others" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    $c["section"] == 1 { found = int($c["flags"] / 8388608) % 2 == 1 } END { exit !found }' "$TMP/mis_params.csv"
  check "... and told why" -- grep -q "section 1: .*3 of the 4 sections of this scan lie in two layers" "$TMP/err"
fi

# Edge circles refitted to the measured points (the stream's points table), or fitted to
# the spline's arcs alone with --edge-on-spline: both within 3 % of the true LE radius
# of a generated compressor section (sigma 5 um), and not the same number.
"$BIN/bladegen" --kind compressor --points --noise 0.005 --z-min 29 --z-max 31 --seed 5 -o "$TMP/c.ply" 2>/dev/null
"$BIN/bladegen" --kind compressor --truth "$TMP/truth.csv" --at 30 2>/dev/null
"$BIN/slice" "$TMP/c.ply" --at 30 2>/dev/null | "$BIN/smooth" 2>/dev/null | "$BIN/fitspline" > "$TMP/c_fit.txt" 2>/dev/null
expect 0 "camber, edges on the points" -- "$camber" "$TMP/c_fit.txt" --params "$TMP/c_pts.csv" -o /dev/null
expect 0 "camber --edge-on-spline" -- "$camber" "$TMP/c_fit.txt" --edge-on-spline --params "$TMP/c_spl.csv" -o /dev/null
col() { awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next } { print $c; exit }' "$1"; }
true_le=$(col "$TMP/truth.csv" le_radius)
le_pts=$(col "$TMP/c_pts.csv" le_radius)
le_spl=$(col "$TMP/c_spl.csv" le_radius)
check "LE radius on the points within 3 % ($le_pts vs $true_le)" -- awk -v a="$le_pts" -v t="$true_le" 'BEGIN { d = a / t - 1; exit !(d < 0.03 && d > -0.03) }'
check "LE radius on the spline within 3 % ($le_spl vs $true_le)" -- awk -v a="$le_spl" -v t="$true_le" 'BEGIN { d = a / t - 1; exit !(d < 0.03 && d > -0.03) }'
check "the refit changes the LE radius" -- test "$le_pts" != "$le_spl"

# A hollow section: an ellipse (a = 20, b = 3) with a channel of radius 1.5 centred at
# (0, 0.5), scanned as a prism (layers 0.05 mm apart, each point up to 0.02 mm off its
# layer): the channel is a cavity, its thinnest wall 1 mm at (0, 3). Without the channel
# --walls writes the header alone.
prism() {
  awk -v channel="$1" 'BEGIN { srand(3); pi = 3.14159265358979
    for (k = -5; k <= 5; ++k) {
      for (i = 0; i < 1720; ++i) { t = 2 * pi * (i + 0.3 * k) / 1720; printf "%.6f %.6f %.6f\n", 20 * cos(t), 3 * sin(t), 0.05 * k + 0.04 * (rand() - 0.5) }
      if (channel)
        for (i = 0; i < 190; ++i) { t = 2 * pi * (i + 0.3 * k) / 190; printf "%.6f %.6f %.6f\n", 1.5 * cos(t), 0.5 + 1.5 * sin(t), 0.05 * k + 0.04 * (rand() - 0.5) } } }'
}
prism 1 > "$TMP/hollow.xyz"
prism 0 > "$TMP/solid.xyz"
"$BIN/slice" "$TMP/hollow.xyz" --at 0 2>/dev/null | "$BIN/smooth" 2>/dev/null | "$BIN/fitspline" > "$TMP/h_fit.txt" 2>/dev/null
expect 0 "camber --walls on a hollow section" -- "$camber" "$TMP/h_fit.txt" --walls "$TMP/walls.csv" -o "$TMP/h.txt"
check "the walls table is in the stream" -- grep -q "^# table walls$" "$TMP/h.txt"
check "--walls has a header and one row" -- test "$(wc -l < "$TMP/walls.csv")" = 2
check "the wall is 1 mm (2 um) at (0, 3)" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { d = $c["wall"] - 1; if (d < 0) d = -d; u = $c["profile_u"]; if (u < 0) u = -u; v = $c["profile_v"] - 3; if (v < 0) v = -v
    if (d > 0.002 || u > 0.05 || v > 0.002 || $c["flags"] != 0) { print $c["wall"], $c["profile_u"], $c["profile_v"], $c["flags"]; exit 1 } }' \
  "$TMP/walls.csv"
# Its wall to each side: 1 mm to the upper, 2 mm to the lower (which is the pressure side of
# a symmetric section is the LE and TE's choice; the lesser is the thinnest).
check "the walls to the two sides are 1 and 2 mm (2 um)" -- awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { p = $c["pressure_wall"]; s = $c["suction_wall"]; lo = p < s ? p : s; hi = p < s ? s : p
    d = lo - $c["wall"]; if (d < 0) d = -d
    if (lo < 0.998 || lo > 1.002 || hi < 1.998 || hi > 2.002 || d > 1e-9 || $c["pressure_flags"] != 0 || $c["suction_flags"] != 0) { print p, s, $c["wall"]; exit 1 } }' \
  "$TMP/walls.csv"
# The wall along the channel: 100 stations on the circle, 1 mm at its top (0, 2), 2 mm at its
# bottom (0, -1), the upper half's nearest points on one side and the lower half's on the other.
expect 0 "camber --wall-map on a hollow section" -- "$camber" "$TMP/h_fit.txt" --wall-map "$TMP/map.csv" -o "$TMP/hm.txt"
check "the wall map is in the stream" -- grep -q "^# table wall_map$" "$TMP/hm.txt"
check "--wall-map has a header and 100 stations" -- test "$(wc -l < "$TMP/map.csv")" = 101
check "the map's stations lie on the channel, its least wall 1 mm (2 um)" -- awk -F, '
  NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; lo = 9; next }
  { u = $c["cavity_u"]; v = $c["cavity_v"] - 0.5; r = sqrt(u * u + v * v) - 1.5; if (r < 0) r = -r
    if (r > 0.003 || $c["flags"] != 0) { print "off the channel", $0; exit 1 }
    w = $c["wall"]; if (w < lo) lo = w; if (w > hi) hi = w
    if (v > 1.4) top = top " " $c["side"]; if (v < -1.4) bottom = bottom " " $c["side"]
    if (v > 1.495 && (w < 0.998 || w > 1.005)) { print "top", $0; exit 1 }
    if (v < -1.495 && (w < 1.998 || w > 2.005)) { print "bottom", $0; exit 1 } }
  END { split(top, t, " "); split(bottom, b, " ")
    if (lo < 0.998 || lo > 1.002 || hi < 1.998 || t[1] == b[1]) { print lo, hi, top, bottom; exit 1 }
    for (k in t) if (t[k] != t[1]) exit 1; for (k in b) if (b[k] != b[1]) exit 1 }' "$TMP/map.csv"
expect 0 "camber --format json on a hollow section" -- "$camber" "$TMP/h_fit.txt" --format json
if command -v python3 >/dev/null; then
  check "its JSON holds the walls and the wall map's 100 stations, as --wall-map writes them" -- python3 -c '
import csv, json, sys
s = json.load(open(sys.argv[1]))["sections"][0]
rows = list(csv.DictReader(open(sys.argv[2])))
m = s["wall_map"]
assert len(s["walls"]) == 1 and len(m) == len(rows) == 100, (len(s["walls"]), len(m))
assert all(a["wall"] == float(b["wall"]) and a["station"] == float(b["station"]) for a, b in zip(m, rows))
assert abs(min(a["wall"] for a in m) - 1) < 0.002' "$TMP/out" "$TMP/map.csv"
fi
expect 0 "camber --wall-stations 0" -- "$camber" "$TMP/h_fit.txt" --wall-stations 0 -o "$TMP/h0.txt"
check "... writes no wall map" -- bash -c "! grep -q '^# table wall_map$' '$TMP/h0.txt'"
expect 2 "camber --wall-stations -1 is refused" -- "$camber" "$TMP/h_fit.txt" --wall-stations -1
if [ -x "$BIN/tocad" ]; then
  expect 0 "tocad's JSON of a hollow section" -- "$BIN/tocad" "$TMP/h.txt" -o "$TMP/h.json"
  check "its default tables hold the walls" -- grep -q '"walls": \[{"loop": 1' "$TMP/h.json"
fi
expect 0 "camber --format table on a hollow section" -- "$camber" "$TMP/h_fit.txt" --format table
check "the table for people lists the cavity" -- grep -q "cavity 1  *wall  *1.00" "$TMP/out"
check "... and its walls to the sides" -- grep -q "to pressure  *[12].00.*to suction  *[12].00" "$TMP/out"
"$BIN/slice" "$TMP/solid.xyz" --at 0 2>/dev/null | "$BIN/smooth" 2>/dev/null | "$BIN/fitspline" > "$TMP/s_fit.txt" 2>/dev/null
expect 0 "camber --walls on a solid section" -- "$camber" "$TMP/s_fit.txt" --walls "$TMP/walls0.csv" -o "$TMP/s.txt"
check "no walls table in a solid section's stream" -- bash -c "! grep -q '^# table walls$' '$TMP/s.txt'"
check "--walls of a solid section is the header alone" -- test "$(wc -l < "$TMP/walls0.csv")" = 1

finish
