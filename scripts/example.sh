#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sets up, builds, and runs the whole pipe on the bundled example blade:
# slice -> smooth -> fitspline -> camber, printing each section's parameters, then compare
# against the blade's nominal with tolerances, printing the report. The example
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
  # The params for people (full precision: params.csv); its warnings were printed above.
  echo "camber: $OUT/camber.csv, params: $OUT/params.csv"; echo
  "$BIN/camber" "$OUT/splines.csv" --format table 2>/dev/null
fi
# The inspection: the sections against the blade's nominal (its exact design as a mesh)
# with data/example_tolerances.csv; exit 4 = a value failed, 5 = one was not measured.
if [ -x "$BIN/compare" ]; then
  "$BIN/bladegen" --kind turbine --mesh --profile-points 4000 --layers 16 -o "$OUT/nominal.stl"
  code=0
  "$BIN/compare" "$OUT/camber.csv" --nominal "$OUT/nominal.stl" --tolerances data/example_tolerances.csv \
    --report "$OUT/report.txt" > "$OUT/compared.csv" || code=$?
  [ "$code" -eq 0 ] || [ "$code" -eq 4 ] || [ "$code" -eq 5 ] || [ "$code" -eq 6 ] || exit "$code"
  echo; echo "compare: $OUT/compared.csv (exit $code), report: $OUT/report.txt"; cat "$OUT/report.txt"
fi
# The Python module, installed for the user (python3 -c "import libsection"), and the same
# pipe in Python (examples/pipe.py).
if [ "${SECTION_PYTHON:-1}" != 0 ]; then
  bash scripts/python.sh install
  echo; "${PYTHON:-$(command -v /usr/bin/python3 || command -v python3)}" examples/pipe.py data/example_blade.ply
fi
