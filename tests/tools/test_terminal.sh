#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the tools at a terminal (forced with SECTION_ASSUME_TTY: ctest has
# none): a stream is not sent to a terminal nor read from one; camber prints its params for
# people there, and --format chooses what camber writes (table, csv, json, stream).
source "$(dirname "$0")/lib.sh"

# A stream to the terminal is refused before any work, naming the redirection.
for tool in slice smooth fitspline; do
  expect 2 "$tool to a terminal" -- env SECTION_ASSUME_TTY=stdout "$BIN/$tool" "$SRC/data/example_blade.ply"
  check "$tool says how to redirect" -- grep -q "usage error: the stream would go to the terminal: redirect it" "$TMP/err"
done
# Reading from a terminal (no input, or -) is refused with what to give instead.
for tool in smooth fitspline camber; do
  expect 2 "$tool from a terminal" -- env SECTION_ASSUME_TTY=stdin "$BIN/$tool"
  check "$tool says to give a file or pipe one in" -- grep -q "no input: give a file" "$TMP/err"
done
expect 2 "smooth - from a terminal" -- env SECTION_ASSUME_TTY=stdin "$BIN/smooth" -
# A file given for the output is not the terminal: the tool runs (and fails on the missing input).
expect 1 "smooth -o FILE at a terminal runs" -- env SECTION_ASSUME_TTY=1 "$BIN/smooth" "$TMP/none.csv" -o "$TMP/x.csv"

# An ellipse (a = 20, b = 3): chord 40, max thickness 6.
awk 'BEGIN { for (i = 0; i < 1000; ++i) { t = 2 * 3.14159265358979 * i / 1000; printf "%.9f %.9f\n", 20 * cos(t), 3 * sin(t) } }' > "$TMP/ellipse.dat"
expect 0 "camber at a terminal" -- env SECTION_ASSUME_TTY=stdout "$BIN/camber" "$TMP/ellipse.dat" --params "$TMP/params.csv"
cp "$TMP/out" "$TMP/table.txt"
check "the table is no stream" -- bash -c "! grep -q '^# libsection-stream' '$TMP/table.txt'"
check "the table has a section block with units" -- grep -q "^section 0" "$TMP/table.txt"
check "the table fits 120 columns" -- awk 'length($0) > 120 { exit 1 }' "$TMP/table.txt"
check "chord 40 and max thickness 6 to 4 decimals (1 um)" -- awk '
  / chord / && $1 == "chord" { c = $2 } $1 == "max" && $2 == "thickness" { t = $3 }
  END { if (c !~ /^[0-9]+\.[0-9][0-9][0-9][0-9]$/ || (c - 40) ^ 2 > 1e-6 || (t - 6) ^ 2 > 1e-6) exit 1 }' "$TMP/table.txt"
check "edge shapes in words" -- grep -q "LE radius .* mm round" "$TMP/table.txt"
expect 0 "camber --format table to a file" -- "$BIN/camber" "$TMP/ellipse.dat" --format table -o "$TMP/table2.txt"
check "the same table in the file" -- cmp -s "$TMP/table.txt" "$TMP/table2.txt"

# --format stream at a terminal writes the stream; with -o FILE the stream is the default.
expect 0 "camber --format stream at a terminal" -- env SECTION_ASSUME_TTY=stdout "$BIN/camber" "$TMP/ellipse.dat" --format stream
check "a stream is written" -- grep -q "^# libsection-stream 1" <(head -n 1 "$TMP/out")
expect 0 "camber -o FILE at a terminal" -- env SECTION_ASSUME_TTY=stdout "$BIN/camber" "$TMP/ellipse.dat" -o "$TMP/stream.txt"
check "the file holds the stream" -- grep -q "^# libsection-stream 1" <(head -n 1 "$TMP/stream.txt")

# --format csv: the --params CSV, full precision.
expect 0 "camber --format csv" -- "$BIN/camber" "$TMP/ellipse.dat" --format csv
check "csv is the params table" -- cmp -s "$TMP/out" "$TMP/params.csv"

# --format json parses, and holds the params at full precision (the CSV's numbers).
expect 0 "camber --format json" -- "$BIN/camber" "$TMP/stream.txt" --format json
if command -v python3 >/dev/null; then
  check "json parses" -- python3 -m json.tool "$TMP/out" /dev/null
  check "json params equal the CSV's doubles" -- python3 -c '
import csv, json, sys
doc = json.load(open(sys.argv[1]))
row = next(csv.DictReader(open(sys.argv[2])))
p = doc["sections"][0]["params"]
assert doc["units"] == "mm" and doc["sections"][0]["section"] == 0
for k in ("chord", "max_thickness", "stagger", "le_radius", "inlet_angle"):
    assert p[k] == float(row[k]), (k, p[k], row[k])
assert abs(p["chord"] - 40) < 1e-3 and repr(p["chord"]) == row["chord"], (p["chord"], row["chord"])
' "$TMP/out" "$TMP/params.csv"
fi
command -v jq >/dev/null && check "jq reads the chord" -- bash -c "jq -e '.sections[0].params.chord > 39.99' '$TMP/out' >/dev/null"
expect 2 "camber --format bogus" -- "$BIN/camber" "$TMP/ellipse.dat" --format bogus
check "--help names --format" -- bash -c "'$BIN/camber' --help | grep -q -- --format"
finish
