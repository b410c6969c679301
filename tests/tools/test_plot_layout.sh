#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The plot's drawings as a browser lays them out (headless Chromium; tests/tools/plot_boxes.js
# measures each element's box): two sections of a generated blade, one with an issue far
# longer than a line and one whose LE circle is a wrong fit 500 mm in radius; every text
# within its drawing and its view, no text block over a view or another text, insets that
# magnify, and the HTML page's pan and zoom. Skipped (exit 0, said on stdout) without Chromium.
source "$(dirname "$0")/lib.sh"
browser="$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)"
if [ -z "$browser" ]; then
  echo "test_plot_layout: skipped: no chromium (Debian: apt-get install chromium)"
  exit 0
fi

expect 0 "bladegen --mesh" -- "$BIN/bladegen" --mesh -o "$TMP/blade.stl"
"$BIN/slice" "$TMP/blade.stl" --at 5,30 2>/dev/null | "$BIN/smooth" 2>/dev/null | "$BIN/fitspline" 2>/dev/null |
  "$BIN/camber" > "$TMP/stream.txt" 2>/dev/null
check "the pipe writes a camber stream" -- grep -q "^# table params" "$TMP/stream.txt"
long="the measured points lie in two layers"
for i in $(seq 1 30); do long="$long, and this sentence goes on as a long warning does ($i)"; done
# Section 0 gets the long issue; section 1's LE radius becomes a wrong fit of 500 mm.
le_radius() {  # FILE SECTION: the section's le_radius in the params table
  awk -F, -v s="$2" '/^# table / { t = substr($0, 9); next }
    t == "params" && /^section,/ { for (i = 1; i <= NF; ++i) if ($i == "le_radius") c = i; next }
    t == "params" && $1 == s { print $c }' "$1"
}
awk -F, -v OFS=, -v long="$long" '
  NR == 2 { print "# issue section=0 loop=0 stage=camber message=" long }
  /^# table / { t = substr($0, 9); print; next }
  t == "params" && /^section,/ { for (i = 1; i <= NF; ++i) { if ($i == "le_radius") c = i; if ($i == "flags") f = i }
    print; next }
  t == "params" && $1 == 1 && c { $c = 500; if (f) $f = 276824124 }  # and six checks failed: their lines wrap
  { print }' "$TMP/stream.txt" > "$TMP/odd.txt"
check "section 1 has the wrong LE radius" -- test "$(le_radius "$TMP/odd.txt" 1)" = 500
check "section 0 keeps its LE radius" -- test "$(le_radius "$TMP/odd.txt" 0)" = "$(le_radius "$TMP/stream.txt" 0)"

expect 0 "plot --html" -- "$BIN/plot" "$TMP/odd.txt" --html -o "$TMP/page.html"
check "section 1's flagged values carry their failed checks" -- grep -q "param-fails" "$TMP/page.html"
# The page holds each section's SVG as plot_svg writes it: one browser run checks them all.
cp "$SRC/tests/tools/plot_boxes.js" "$TMP/"
sed -e 's|<body>|<body data-page="html">|' -e 's|</body>|<script src="plot_boxes.js"></script></body>|' \
  "$TMP/page.html" > "$TMP/page-check.html"

SANDBOX=(); [ "$(id -u)" -eq 0 ] && SANDBOX=(--no-sandbox)
for page in page-check; do
  timeout 120 "$browser" --headless --disable-gpu "${SANDBOX[@]}" --window-size=1200,900 --dump-dom \
    "file://$TMP/$page.html" 2>/dev/null | sed -n '/<pre id="report">/,/<\/pre>/p' > "$TMP/$page.report"
  check "$page: the browser ran the checks" -- grep -q "^ok " "$TMP/$page.report"
  grep "^FAIL" "$TMP/$page.report" | sed "s/^/  $page: /"
  check "$page: no box check failed" -- test "$(grep -c '^FAIL' "$TMP/$page.report")" = 0
done
check "the page zooms, pans and resets" -- test "$(grep -c '^ok \(the wheel\|a drag\|a double\)' "$TMP/page-check.report")" = 3
finish
