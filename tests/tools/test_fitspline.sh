#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the fitspline tool: help, usage errors, malformed input, a real fit.
set -u
BIN="${SECTION_BIN:?}/fitspline"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail=0
check() {  # check NAME EXPECTED_STATUS ACTUAL_STATUS
  if [ "$2" != "$3" ]; then echo "FAIL: $1: exit $3, expected $2"; fail=1; else echo "ok: $1"; fi
}

"$BIN" --help > "$TMP/help" 2>&1; check "--help exits 0" 0 $?
grep -q -- "--control-points" "$TMP/help" || { echo "FAIL: help lacks --control-points"; fail=1; }
"$BIN" --no-such-flag < /dev/null > /dev/null 2>&1; check "bad flag exits 2" 2 $?
"$BIN" --control-points 20 --tolerance 0.001 < /dev/null > /dev/null 2>&1; check "exclusive flags exit 2" 2 $?

# A stream with two sections: a circle of radius 5 (section 0) and a loop of 3 points (section 1).
{
  echo "# libsection-stream 1"
  echo "# units mm"
  echo "# table frames"
  echo "section,origin_x,origin_y,origin_z,u_x,u_y,u_z,v_x,v_y,v_z,n_x,n_y,n_z"
  echo "0,0,0,7,1,0,0,0,1,0,0,0,1"
  echo "1,0,0,9,1,0,0,0,1,0,0,0,1"
  echo "# table points"
  echo "section,loop,index,u,v,nu,nv"
  awk 'BEGIN { pi = atan2(0, -1); for (i = 0; i < 400; i++) { a = 2 * pi * i / 400;
       printf "0,0,%d,%.12f,%.12f,%.12f,%.12f\n", i, 5 * cos(a), 5 * sin(a), cos(a), sin(a) } }'
  echo "1,0,0,0,0,0,-1"
  echo "1,0,1,1,0,1,0"
  echo "1,0,2,0,1,0,1"
} > "$TMP/in.stream"

"$BIN" "$TMP/in.stream" --spacing 0.5 -o "$TMP/out.stream" 2> "$TMP/err"; check "fit exits 0" 0 $?
grep -q "^# table splines" "$TMP/out.stream" || { echo "FAIL: no splines table"; fail=1; }
grep -q "^# table spline_knots" "$TMP/out.stream" || { echo "FAIL: no spline_knots table"; fail=1; }
grep -q "^# table spline_ctrl" "$TMP/out.stream" || { echo "FAIL: no spline_ctrl table"; fail=1; }
grep -q "^# table samples" "$TMP/out.stream" || { echo "FAIL: no samples table"; fail=1; }
grep -q "^# issue section=1 loop=0 stage=fitspline" "$TMP/out.stream" ||
  { echo "FAIL: the 3-point loop is not reported as an issue"; fail=1; }
grep -q "section 1" "$TMP/err" || { echo "FAIL: no warning for section 1 on stderr"; fail=1; }
# Samples lie on the circle of radius 5 (to 1 um) at z = 7, with outward normals.
awk -F, '/^# table samples/ { s = 1; getline; next } /^#/ { s = 0 }
  s && NF == 12 { n++; r = sqrt($5 * $5 + $6 * $6); if (r - 5 > 1e-3 || 5 - r > 1e-3) bad++;
                  if ($9 != 7) bad++; if ($10 * $5 + $11 * $6 < 0) bad++ }
  END { if (n < 60 || bad > 0) { print "FAIL: " n " samples, " bad " off the circle"; exit 1 } }' \
  "$TMP/out.stream" || fail=1
# Fixed control points.
"$BIN" --control-points 24 < "$TMP/in.stream" > "$TMP/out2.stream" 2> /dev/null; check "--control-points exits 0" 0 $?
awk -F, '/^# table splines/ { getline; getline; if ($5 != 24) { print "FAIL: control points " $5; exit 1 } }' \
  "$TMP/out2.stream" || fail=1

grep -q "two layers" "$TMP/err" && { echo "FAIL: a clean circle is reported as two layers"; fail=1; }

# Two views of a circle of radius 12 (right and left halves, each 0.15 rad past the top and
# bottom), 5 um of noise, the left one shifted 15 um along y: reported as two layers.
{
  echo "# libsection-stream 1"
  echo "# units mm"
  echo "# table frames"
  echo "section,origin_x,origin_y,origin_z,u_x,u_y,u_z,v_x,v_y,v_z,n_x,n_y,n_z"
  echo "0,0,0,0,1,0,0,0,1,0,0,0,1"
  echo "# table points"
  echo "section,loop,index,u,v,nu,nv"
  awk 'BEGIN { pi = atan2(0, -1); srand(5)
       for (v = 0; v < 2; v++) {
         a0 = v ? pi / 2 - 0.15 : -pi / 2 - 0.15; m = int((pi + 0.3) * 12 / 0.04)
         for (i = 0; i < m; i++) {
           a = a0 + (pi + 0.3) * (i + 0.5) / m
           g = sqrt(-2 * log(1 - rand())) * cos(2 * pi * rand())
           x = (12 + 0.005 * g) * cos(a); y = (12 + 0.005 * g) * sin(a) + (v ? 0.015 : 0)
           printf "%.12f %.12f %.12f\n", atan2(y, x), x, y } } }' |
    sort -g | awk '{ printf "0,0,%d,%s,%s,0,0\n", NR - 1, $2, $3 }'
} > "$TMP/views.stream"
"$BIN" "$TMP/views.stream" -o "$TMP/views.out" 2> "$TMP/err"; check "two views exit 0" 0 $?
grep -q "two layers" "$TMP/err" || { echo "FAIL: two views 15 um apart not reported: $(cat "$TMP/err")"; fail=1; }
awk -F, '/^# table splines/ { getline; for (i = 1; i <= NF; i++) c[$i] = i; getline;
  if (!($c["layers"] > 0.010 && $c["layers"] < 0.020)) { print "FAIL: layers " $c["layers"]; exit 1 } }' \
  "$TMP/views.out" || fail=1
"$BIN" "$TMP/views.stream" --layer-ratio 0 -o /dev/null 2> "$TMP/err"; check "--layer-ratio 0 exits 0" 0 $?
grep -q "two layers" "$TMP/err" && { echo "FAIL: --layer-ratio 0 still reports layers"; fail=1; }

# A malformed row: exit 1 and the message names the line.
sed '12s/.*/0,0,3,abc,1,0,0/' "$TMP/in.stream" > "$TMP/bad.stream"
"$BIN" "$TMP/bad.stream" > /dev/null 2> "$TMP/err"; check "malformed stream exits 1" 1 $?
grep -q "12" "$TMP/err" || { echo "FAIL: the error does not name line 12: $(cat "$TMP/err")"; fail=1; }
# No points table: exit 1.
printf '# libsection-stream 1\n' | "$BIN" > /dev/null 2>&1; check "missing points table exits 1" 1 $?
exit $fail
