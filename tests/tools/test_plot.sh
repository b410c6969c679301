#!/usr/bin/env bash
# Black-box tests of the plot tool: help, usage errors, bad data, a stream that stops after
# slice, a full camber stream as SVG, as a directory of SVGs and as one HTML page.
set -euo pipefail
bin="${SECTION_BIN:?SECTION_BIN must name the tool directory}"
plot="$bin/plot"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "test_plot: FAILED: $*" >&2; exit 1; }
expect_exit() {  # expected-code command...
  local want="$1"; shift
  set +e; "$@" > "$tmp/out" 2> "$tmp/err"; local got=$?; set -e
  [ "$got" = "$want" ] || fail "'$*' exited $got, expected $want: $(cat "$tmp/err")"
}

expect_exit 0 "$plot" --help
grep -q "draw the sections" "$tmp/out" || fail "--help does not describe the tool"
expect_exit 0 "$plot" --version
expect_exit 2 "$plot" --width 5
expect_exit 2 "$plot" --html --section 0
expect_exit 2 "$plot" --no-such-flag

# A stream that stops after slice: two sections of points (ellipses), no other table.
{
  echo "# libsection-stream 1"
  echo "# units mm"
  echo "# table points"
  echo "section,loop,index,u,v,nu,nv"
  awk 'BEGIN { for (s = 0; s < 2; ++s) for (i = 0; i < 300; ++i) { t = 2 * 3.14159265358979 * i / 300
    printf "%d,0,%d,%.9f,%.9f,%.9f,%.9f\n", s, i, 15 * cos(t), (2 + s) * sin(t), cos(t), sin(t) } }'
} > "$tmp/slice.txt"
expect_exit 0 "$plot" "$tmp/slice.txt" --section 1 -o "$tmp/slice1.svg"
head -c 5 "$tmp/slice1.svg" | grep -q "<svg" || fail "no SVG written"
[ "$(grep -o '<circle cx=' "$tmp/slice1.svg" | wc -l)" -ge 300 ] || fail "the 300 points of section 1 are not drawn"
grep -q 'class="camber"' "$tmp/slice1.svg" && fail "a slice stream has no camber line to draw"
# Several sections and no --section, --html or -o DIR: a clear error.
expect_exit 1 "$plot" "$tmp/slice.txt"
grep -q "give --section N, --html, or -o DIR" "$tmp/err" || fail "no hint for several sections: $(cat "$tmp/err")"
expect_exit 1 "$plot" "$tmp/slice.txt" --section 9 -o "$tmp/none.svg"
grep -q "section 9 is not in the stream (sections: 0, 1)" "$tmp/err" || fail "unknown section not named: $(cat "$tmp/err")"
[ ! -e "$tmp/none.svg" ] || fail "a failed plot left a file"
expect_exit 0 "$plot" "$tmp/slice.txt" -o "$tmp/dir"
[ -s "$tmp/dir/section-0.svg" ] && [ -s "$tmp/dir/section-1.svg" ] || fail "-o DIR did not write one SVG per section"

# Bad data: a malformed row names the line and exits 1.
printf '# libsection-stream 1\n# table points\nsection,loop,index,u,v\n0,0,0,1,x\n' > "$tmp/bad.txt"
expect_exit 1 "$plot" "$tmp/bad.txt"
grep -q "bad.txt:4" "$tmp/err" || fail "the error does not name line 4: $(cat "$tmp/err")"

# A full camber stream (an ellipse profile through the camber tool): every element drawn.
if [ -x "$bin/camber" ]; then
  awk 'BEGIN { print "ELLIPSE 20 x 3"; for (i = 0; i < 800; ++i) { t = 2 * 3.14159265358979 * i / 800; printf "%.9f %.9f\n", 20 * cos(t), 3 * sin(t) } }' > "$tmp/ellipse.dat"
  "$bin/camber" "$tmp/ellipse.dat" -o "$tmp/camber.txt" 2> /dev/null || fail "camber failed on the ellipse"
  expect_exit 0 "$plot" "$tmp/camber.txt" -o "$tmp/full.svg"   # one section: stdout rule not needed
  for c in curve camber station chord le-circle te-circle scale-bar param-table; do
    grep -q "class=\"$c\"" "$tmp/full.svg" || fail "class $c missing from the full drawing"
  done
  for id in s0-main s0-le s0-te; do grep -q "id=\"$id\"" "$tmp/full.svg" || fail "id $id missing"; done
  grep -qi "nan" "$tmp/full.svg" && fail "non-finite number in the SVG"
  expect_exit 0 "$plot" "$tmp/camber.txt" --html -o "$tmp/page.html"
  head -1 "$tmp/page.html" | grep -q "<!DOCTYPE html>" || fail "--html did not write a page"
  grep -q 'id="s0"' "$tmp/page.html" || fail "the page lacks section 0's drawing"
  # From standard input, --no-insets drops the insets.
  "$plot" --no-insets < "$tmp/camber.txt" > "$tmp/stdin.svg" || fail "reading standard input failed"
  grep -q 'id="s0-le"' "$tmp/stdin.svg" && fail "--no-insets still drew an inset"
fi
echo "test_plot: ok"
