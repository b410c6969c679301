#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the input formats (tests/data/formats/, written by laspy, lazrs, pypcd4,
# pye57, Python's csv module and numpy: scripts/make_format_fixtures.py): slice gives the
# same sections from each file as from the same points in XYZ, byte for byte where the
# format holds the decimals exactly; float PCD and E57 scans with poses the same
# parameters to 1e-4 (their coordinates are rounded to float or moved by a pose, ~1e-5 mm);
# LAZ of point formats 3 and 6 (lazrs) byte for byte; what is not read (binary_compressed
# PCD, an E57 codec other than bitPackCodec) is refused by name.
source "$(dirname "$0")/lib.sh"
D="$SRC/tests/data/formats"
AT=(--at 15,30,45)

sections() {  # sections INPUT OUT: slice's stream without its history line
  "$BIN/slice" "$1" "${AT[@]}" | grep -v '^# history' > "$2"
}
# params INPUT OUT: the params of the whole pipe on INPUT.
params() {
  "$BIN/slice" "$1" "${AT[@]}" | "$BIN/smooth" | "$BIN/fitspline" | "$BIN/camber" --params "$2" > /dev/null
}
# close A B: chord, max thickness, camber length (mm) and stagger (deg) of two params files
# agree within 1e-4 on every section.
close() {
  python3 - "$1" "$2" <<'PY'
import csv, sys
a, b = (list(csv.DictReader(l for l in open(p) if not l.startswith("#"))) for p in sys.argv[1:])
assert len(a) == len(b) == 3, (len(a), len(b))
for ra, rb in zip(a, b):
    for k in ("chord", "max_thickness", "camber_length", "stagger"):
        assert abs(float(ra[k]) - float(rb[k])) <= 1e-4, (k, ra[k], rb[k])
PY
}

# near A B: two slice streams with the same tables, rows and section points, the points'
# u and v within 1e-5 mm (their normals, estimated from neighbours, may differ more).
near() {
  python3 - "$1" "$2" <<'PY'
import sys
a, b = (open(p).read().split("\n") for p in sys.argv[1:])
assert len(a) == len(b), (len(a), len(b))
table, worst = None, 0.0
for la, lb in zip(a, b):
    if la.startswith("# table"):
        table, head = la, None
        assert la == lb, (la, lb)
    elif table == "# table points" and not la.startswith("#"):
        if head is None:
            head = la.split(",")
            assert la == lb
            continue
        ra, rb = dict(zip(head, la.split(","))), dict(zip(head, lb.split(",")))
        assert [ra[k] for k in ("section", "loop", "index")] == [rb[k] for k in ("section", "loop", "index")]
        worst = max(worst, abs(float(ra["u"]) - float(rb["u"])), abs(float(ra["v"]) - float(rb["v"])))
assert worst <= 1e-5, worst
PY
}

expect 0 "slice blade.xyz" -- sections "$D/blade.xyz" "$TMP/ref"
check "the XYZ gives 3 sections" -- test "$(grep -c '^# part' "$TMP/ref")" -eq 3
for f in blade.pts blade_12_f3.las blade_14_f6.las blade_12_f3.laz blade_14_f6.laz blade_ascii.pcd blade_scaled.e57 \
  blade_semicolon.csv blade_semicolon.txt blade_tab.txt; do
  expect 0 "slice $f" -- sections "$D/$f" "$TMP/$f.out"
  check "$f gives the same sections as the XYZ" -- cmp -s "$TMP/ref" "$TMP/$f.out"
done
expect 0 "pipe on blade.xyz" -- params "$D/blade.xyz" "$TMP/ref.csv"
expect 0 "pipe on blade_binary.pcd" -- params "$D/blade_binary.pcd" "$TMP/bin.csv"
check "float PCD gives the same chord, thickness, camber length, stagger to 1e-4" -- close "$TMP/ref.csv" "$TMP/bin.csv"
expect 0 "slice blade_scans.e57" -- sections "$D/blade_scans.e57" "$TMP/scans.out"
check "E57 in four posed scans gives the same sections, their points to 1e-5 mm" -- near "$TMP/ref" "$TMP/scans.out"
# E57's unit is the metre (E2807): a part under 1 m across is read as metres, its --at too.
"$BIN/slice" "$D/blade_metres.e57" --at 0.015,0.03,0.045 2> "$TMP/metres.err" | grep -v '^# history' > "$TMP/metres.out"
check "its stream notes the unit" -- grep -q "^# units_from m " "$TMP/metres.out"
grep -v '^# units_from' "$TMP/metres.out" > "$TMP/metres.mm"
check "E57 in metres gives the same sections in mm, their points to 1e-5 mm" -- near "$TMP/ref" "$TMP/metres.mm"
check "and says on stderr it read metres" -- grep -q "taken to be in metres" "$TMP/metres.err"
expect 0 "pipe on blade_scans.e57" -- params "$D/blade_scans.e57" "$TMP/e57.csv"
check "E57 in four posed scans gives the same chord, thickness, camber length, stagger to 1e-4" -- \
  close "$TMP/ref.csv" "$TMP/e57.csv"
