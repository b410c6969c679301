#!/usr/bin/env bash
# Sets up, builds, and runs the whole pipe on the bundled example blade:
# slice -> smooth -> fitspline -> camber, printing each section's parameters. The example
# scan's two views are merged 15 um apart, and fitspline says so (two layers of points).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
BIN="${BUILD_DIR:-build}/tools"
OUT="${OUT:-example-out}"
mkdir -p "$OUT"
"$BIN/slice" data/example_blade.ply --normal 0,0,1 --at 12,20,28 > "$OUT/sections.csv"
echo "sections: $OUT/sections.csv"
if [ -x "$BIN/smooth" ]; then "$BIN/smooth" "$OUT/sections.csv" > "$OUT/smoothed.csv"; echo "smoothed: $OUT/smoothed.csv"; fi
if [ -x "$BIN/fitspline" ]; then "$BIN/fitspline" "$OUT/smoothed.csv" --samples 400 > "$OUT/splines.csv"; echo "splines: $OUT/splines.csv"; fi
if [ -x "$BIN/camber" ]; then
  "$BIN/camber" "$OUT/splines.csv" --params "$OUT/params.csv" > "$OUT/camber.csv"
  echo "camber: $OUT/camber.csv"; echo; column -s, -t "$OUT/params.csv" 2>/dev/null || cat "$OUT/params.csv"
fi
# The Python module, installed for the user (python3 -c "import libsection"), and the same
# pipe in Python (examples/pipe.py).
if [ "${SECTION_PYTHON:-1}" != 0 ]; then
  bash scripts/python.sh install
  echo; "${PYTHON:-$(command -v /usr/bin/python3 || command -v python3)}" examples/pipe.py data/example_blade.ply
fi
