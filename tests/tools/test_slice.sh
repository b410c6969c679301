#!/usr/bin/env bash
# Black-box tests of the slice tool.
source "$(dirname "$0")/lib.sh"

expect 0 "help" -- "$BIN/slice" --help
check "help names the options" -- grep -q -- "--normal" "$TMP/out"
expect 0 "version" -- "$BIN/slice" --version
expect 2 "bad flag" -- "$BIN/slice" --no-such-flag x.xyz
expect 2 "no planes" -- "$BIN/slice" x.xyz
expect 2 "bad normal" -- "$BIN/slice" x.xyz --normal 0,1 --at 1
expect 1 "missing file" -- "$BIN/slice" "$TMP/none.xyz" --at 1
check "missing file named" -- grep -q "none.xyz" "$TMP/err"
check "no partial output" -- test ! -s "$TMP/out"

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
"$BIN/slice" --at 0,5 --slab 0.1 < "$TMP/ring.xyz" > "$TMP/from_stdin.csv" 2>/dev/null
check "stdin gives the same rows" -- cmp -s <(grep -v '^# history' "$TMP/from_file.csv") <(grep -v '^# history' "$TMP/from_stdin.csv")
expect 1 "all planes miss" -- "$BIN/slice" "$TMP/ring.xyz" --at 50 --slab 0.1
check "nothing on stdout when all fail" -- test ! -s "$TMP/out"

finish
