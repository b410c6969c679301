#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Renders the example blade's drawings (plot: one SVG per section and the HTML page) with
# headless Chromium and checks the screenshots are not blank: each element's colour must
# cover enough pixels (measured points, curve, camber line, stations, LE and TE circles).
# Installs Debian's chromium when missing. Screenshots land in $OUT/plot/.
# With --real: also draws the real sections of $REAL_DATA (default ../shared/data/real
# beside the checkout: the LS89 vane through camber, parablade's 2D cases and the APU rotor
# (5 planes) through slice | smooth | fitspline | camber, default options) and measures
# every element's box in the browser (tests/tools/plot_boxes.js); the data stay outside the
# repository, the drawings land in $OUT/plot/real/.
set -euo pipefail
cd "$(dirname "$0")/.."
REAL=0; [ "${1:-}" = "--real" ] && REAL=1
BUILD_DIR="${BUILD_DIR:-build}"
OUT="${OUT:-example-out}"
BIN="$BUILD_DIR/tools"

if ! command -v chromium > /dev/null 2>&1; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get install -y chromium > /dev/null || { $SUDO apt-get update > /dev/null && $SUDO apt-get install -y chromium > /dev/null; }
fi
[ -f "$OUT/camber.csv" ] || BUILD_DIR="$BUILD_DIR" OUT="$OUT" bash scripts/example.sh > /dev/null
cmake --build "$BUILD_DIR" --target plot > /dev/null

mkdir -p "$OUT/plot"
"$BIN/plot" "$OUT/camber.csv" -o "$OUT/plot"
"$BIN/plot" "$OUT/camber.csv" --html -o "$OUT/plot/sections.html"

SANDBOX=(); [ "$(id -u)" -eq 0 ] && SANDBOX=(--no-sandbox)
shot() {  # file.svg|file.html width height png
  chromium --headless --disable-gpu --hide-scrollbars "${SANDBOX[@]}" --window-size="$2,$3" \
    --screenshot="$4" "file://$(realpath "$1")" > /dev/null 2>&1
  [ -s "$4" ] || { echo "check_plot: chromium wrote no screenshot of $1" >&2; exit 1; }
}
pngs=()
for svg in "$OUT"/plot/section-*.svg; do
  width=$(grep -o 'width="[0-9.]*"' "$svg" | head -1 | tr -dc '0-9.' | cut -d. -f1)
  height=$(grep -o 'height="[0-9.]*"' "$svg" | head -1 | tr -dc '0-9.' | cut -d. -f1)
  shot "$svg" "$width" "$height" "${svg%.svg}.png"
  pngs+=("${svg%.svg}.png")
done
shot "$OUT/plot/sections.html" 1100 1500 "$OUT/plot/sections.png"
pngs+=("$OUT/plot/sections.png")

if [ "$REAL" = 1 ]; then
  data="${REAL_DATA:-$(cd .. && pwd)/shared/data/real}"
  [ -d "$data" ] || data="$(cd ../.. && pwd)/shared/data/real"   # from a worktree under wt/
  [ -d "$data" ] || { echo "check_plot: no real data at $data (set REAL_DATA)" >&2; exit 2; }
  real="$OUT/plot/real"; rm -rf "$real"; mkdir -p "$real"
  pipe() { "$BIN/slice" "$@" 2>/dev/null | "$BIN/smooth" 2>/dev/null | "$BIN/fitspline" 2>/dev/null | "$BIN/camber" 2>/dev/null; }
  awk 'NF >= 4 && $1 <= 206 { printf "%.6f %.6f\n", $4 * 1000, $3 * 1000 }' "$data/ls89/point_cloud_LS89.txt" > "$real/ls89.xy"
  awk 'NF >= 4 && $1 > 207 && $1 < 405 { printf "%.6f %.6f\n", $4 * 1000, $3 * 1000 }' "$data/ls89/point_cloud_LS89.txt" | tac >> "$real/ls89.xy"
  "$BIN/camber" "$real/ls89.xy" 2>/dev/null > "$real/ls89.txt" || true
  for case in Aachen_2D Impulse_2D STD10_2D; do
    cut -f2,3 "$data/parablade/$case"/MoveSurface*.txt > "$real/$case.xy"
    pipe "$real/$case.xy" > "$real/$case.txt" || true
  done
  cut -f2,3,4 "$data/parablade/APU_rotor/MoveSurface.txt" > "$real/APU_rotor.xyz"
  pipe "$real/APU_rotor.xyz" --count 5 > "$real/APU_rotor.txt" || true
  cp tests/tools/plot_boxes.js "$real/"
  for stream in "$real"/*.txt; do
    name="$(basename "$stream" .txt)"
    "$BIN/plot" "$stream" --html -o "$real/$name.html" 2>/dev/null || continue
    sed -e 's|<body>|<body data-page="html">|' -e 's|</body>|<script src="plot_boxes.js"></script></body>|' \
      "$real/$name.html" > "$real/$name-check.html"
    chromium --headless --disable-gpu "${SANDBOX[@]}" --window-size=1200,900 --dump-dom \
      "file://$(realpath "$real/$name-check.html")" 2>/dev/null | sed -n '/<pre id="report">/,/<\/pre>/p' > "$real/$name.report"
    echo "check_plot: $name: $(grep -c '^ok' "$real/$name.report") boxes ok, $(grep -c '^FAIL' "$real/$name.report") failed, $(wc -c < "$real/$name.html") bytes"
    grep '^FAIL' "$real/$name.report" | sed 's/^/  /' || true
    ! grep -q '^FAIL' "$real/$name.report" && grep -q '^ok' "$real/$name.report" || real_failed=1
  done
  [ -z "${real_failed:-}" ] || { echo "check_plot: a real section's drawing failed its box checks" >&2; exit 1; }
fi

# Decodes each PNG (8-bit RGB/RGBA, as Chromium writes) and counts the pixels near each
# element's colour (plot_svg.cpp's style).
python3 - "${pngs[@]}" <<'EOF'
import struct, sys, zlib

def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path + ": not a PNG"
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), path + ": unexpected PNG format"
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line); prev = line
    return w, h, bpp, rows

colours = {"measured points": (0x1f, 0x77, 0xb4), "camber line": (0xd6, 0x27, 0x28),
           "stations": (0x2c, 0xa0, 0x2c), "LE circle": (0xff, 0x7f, 0x0e),
           "TE circle": (0x94, 0x67, 0xbd), "curve/text": (0x11, 0x11, 0x11)}
failed = False
for path in sys.argv[1:]:
    w, h, bpp, rows = read_png(path)
    counts = dict.fromkeys(colours, 0)
    background = 0
    for line in rows:
        for x in range(0, w * bpp, bpp):
            r, g, b = line[x], line[x + 1], line[x + 2]
            if r > 235 and g > 235 and b > 235: background += 1; continue
            for name, (cr, cg, cb) in colours.items():
                if abs(r - cr) + abs(g - cg) + abs(b - cb) < 60: counts[name] += 1
    ink = 1 - background / (w * h)
    missing = [k for k, v in counts.items() if v < 30]
    status = "ok" if ink > 0.01 and not missing else "FAILED"
    failed |= status != "ok"
    print(f"check_plot: {path}: {w}x{h}, {100 * ink:.1f}% ink, " +
          ", ".join(f"{k} {v}" for k, v in counts.items()) + f": {status}" +
          (f" (missing: {', '.join(missing)})" if missing else ""))
sys.exit(1 if failed else 0)
EOF
