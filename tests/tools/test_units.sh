#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box tests of length units: the same blade scanned in mm, written in metres and in
# inches, gives the same parameters (to 1e-6 relative) once slice converts it to mm, given
# --units or, for metres, guessed from the extent; a plain profile likewise through camber;
# a stream in metres is converted by the stage tools; unknown units are refused; a stray
# point a metre off changes nothing but a warning.
source "$(dirname "$0")/lib.sh"

# same_params A B: every number of two params CSVs agrees to 1e-6 relative (1e-9 absolute).
same_params() {
  awk -F, 'NR == FNR { a[FNR] = $0; next }
    { n = split(a[FNR], x, ","); if (n != NF) { print "columns differ at line " FNR; exit 1 }
      if (FNR == 1) { if (a[FNR] != $0) { print "headers differ"; exit 1 } next }
      for (i = 1; i <= NF; ++i) { d = x[i] - $i; if (d < 0) d = -d; m = ($i < 0 ? -$i : $i)
        if (d > 1e-6 * m && d > 1e-9) { print "line " FNR " column " i ": " x[i] " vs " $i; exit 1 } } }
    END { if (FNR < 2) { print "no rows"; exit 1 } }' "$1" "$2"
}
pipe() {  # pipe INPUT PARAMS [slice flags...]
  local in="$1" out="$2"; shift 2
  "$BIN/slice" "$in" --count 3 "$@" 2>>"$TMP/warnings" | "$BIN/smooth" | "$BIN/fitspline" |
    "$BIN/camber" --params "$out" > /dev/null
}

for kind in turbine compressor; do
  "$BIN/bladegen" --kind "$kind" --points --spacing 0.2 --noise 0.003 --seed 4 -o "$TMP/$kind.xyz"
  awk '{ printf "%.15g %.15g %.15g\n", $1 / 1000, $2 / 1000, $3 / 1000 }' "$TMP/$kind.xyz" > "$TMP/${kind}_m.xyz"
  awk '{ printf "%.15g %.15g %.15g\n", $1 / 25.4, $2 / 25.4, $3 / 25.4 }' "$TMP/$kind.xyz" > "$TMP/${kind}_in.xyz"
  expect 0 "$kind in mm" -- pipe "$TMP/$kind.xyz" "$TMP/$kind.mm.csv"
  : > "$TMP/warnings"
  expect 0 "$kind in metres, unit guessed" -- pipe "$TMP/${kind}_m.xyz" "$TMP/$kind.m.csv"
  check "$kind: the guess is said" -- grep -q "taken to be in metres" "$TMP/warnings"
  expect 0 "$kind in metres, --units m" -- pipe "$TMP/${kind}_m.xyz" "$TMP/$kind.m2.csv" --units m
  expect 0 "$kind in inches, --units in" -- pipe "$TMP/${kind}_in.xyz" "$TMP/$kind.in.csv" --units in
  check "$kind: metres (guessed) give the mm parameters" -- same_params "$TMP/$kind.mm.csv" "$TMP/$kind.m.csv"
  check "$kind: metres (given) give the mm parameters" -- same_params "$TMP/$kind.mm.csv" "$TMP/$kind.m2.csv"
  check "$kind: inches give the mm parameters" -- same_params "$TMP/$kind.mm.csv" "$TMP/$kind.in.csv"
done

# A stray point a metre off a scan in metres (a reflection): the unit is still guessed, the
# --count planes are spread over the blade, not over the stray, and the stray is said; read
# from a file (streamed) and from standard input (held) alike.
{ cat "$TMP/turbine_m.xyz"; echo "0.9 0.1 0.5"; } > "$TMP/turbine_stray.xyz"
: > "$TMP/warnings"
expect 0 "a scan in metres with a stray point" -- pipe "$TMP/turbine_stray.xyz" "$TMP/stray.csv"
check "the unit is guessed without the stray" -- grep -q "taken to be in metres" "$TMP/warnings"
check "the stray is said" -- grep -q "1 point lies far beyond the rest along the normal" "$TMP/warnings"
check "the stray changes no parameter" -- same_params "$TMP/turbine.mm.csv" "$TMP/stray.csv"
: > "$TMP/warnings"
piped() { pipe - "$2" < "$1"; }  # expect reads standard input from /dev/null
expect 0 "the same from standard input" -- piped "$TMP/turbine_stray.xyz" "$TMP/stray_in.csv"
check "from standard input, the stray is said" -- grep -q "1 point lies far beyond the rest" "$TMP/warnings"
# The planes are those of the file without the stray (held in memory, the cloud's slab comes
# from all its points, the stray's distance to its neighbours among them: its parameters
# move by 0.1 um).
held_frames() { "$BIN/slice" - --count 3 < "$1" 2>/dev/null | sed -n '/^# table frames/,/^# table loops/p' | sed -n 3p; }
check "from standard input, the planes are the blade's" -- \
  test "$(held_frames "$TMP/turbine_stray.xyz")" = "$(held_frames "$TMP/turbine_m.xyz")"

