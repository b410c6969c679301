#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of the compare tool: help and exit codes, usage errors, bad data naming
# the file and line, and the inspection pipe on a generated blade against its nominal mesh
# (pass, fail on a tightened tolerance, not measured over a plane the nominal misses).
source "$(dirname "$0")/lib.sh"
compare="$BIN/compare"

expect 0 "compare --help" -- "$compare" --help
check "--help documents the exit codes" -- grep -q "4 a value failed its tolerance" "$TMP/out"
check "--help documents 'not measured'" -- grep -q "5 none failed but a value was not measured" "$TMP/out"
check "--help documents 'uncertain'" -- grep -q "6 none failed or was not measured but a value was uncertain" "$TMP/out"
expect 2 "compare --decision-rule loose" -- "$compare" --nominal x.stl --decision-rule loose
expect 2 "compare --coverage-factor 0" -- "$compare" --nominal x.stl --coverage-factor 0
expect 2 "compare without --nominal" -- "$compare" -
expect 2 "compare --fit sideways" -- "$compare" --nominal x.stl --fit sideways
expect 2 "compare --freedom along without --direction" -- "$compare" --nominal x.stl --freedom along
expect 2 "compare --direction 1,2,3 per section" -- "$compare" --nominal x.stl --direction 1,2,3
expect 2 "compare --weights le=x" -- "$compare" --nominal x.stl --fit weighted --weights le=x

# The blade: its nominal mesh (rings at z = 4 k), and a scan's pipe at z = 12, 20.
"$BIN/bladegen" --kind compressor --mesh --profile-points 2000 --layers 16 -o "$TMP/nominal.stl" || exit 1
"$BIN/bladegen" --kind compressor --points --noise 0.003 --z-min 9 --z-max 23 -o "$TMP/scan.ply" || exit 1
"$BIN/slice" "$TMP/scan.ply" --normal 0,0,1 --at 12,20 2>/dev/null | "$BIN/smooth" | "$BIN/fitspline" 2>/dev/null |
  "$BIN/camber" > "$TMP/measured.csv" 2>/dev/null || exit 1
cat > "$TMP/tol.csv" <<'TOL'
# compare tolerances (mm, degrees)
item,section,low,high,on
profile,*,-0.03,0.03
profile_le,*,-0.02,0.02
form,,,0.05
chord,*,-0.02,0.02
max_thickness,*,-0.01,0.01
le_radius,*,-0.02,0.02
fit_shift,*,,0.01,value
TOL
expect 0 "the pipe's sections pass" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" \
  --tolerances "$TMP/tol.csv" --report "$TMP/report.txt" -o "$TMP/compared.csv"
for t in fits deviations zones compared verdicts; do
  check "table $t is written" -- grep -q "^# table $t$" "$TMP/compared.csv"
done
check "the stream ends" -- test "$(tail -n 1 "$TMP/compared.csv")" = "# end"
check "the report opens with the verdict" -- grep -q "^blade: PASS" "$TMP/report.txt"
check "the report lists the values" -- grep -q "max_thickness .* pass" "$TMP/report.txt"
# At a terminal (forced: SECTION_ASSUME_TTY) the report takes the stream's place; --format
# json gives the verdicts, zones and compared values per section at full precision.
expect 0 "compare at a terminal" -- env SECTION_ASSUME_TTY=stdout "$compare" "$TMP/measured.csv" \
  --nominal "$TMP/nominal.stl" --tolerances "$TMP/tol.csv"
check "the terminal gets the report" -- cmp -s "$TMP/out" "$TMP/report.txt"
expect 0 "compare --format json" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" \
  --tolerances "$TMP/tol.csv" --format json
if command -v python3 >/dev/null; then
  check "the json parses, a section with its verdict, zones and compared values" -- python3 -c '
import json, sys
doc = json.load(open(sys.argv[1]))
s = doc["sections"][0]
assert "verdict" in s["verdicts"] and len(s["zones"]) >= 1 and len(s["compared"]) >= 1, s.keys()
' "$TMP/out"
fi

