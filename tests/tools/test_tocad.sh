#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the tocad tool: help, usage errors, bad data, and an ellipse profile
# written as DXF, IGES and JSON (tests/python/test_cad.py reads them back with ezdxf and an
# IGES parser and checks the curves within 0.1 um).
. "$(dirname "$0")/lib.sh"
tocad="$BIN/tocad"
camber="$BIN/camber"

expect 0 "--help" -- "$tocad" --help
check "--help names the formats" -- grep -q "dxf, iges or json" "$TMP/out"
expect 2 "a bad flag" -- "$tocad" --bogus
expect 2 "no format for standard output" -- "$tocad" -
check "the usage error says how to give the format" -- grep -q "give --format" "$TMP/err"
expect 2 "an unknown format" -- "$tocad" --format step
expect 2 "an unknown table" -- "$tocad" --format json --tables params,bogus
check "the usage error names the table" -- grep -q "no table 'bogus'" "$TMP/err"

# An ellipse 40 x 6 as a plain profile, through camber: one section with its spline and params.
awk 'BEGIN { for (i = 0; i < 800; ++i) { t = 2 * 3.14159265358979 * i / 800; printf "%.9f %.9f\n", 20 * cos(t), 3 * sin(t) } }' > "$TMP/ellipse.dat"
"$camber" "$TMP/ellipse.dat" -o "$TMP/stream.csv" 2>/dev/null

expect 0 "DXF by extension" -- "$tocad" "$TMP/stream.csv" -o "$TMP/e.dxf"
check "the DXF ends with EOF" -- bash -c "tail -1 '$TMP/e.dxf' | grep -qx EOF"
check "the DXF has one SPLINE and one POLYLINE" -- bash -c "[ \$(grep -cx SPLINE '$TMP/e.dxf') -eq 1 ] && [ \$(grep -cx POLYLINE '$TMP/e.dxf') -eq 1 ]"
expect 0 "DXF splines only" -- "$tocad" "$TMP/stream.csv" --format dxf --polyline-tolerance 0
check "no POLYLINE with --polyline-tolerance 0" -- bash -c "! grep -qx POLYLINE '$TMP/out'"
expect 0 "IGES by extension" -- "$tocad" "$TMP/stream.csv" -o "$TMP/e.IGS"
check "every IGES line is 80 columns" -- awk 'length($0) != 80 { exit 1 }' "$TMP/e.IGS"
check "the IGES has one entity 126 (two directory lines)" -- bash -c "[ \$(grep -c 'D      [0-9]\$' '$TMP/e.IGS') -eq 2 ]"
expect 0 "JSON on standard output" -- "$tocad" "$TMP/stream.csv" --format json
check "the JSON holds the chord (40 within 1 um)" -- bash -c "grep -oE '\"chord\": [0-9.e-]+' '$TMP/out' | awk '{ d = \$2 - 40; if (d < 0) d = -d; exit !(d < 1e-3) }'"
if command -v jq >/dev/null 2>&1; then
  check "jq parses the JSON" -- bash -c "jq -e '.sections[0].thickness.fraction | length > 5' '$TMP/out' >/dev/null"
fi

# Bad data: a letter in a number cell names the line; no output file is left.
sed '8s/^0,/0,abc/' "$TMP/stream.csv" > "$TMP/bad.csv"
expect 1 "a malformed stream" -- "$tocad" "$TMP/bad.csv" -o "$TMP/bad.dxf"
check "the error names the file and line 8" -- grep -q "bad.csv:8" "$TMP/err"
check "no DXF is left" -- test ! -e "$TMP/bad.dxf"
printf '# libsection-stream 1\n# units mm\n# table points\nsection,loop,index,u,v\n0,0,0,1,2\n' > "$TMP/nosplines.csv"
expect 1 "a stream without splines" -- "$tocad" "$TMP/nosplines.csv" -o "$TMP/n.igs"
check "the error says fitspline writes them" -- grep -q "written by fitspline" "$TMP/err"
expect 1 "JSON without params" -- "$tocad" "$TMP/nosplines.csv" -o "$TMP/n.json"
check "the error says camber writes them" -- grep -q "written by camber" "$TMP/err"
expect 1 "a missing file" -- "$tocad" "$TMP/none.csv" -o "$TMP/n.dxf"
check "the error names the file" -- grep -q "none.csv" "$TMP/err"
finish