# Lengths given on slice's command line are in the input's unit: --at in metres.
expect 0 "--units m --at in metres" -- "$BIN/slice" "$TMP/turbine_m.xyz" --units m --at 0.02 -o "$TMP/at.txt"
check "the plane lies at 20 mm" -- grep -q "^0,0,0,20,1,0,0,0,1,0,0,0,1$" "$TMP/at.txt"
check "the stream is in mm and says where its unit came from" -- \
  grep -q "^# units mm$" "$TMP/at.txt"
check "the stream notes the input's unit" -- grep -q "^# units_from m" "$TMP/at.txt"

# A plain profile in metres: camber converts it (guessed and given alike).
awk 'BEGIN { for (i = 0; i < 400; ++i) { t = 2 * 3.14159265358979 * i / 400
  x = 20 * cos(t); y = 3 * sin(t) + 2 * (1 - (x / 20) ^ 2); printf "%.15g %.15g\n", x / 1000, y / 1000 } }' \
  > "$TMP/profile_m.dat"
awk '{ printf "%.15g %.15g\n", $1 * 1000, $2 * 1000 }' "$TMP/profile_m.dat" > "$TMP/profile.dat"
expect 0 "camber, a profile in mm" -- "$BIN/camber" "$TMP/profile.dat" --params "$TMP/prof_mm.csv" -o /dev/null
expect 0 "camber, a profile in metres" -- "$BIN/camber" "$TMP/profile_m.dat" --params "$TMP/prof_m.csv" -o /dev/null
check "camber says it took metres" -- grep -q "taken to be in metres" "$TMP/err"
expect 0 "camber --units m" -- "$BIN/camber" "$TMP/profile_m.dat" --units m --params "$TMP/prof_m2.csv" -o /dev/null
check "a profile in metres gives the mm parameters" -- same_params "$TMP/prof_mm.csv" "$TMP/prof_m.csv"
check "a profile in metres (given) gives the mm parameters" -- same_params "$TMP/prof_mm.csv" "$TMP/prof_m2.csv"

# A stream in metres: the stages convert it to mm before they run.
"$BIN/slice" "$TMP/turbine.xyz" --count 3 > "$TMP/mm.stream"
awk -F, 'BEGIN { OFS = "," }
  /^# units/ { print "# units m"; next }
  /^# table / { t = $0; sub("# table ", "", t); head = 1; print; next }
  /^#/ { print; next }
  head { for (i = 1; i <= NF; ++i) col[i] = $i; head = 0; print; next }
  { for (i = 1; i <= NF; ++i) if ((t == "points" && (col[i] == "u" || col[i] == "v" || col[i] == "offset")) ||
      (t == "skeleton" && (col[i] == "u" || col[i] == "v" || col[i] == "radius")) ||
      (t == "frames" && col[i] ~ /^origin_/) || (t == "loops" && (col[i] == "length" || col[i] == "cell")))
      $i = sprintf("%.15g", $i / 1000)
    else if (t == "loops" && col[i] == "area") $i = sprintf("%.15g", $i / 1e6)
    print }' "$TMP/mm.stream" > "$TMP/m.stream"
expect 0 "smooth a stream in metres" -- "$BIN/smooth" "$TMP/m.stream" -o "$TMP/m.smooth"
check "smooth writes mm" -- grep -q "^# units mm$" "$TMP/m.smooth"
"$BIN/smooth" "$TMP/mm.stream" | "$BIN/fitspline" | "$BIN/camber" --params "$TMP/s_mm.csv" > /dev/null
"$BIN/fitspline" "$TMP/m.smooth" | "$BIN/camber" --params "$TMP/s_m.csv" > /dev/null
check "a stream in metres gives the mm parameters" -- same_params "$TMP/s_mm.csv" "$TMP/s_m.csv"

# Unknown units are refused, naming the known ones.
expect 2 "slice --units furlong" -- "$BIN/slice" "$TMP/turbine.xyz" --count 3 --units furlong
check "the known units are named" -- grep -q "mm, m, cm, um, in" "$TMP/err"
sed 's/^# units mm$/# units furlong/' "$TMP/mm.stream" > "$TMP/furlong.stream"
expect 1 "smooth refuses a stream in furlongs" -- "$BIN/smooth" "$TMP/furlong.stream"
check "naming the stream and the unit" -- grep -q "furlong.stream.*furlong" "$TMP/err"
finish