# The compared stream reads back: plot draws it (one row per zone and item of a section is
# not a duplicated row), and the page opens with the blade's verdict.
expect 0 "plot reads compare's stream" -- "$BIN/plot" "$TMP/compared.csv" --html -o "$TMP/blade.html"
check "the page gives the blade's verdict" -- grep -q "Blade: PASS" "$TMP/blade.html"
expect 0 "tocad reads compare's stream" -- "$BIN/tocad" "$TMP/compared.csv" -o "$TMP/params.json"

# A tolerance too tight for the scan's noise fails: exit 4, the report says which.
sed 's/^profile,\*,-0.03,0.03/profile,*,-0.002,0.002/' "$TMP/tol.csv" > "$TMP/tight.csv"
expect 4 "a tight profile tolerance fails" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" \
  --tolerances "$TMP/tight.csv" --report -
check "the report names the failed value" -- grep -q "^  profile .*FAIL" "$TMP/err"
check "the blade fails" -- grep -q "^blade: FAIL" "$TMP/err"

# An LE radius whose upper limit lies within its uncertainty (half of U above its deviation)
# is uncertain: exit 6 under the guarded rule (the default), 0 when judged by the value alone.
le=$(awk -F, '/^# table compared/ { f = 1; next } /^#/ { f = 0 } f && $1 == "section" { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  f && $1 == 0 && $c["item"] == 4 { printf "%.9f %.9f", $c["deviation"], $c["uncertainty"] }' "$TMP/compared.csv")
check "the LE radius has an uncertainty" -- awk -v u="${le#* }" 'BEGIN { exit !(u > 0 && u < 0.02) }'
printf 'item,section,low,high\nle_radius,0,-1,%s\n' "$(awk -v d="${le% *}" -v u="${le#* }" 'BEGIN { printf "%.9f", d + 0.5 * u }')" > "$TMP/guard.csv"
expect 6 "a limit within the uncertainty: uncertain" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" \
  --tolerances "$TMP/guard.csv" --report -
check "the report says uncertain, with the +- U" -- grep -q "^  le_radius .* +- .*uncertain" "$TMP/err"
check "the blade is uncertain" -- grep -q "^blade: UNCERTAIN" "$TMP/err"
expect 0 "--decision-rule simple: by the value" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" \
  --tolerances "$TMP/guard.csv" --decision-rule simple -o /dev/null

# A nominal mesh in metres (a CAD export) is taken as metres from its extent, with a warning,
# and compares as the same mesh in mm; told it is mm, no plane meets it: not measured.
"$BIN/bladegen" --kind compressor --mesh --profile-points 2000 --layers 16 --units m -o "$TMP/nominal_m.stl" || exit 1
expect 0 "a nominal in metres" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal_m.stl" \
  --tolerances "$TMP/tol.csv" -o /dev/null
check "the warning says metres" -- grep -q "nominal_m.stl: the input is 0.0.* across: taken to be in metres" "$TMP/err"
expect 0 "--nominal-units m" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal_m.stl" --nominal-units m \
  --tolerances "$TMP/tol.csv" -o /dev/null
expect 5 "--nominal-units mm on a mesh in metres" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal_m.stl" \
  --nominal-units mm --tolerances "$TMP/tol.csv" -o /dev/null
expect 2 "--nominal-units ft" -- "$compare" --nominal x.stl --nominal-units ft

# A tolerance row naming a section the stream does not have (9: only 0 and 1 were sliced)
# judges nothing: a warning naming the row, its values not measured (exit 5).
printf 'item,section,low,high\nchord,*,-0.05,0.05\nle_radius,9,-0.05,0.05\n' > "$TMP/absent.csv"
expect 5 "a tolerance for a section not in the stream" -- "$compare" "$TMP/measured.csv" \
  --nominal "$TMP/nominal.stl" --tolerances "$TMP/absent.csv" --report "$TMP/absent.txt" -o /dev/null
check "the warning names the row" -- grep -q "section 9: the tolerances name this section (.*absent.csv:3)" "$TMP/err"
check "the report lists it not measured" -- grep -q "^section 9: not measured (0 passed, 0 failed, 2 not measured" "$TMP/absent.txt"

# Minimum zone, weighted and whole-blade fits run; the minimum zone's largest deviation is
# no larger than least squares'.
expect 0 "minimum zone" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" --fit minimum-zone -o "$TMP/mz.csv"
expect 0 "least squares" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" -o "$TMP/ls.csv"
max_after() { awk -F, '/^# table fits/ { f = 1; next } /^#/ { f = 0 } f && $1 == "section" { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  f { printf "%s %s\n", $1, $c["max_after"] }' "$1"; }
check "minimum zone <= least squares" -- awk 'NR == FNR { ls[$1] = $2; next } $2 > ls[$1] + 1e-12 { exit 1 }' \
  <(max_after "$TMP/ls.csv") <(max_after "$TMP/mz.csv")
expect 0 "weighted" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" --fit weighted --weights le=5,te=5 -o /dev/null
expect 0 "whole blade" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" --whole-blade -o "$TMP/whole.csv"
check "whole blade: one motion" -- test "$(awk -F, '/^# table fits/ { f = 1; getline; next } /^#/ { f = 0 } f { print $4 "," $5 }' "$TMP/whole.csv" | sort -u | wc -l)" = 1

# The nominal as a stream: the same pipe run on the mesh, sections matched by plane.
"$BIN/slice" "$TMP/nominal.stl" --normal 0,0,1 --at 12,20 | "$BIN/fitspline" 2>/dev/null | "$BIN/camber" > "$TMP/nominal.csv" 2>/dev/null
expect 0 "a nominal stream" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.csv" --tolerances "$TMP/tol.csv" -o /dev/null

# A plane the nominal does not reach: its values are not measured (exit 5) with a warning.
"$BIN/slice" "$TMP/scan.ply" --normal 0,0,1 --at 12 2>/dev/null | "$BIN/smooth" | "$BIN/fitspline" 2>/dev/null |
  "$BIN/camber" 2>/dev/null > "$TMP/one.csv"
awk '{ if ($0 ~ /^section,origin_x/) { print; getline; n = split($0, a, ","); a[4] = 80; s = a[1]; for (i = 2; i <= n; ++i) s = s "," a[i]; print s } else print }' \
  "$TMP/one.csv" > "$TMP/off.csv"
expect 5 "a section the nominal misses is not measured" -- "$compare" "$TMP/off.csv" --nominal "$TMP/nominal.stl" \
  --tolerances "$TMP/tol.csv" -o /dev/null
check "a warning says why" -- grep -q "compare: warning: section 0: .*not measured" "$TMP/err"

# Bad data: a tolerance file's bad line, a nominal CSV's bad line, a missing nominal: exit 1.
printf 'item,low,high\nchord,-1,1\nchrod,-1,1\n' > "$TMP/badtol.csv"
expect 1 "an unknown tolerance item" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/nominal.stl" --tolerances "$TMP/badtol.csv"
check "the error names the file and line" -- grep -q "badtol.csv:3: unknown item 'chrod'" "$TMP/err"
printf 'section,u,v\n0,1,2\n0,x,3\n' > "$TMP/badnominal.csv"
expect 1 "a malformed nominal CSV" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/badnominal.csv"
check "the error names the nominal's line" -- grep -q "badnominal.csv:3" "$TMP/err"
"$BIN/slice" "$TMP/nominal.stl" --normal 0,0,1 --at 12 > "$TMP/sliced.csv" 2>/dev/null
expect 1 "a nominal stream without splines" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/sliced.csv"
check "the error names the nominal and what it lacks" -- grep -q "sliced.csv: pipe: the stream has no 'splines' table" "$TMP/err"
expect 1 "a missing nominal" -- "$compare" "$TMP/measured.csv" --nominal "$TMP/none.stl"
check "the error names the file" -- grep -q "none.stl" "$TMP/err"
check "no partial output on bad data" -- test ! -s "$TMP/out"
finish
