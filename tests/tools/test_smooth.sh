#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box test of the smooth tool: help, usage errors, malformed data, a small stream.
set -euo pipefail
BIN=${SECTION_BIN:?SECTION_BIN must point to the tool directory}/smooth
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "test_smooth: FAIL: $*" >&2; exit 1; }

"$BIN" --help > "$TMP/help" || fail "--help exited $?"
grep -q -- "--length" "$TMP/help" || fail "--help does not mention --length"

set +e
"$BIN" --bogus < /dev/null > /dev/null 2>&1; rc=$?
[ $rc -eq 2 ] || fail "a bad flag exited $rc, expected 2"
"$BIN" --solver jacobi < /dev/null > /dev/null 2>&1; rc=$?
[ $rc -eq 2 ] || fail "a bad solver exited $rc, expected 2"
set -e

# A circle of radius 2 (200 points, +-5 um of deterministic wiggle) as section 0, and a
# four-point loop as section 1, which must fail alone.
{
  echo "# libsection-stream 1"
  echo "# units mm"
  echo "# table points"
  echo "section,loop,index,u,v,nu,nv"
  awk 'BEGIN { pi = atan2(0, -1); for (i = 0; i < 200; i++) { t = 2 * pi * i / 200;
       r = 2 + 0.005 * ((i % 2) ? 1 : -1); printf "0,0,%d,%.12f,%.12f,%.12f,%.12f\n", i,
       r * cos(t), r * sin(t), cos(t), sin(t) } }'
  for i in 0 1 2 3; do echo "1,0,$i,$((i % 2)),$((i / 2)),0,1"; done
} > "$TMP/in.txt"

# Malformed: a letter in a number cell, on line 7.
sed '7s/^0,0,2,/0,0,2,abc/' "$TMP/in.txt" > "$TMP/bad.txt"
set +e
"$BIN" "$TMP/bad.txt" > "$TMP/bad.out" 2> "$TMP/bad.err"; rc=$?
set -e
[ $rc -eq 1 ] || fail "a malformed stream exited $rc, expected 1"
grep -q ":7" "$TMP/bad.err" || fail "the error does not name line 7: $(cat "$TMP/bad.err")"
[ ! -s "$TMP/bad.out" ] || fail "a malformed stream produced output"

# Missing points table.
printf '# libsection-stream 1\n# table frames\nsection\n0\n' > "$TMP/nopoints.txt"
set +e
"$BIN" "$TMP/nopoints.txt" > /dev/null 2> "$TMP/np.err"; rc=$?
set -e
[ $rc -eq 1 ] || fail "a stream without points exited $rc, expected 1"
grep -q "points" "$TMP/np.err" || fail "the error does not name the points table"

"$BIN" "$TMP/in.txt" --length 0.5 -o "$TMP/out.txt" --report "$TMP/report.csv" 2> "$TMP/err" \
  || fail "smoothing a good stream exited $?"
grep -q "section 1 loop 0" "$TMP/err" || fail "no warning for the four-point loop"
grep -q "^# issue section=1 loop=0 stage=smooth" "$TMP/out.txt" || fail "no issue recorded"
grep -q "^# history smooth" "$TMP/out.txt" || fail "no history line"
grep -q "^# table points" "$TMP/out.txt" || fail "the points table was not passed through"
# The smoothed circle: 200 rows, each within 2 um of radius 2 (the input was 5 um off).
awk -F, '/^# table smoothed/ { getline; on = 1; next } /^#/ { on = 0 }
         on && NF == 5 { n++; r = sqrt($4 * $4 + $5 * $5); d = r - 2; if (d < 0) d = -d;
                         if (d > 0.002 || $1 != 0) bad++ }
         END { if (n != 200 || bad) { print "smoothed rows " n ", bad " bad; exit 1 } }' \
  "$TMP/out.txt" || fail "unexpected smoothed table"
head -1 "$TMP/report.csv" | grep -q "^section,loop,points,energy_before,energy_after,iterations" \
  || fail "bad report header"
[ "$(wc -l < "$TMP/report.csv")" -eq 2 ] || fail "the report should have one loop"

# Both solvers agree; reading stdin works.
"$BIN" --length 0.5 --solver gauss-seidel < "$TMP/in.txt" > "$TMP/gs.txt" 2> /dev/null
paste -d, <(awk '/^# table smoothed/{getline; on=1; next} /^#/{on=0} on' "$TMP/out.txt") \
          <(awk '/^# table smoothed/{getline; on=1; next} /^#/{on=0} on' "$TMP/gs.txt") |
  awk -F, '{ d = ($4 - $9) ^ 2 + ($5 - $10) ^ 2; if (d > 1e-12) bad++ } END { exit bad ? 1 : 0 }' \
  || fail "cholmod and gauss-seidel disagree"
echo "test_smooth: ok"
