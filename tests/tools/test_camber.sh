#!/usr/bin/env bash
# Black-box tests of the camber tool: help, usage errors, bad data, a plain profile, a
# non-blade section, and the full pipe when the other tools are built.
set -euo pipefail
bin="${SECTION_BIN:?SECTION_BIN must name the tool directory}"
camber="$bin/camber"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "test_camber: FAILED: $*" >&2; exit 1; }
expect_exit() {  # expected-code command...
  local want="$1"; shift
  set +e; "$@" > "$tmp/out" 2> "$tmp/err"; local got=$?; set -e
  [ "$got" = "$want" ] || fail "'$*' exited $got, expected $want: $(cat "$tmp/err")"
}

expect_exit 0 "$camber" --help
grep -q "mean-camber" "$tmp/out" || fail "--help does not describe the tool"
expect_exit 2 "$camber" --edge square
expect_exit 2 "$camber" --stations 0.5,abc

# An ellipse (a = 20, b = 3) as a plain profile with a title line: its camber line is
# the major axis, LE and TE points the vertices, chord 40.
awk 'BEGIN { print "ELLIPSE 20 x 3"; for (i = 0; i < 1000; ++i) { t = 2 * 3.14159265358979 * i / 1000; printf "%.9f %.9f\n", 20 * cos(t), 3 * sin(t) } }' > "$tmp/ellipse.dat"
expect_exit 0 "$camber" "$tmp/ellipse.dat" --params "$tmp/params.csv" --thickness "$tmp/thick.csv" \
  --stations 0.25,0.5,0.75 -o "$tmp/stream.txt"
head -1 "$tmp/stream.txt" | grep -q "^# libsection-stream 1" || fail "no stream written"
for t in camber params thickness sides; do
  grep -q "^# table $t$" "$tmp/stream.txt" || fail "table $t missing"
done
[ "$(wc -l < "$tmp/params.csv")" = 2 ] || fail "params CSV should have a header and one row"
[ "$(wc -l < "$tmp/thick.csv")" = 4 ] || fail "thickness CSV should have a header and 3 rows"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { d = $c["chord"] - 40; if (d < 0) d = -d; if (d > 1e-3) { print "chord " $c["chord"]; exit 1 }
    t = $c["max_thickness"] - 6; if (t < 0) t = -t; if (t > 1e-3) { print "max_thickness " $c["max_thickness"]; exit 1 } }' \
  "$tmp/params.csv" || fail "ellipse parameters are off"
awk -F, 'NR > 1 && $3 == 0.5 { t = $7 - 6; if (t < 0) t = -t; if (t > 1e-3) exit 1 }' "$tmp/thick.csv" \
  || fail "ellipse mid thickness is off"

# The stream itself is accepted as input (the spline tables are read back).
expect_exit 0 "$camber" "$tmp/stream.txt" -o "$tmp/again.txt"
grep -q "^# table params$" "$tmp/again.txt" || fail "re-reading the stream lost the params"

# Forcing the LE direction swaps the ends: the LE point is now at +u.
expect_exit 0 "$camber" "$tmp/ellipse.dat" --le-direction 1,0 --params "$tmp/p2.csv" -o /dev/null
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next } { if ($c["le_u"] < 19.9 || $c["le_by_direction"] != 1) exit 1 }' \
  "$tmp/p2.csv" || fail "--le-direction did not set the LE"

# A circle is not a blade: an issue and a warning, no params row, exit 0.
awk 'BEGIN { for (i = 0; i < 500; ++i) { t = 2 * 3.14159265358979 * i / 500; printf "%.9f,%.9f\n", 5 * cos(t), 5 * sin(t) } }' > "$tmp/circle.csv"
expect_exit 0 "$camber" "$tmp/circle.csv" -o "$tmp/circle.txt"
grep -q "not blade-like" "$tmp/err" || fail "no warning for a circle"
grep -q "^# issue section=0 .*stage=camber" "$tmp/circle.txt" || fail "no issue recorded for a circle"

# Bad data: a malformed row names the line and exits 1.
printf '1 2\n3 4\n5 x\n' > "$tmp/bad.txt"
expect_exit 1 "$camber" "$tmp/bad.txt"
grep -q "bad.txt:3" "$tmp/err" || fail "the error does not name line 3: $(cat "$tmp/err")"

# The full pipe on the example blade, when the other tools are built.
if [ -x "$bin/bladegen" ] && [ -x "$bin/slice" ] && [ -x "$bin/smooth" ] && [ -x "$bin/fitspline" ]; then
  expect_exit 0 "$bin/bladegen" --help
  if "$bin/bladegen" -o "$tmp/blade.ply" > /dev/null 2>&1; then
    "$bin/slice" "$tmp/blade.ply" --count 3 | "$bin/smooth" | "$bin/fitspline" | "$camber" --params "$tmp/pipe.csv" -o /dev/null \
      || fail "the full pipe failed"
    [ "$(wc -l < "$tmp/pipe.csv")" -ge 2 ] || fail "the full pipe wrote no params"
  fi
fi
echo "test_camber: ok"