# Standard input: LAS and PCD by their first bytes.
"$BIN/slice" - "${AT[@]}" < "$D/blade_12_f3.las" | grep -v '^# history' > "$TMP/stdin.out"
check "LAS on standard input gives the same sections" -- cmp -s "$TMP/ref" "$TMP/stdin.out"
"$BIN/slice" - "${AT[@]}" < "$D/blade_12_f3.laz" | grep -v '^# history' > "$TMP/stdin.out"
check "LAZ on standard input gives the same sections" -- cmp -s "$TMP/ref" "$TMP/stdin.out"
"$BIN/slice" - "${AT[@]}" < "$D/blade_ascii.pcd" | grep -v '^# history' > "$TMP/stdin.out"
check "PCD (starting with VERSION) on standard input gives the same sections" -- cmp -s "$TMP/ref" "$TMP/stdin.out"
"$BIN/slice" - "${AT[@]}" < "$D/blade_scaled.e57" | grep -v '^# history' > "$TMP/stdin.out"
check "E57 on standard input gives the same sections" -- cmp -s "$TMP/ref" "$TMP/stdin.out"

expect 1 "binary_compressed PCD is refused" -- "$BIN/slice" "$D/compressed.pcd" "${AT[@]}"
check "its message names the file and the way out" -- \
  grep -q "compressed.pcd: PCD DATA binary_compressed is not supported: save it as binary or ascii" "$TMP/err"
check "nothing on stdout" -- test ! -s "$TMP/out"
expect 1 "an E57 file with an unknown codec is refused" -- "$BIN/slice" "$D/codec.e57" "${AT[@]}"
check "its message names the file, the scan and the codec" -- grep -q "codec.e57: E57 scan 1 ('tiny'): its points use the codec 'zLibCodec'" "$TMP/err"
check "nothing on stdout" -- test ! -s "$TMP/out"
head -c 30000 "$D/blade_scans.e57" > "$TMP/cut.e57"
expect 1 "a truncated E57 file is refused" -- "$BIN/slice" "$TMP/cut.e57" "${AT[@]}"
check "its message names the file and both lengths" -- grep -q "cut.e57: E57 header declares 82944 bytes but the file holds only 30000 (truncated file?)" "$TMP/err"
printf '3\n1 2 3\n4 5 6\n' > "$TMP/short.pts"
expect 1 "a PTS count line larger than its points is refused" -- "$BIN/slice" "$TMP/short.pts" --at 1
check "its message names the file and both counts" -- grep -q "short.pts: its PTS count lines declare 3 points, the file holds 2" "$TMP/err"
# T-Blade3's .dat: the XYZ's rows after their count line (POINTS SECTIONS, product = rows).
n=$(grep -c . "$D/blade.xyz")
{ echo "$n 1"; cat "$D/blade.xyz"; } > "$TMP/blade3d.dat"
expect 0 "slice a T-Blade3 .dat" -- sections "$TMP/blade3d.dat" "$TMP/dat.out"
check "the .dat gives the same sections as the XYZ" -- cmp -s "$TMP/ref" "$TMP/dat.out"
head -n 100 "$TMP/blade3d.dat" > "$TMP/cut.dat"
expect 1 "a truncated T-Blade3 .dat is refused" -- "$BIN/slice" "$TMP/cut.dat" "${AT[@]}"
check "its message names the file and both counts" -- grep -q "cut.dat: its count line \`$n 1\` (points a section, sections) declares $n points, the file holds 99" "$TMP/err"
check "nothing on stdout" -- test ! -s "$TMP/out"
finish
