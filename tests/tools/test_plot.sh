#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the plot tool: help, usage errors, bad data, a stream that stops after
# slice, a full camber stream as SVG, as a directory of SVGs and as one HTML page.
source "$(dirname "$0")/lib.sh"
plot="$BIN/plot"

expect 0 "plot --help" -- "$plot" --help
check "--help describes the tool" -- grep -q "draw the sections" "$TMP/out"
expect 0 "plot --version" -- "$plot" --version
expect 2 "plot --width 5" -- "$plot" --width 5
expect 2 "plot --html --section 0" -- "$plot" --html --section 0
expect 2 "plot --no-such-flag" -- "$plot" --no-such-flag

# A stream that stops after slice: two sections of points (ellipses), no other table.
{
  echo "# libsection-stream 1"
  echo "# units mm"
  echo "# table points"
  echo "section,loop,index,u,v,nu,nv"
  awk 'BEGIN { for (s = 0; s < 2; ++s) for (i = 0; i < 300; ++i) { t = 2 * 3.14159265358979 * i / 300
    printf "%d,0,%d,%.9f,%.9f,%.9f,%.9f\n", s, i, 15 * cos(t), (2 + s) * sin(t), cos(t), sin(t) } }'
} > "$TMP/slice.txt"
expect 0 "plot --section 1" -- "$plot" "$TMP/slice.txt" --section 1 -o "$TMP/slice1.svg"
check "an SVG is written" -- grep -q "<svg" <(head -c 5 "$TMP/slice1.svg")
check "the 300 points of section 1 are drawn" -- test "$(grep -o "h0" "$TMP/slice1.svg" | wc -l)" -ge 300
check "a slice stream has no camber line to draw" -- test "$(grep -c 'class="camber"' "$TMP/slice1.svg")" = 0
# Several sections and no --section, --html or -o DIR: a clear error.
expect 1 "plot on several sections without a target" -- "$plot" "$TMP/slice.txt"
check "a hint for several sections" -- grep -q "give --section N, --html, or -o DIR" "$TMP/err"
expect 1 "plot --section 9" -- "$plot" "$TMP/slice.txt" --section 9 -o "$TMP/none.svg"
check "an unknown section is named" -- grep -q "section 9 is not in the stream (sections: 0, 1)" "$TMP/err"
check "a failed plot leaves no file" -- test ! -e "$TMP/none.svg"
expect 0 "plot -o DIR" -- "$plot" "$TMP/slice.txt" -o "$TMP/dir"
check "-o DIR writes one SVG per section" -- test -s "$TMP/dir/section-0.svg" -a -s "$TMP/dir/section-1.svg"

# Bad data: a malformed row names the line and exits 1.
printf '# libsection-stream 1\n# table points\nsection,loop,index,u,v\n0,0,0,1,x\n' > "$TMP/bad.txt"
expect 1 "plot on a malformed row" -- "$plot" "$TMP/bad.txt"
check "the error names line 4" -- grep -q "bad.txt:4" "$TMP/err"

# A full camber stream (an ellipse profile through the camber tool): every element drawn.
if [ -x "$BIN/camber" ]; then
  awk 'BEGIN { print "ELLIPSE 20 x 3"; for (i = 0; i < 800; ++i) { t = 2 * 3.14159265358979 * i / 800; printf "%.9f %.9f\n", 20 * cos(t), 3 * sin(t) } }' > "$TMP/ellipse.dat"
  expect 0 "camber on the ellipse" -- "$BIN/camber" "$TMP/ellipse.dat" -o "$TMP/camber.txt"
  expect 0 "plot a camber stream" -- "$plot" "$TMP/camber.txt" -o "$TMP/full.svg"   # one section: stdout rule not needed
  for c in curve camber station chord le-circle te-circle scale-bar param-table; do
    check "class $c in the full drawing" -- grep -q "class=\"$c\"" "$TMP/full.svg"
  done
  for id in s0-main s0-le s0-te; do check "id $id in the full drawing" -- grep -q "id=\"$id\"" "$TMP/full.svg"; done
  check "no non-finite number in the SVG" -- test "$(grep -ci "nan" "$TMP/full.svg")" = 0
  expect 0 "plot --html" -- "$plot" "$TMP/camber.txt" --html -o "$TMP/page.html"
  check "--html writes a page" -- grep -q "<!DOCTYPE html>" <(head -n 1 "$TMP/page.html")
  check "the page has section 0's drawing" -- grep -q 'id="s0"' "$TMP/page.html"
  # From standard input, --no-insets drops the insets.
  "$plot" --no-insets < "$TMP/camber.txt" > "$TMP/stdin.svg" 2>"$TMP/err"
  rc=$?
  check "plot reads standard input (exit $rc)" -- test "$rc" -eq 0
  check "--no-insets draws no inset" -- test "$(grep -c 'id="s0-le"' "$TMP/stdin.svg")" = 0
  check "dimension lines by default" -- grep -q 'class="dimension dim-chord"' "$TMP/full.svg"
  expect 0 "plot --no-dimensions" -- "$plot" "$TMP/camber.txt" --no-dimensions -o "$TMP/nodim.svg"
  check "--no-dimensions draws none" -- test "$(grep -c 'class="dimension' "$TMP/nodim.svg")" = 0
fi
finish
