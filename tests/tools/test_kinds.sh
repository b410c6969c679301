#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box test of bench/evaluate_kinds (docs/ACCURACY.md, "Data kinds"): the kinds of data
# users have through the real tools with default options, scored against the exact truth.
#
# Every kind passes today (issue 21); EXPECTED lists them, so that a kind added to the
# harness is printed until it passes and is added here. KINDS_STRICT=1 asserts every kind.
source "$(dirname "$0")/lib.sh"
E="$BIN/../bench/evaluate_kinds"
if [ ! -x "$E" ]; then echo "skipped: no $E (built with SECTION_BUILD_BENCH=OFF)"; exit 0; fi
EXPECTED="scan-mm,scan-m,scan-in,grid-chordwise,grid-spanwise,rows-height,rows-radius,sharp-te,symmetric,thick-root,misregistered,grid-noise-1um,grid-noise-3um,grid-noise-10um"
[ "${KINDS_STRICT:-0}" = 1 ] && EXPECTED=all

expect 0 "--help" -- "$E" --help
check "--help lists the kinds" -- grep -q "rows-radius" "$TMP/out"
expect 2 "an unknown kind" -- "$E" --kinds nothing
expect 2 "an unknown flag" -- "$E" --bogus

# The quick run: every kind once, the expected ones must pass.
expect 0 "quick run, the expected kinds ($EXPECTED) pass" -- "$E" --quick --tools "$BIN" --expect "$EXPECTED"
sed -n '/^summary/,$p' "$TMP/out"
check "a summary line per kind" -- test "$(grep -cE '^(PASS|FAIL) ' "$TMP/out")" -eq 14
cp "$TMP/out" "$TMP/quick.txt"

# The harness itself: a camber that writes a chord 1 % long is caught as a silent wrong
# value; the same with the flags column's chord bit set is counted as flagged.
mkdir -p "$TMP/fake"
BIN="$(cd "$BIN" && pwd)"
for t in slice smooth fitspline; do ln -s "$BIN/$t" "$TMP/fake/$t"; done
cat > "$TMP/fake/camber" <<EOS
#!/usr/bin/env bash
# camber, then the params file's chord made 1 % long (and its flags set to FLAG if given)
args=("\$@"); p=""
for ((i = 0; i < \${#args[@]}; ++i)); do [ "\${args[i]}" = --params ] && p="\${args[i+1]}"; done
"$BIN/camber" "\$@" || exit \$?
awk -F, -v OFS=, -v flag="\${FLAG:-}" '
  NR == 1 { for (i = 1; i <= NF; ++i) { if (\$i == "chord") c = i; if (\$i == "flags") f = i }; print; next }
  { \$c = \$c * 1.01; if (flag != "") \$f = flag; print }' "\$p" > "\$p.tmp" && mv "\$p.tmp" "\$p"
EOS
chmod +x "$TMP/fake/camber"
expect 1 "a chord 1 % long is a silent wrong value" -- "$E" --quick --kinds scan-mm --tools "$TMP/fake"
check "it is named" -- grep -q "SILENT WRONG seed 1 section 0 (z .*): chord off by" "$TMP/out"
expect 0 "flagged in the row's flags column (the chord check's bit, 256)" -- env FLAG=256 "$E" --quick --kinds scan-mm \
  --tools "$TMP/fake"
check "counted as flagged" -- grep -qE "^  chord +[0-9.]+ um +10 +3 +3 +0" "$TMP/out"
finish
