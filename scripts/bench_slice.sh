#!/usr/bin/env bash
# Prints read and slice throughput and peak memory for generated turbine-blade scans of
# about 1, 5 and 20 million points (binary PLY and XYZ text), 20 planes each.
# Usage: scripts/bench_slice.sh [SIZES...]   (default: 1 5 20, millions of points)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${BUILD_DIR:-build}"
cmake --build "$BUILD" --target bladegen slice bench_read >/dev/null
WORK="${BENCH_DIR:-/tmp/libsection-bench}"
mkdir -p "$WORK"
SIZES=("$@")
[ ${#SIZES[@]} -eq 0 ] && SIZES=(1 5 20)
printf '%-8s %-6s %12s %10s %14s %12s %10s\n' points format read_s read_Mpt/s slice20_s slice_Mpt/s peak_MB
for m in "${SIZES[@]}"; do
  # The full turbine blade at 0.08 mm spacing has about 0.94 million points.
  spacing=$(python3 -c "import math; print(0.08*math.sqrt(0.94/$m))")
  ply="$WORK/blade_${m}M.ply"
  xyz="$WORK/blade_${m}M.xyz"
  [ -f "$ply" ] || "$BUILD/tools/bladegen" --kind turbine --points --spacing "$spacing" --noise 0.005 --seed 3 -o "$ply"
  [ -f "$xyz" ] || "$BUILD/tools/bladegen" --kind turbine --points --spacing "$spacing" --noise 0.005 --seed 3 -o "$xyz"
  for f in "$ply" "$xyz"; do
    line=$("$BUILD/bench/bench_read" "$f")
    n=$(echo "$line" | sed -E 's/.*: ([0-9]+) points in ([0-9.]+) s.*/\1/')
    rs=$(echo "$line" | sed -E 's/.*: ([0-9]+) points in ([0-9.]+) s.*/\2/')
    /usr/bin/time -f "%e %M" -o "$WORK/time.txt" "$BUILD/tools/slice" "$f" --count 20 > /dev/null
    read -r ss mem < "$WORK/time.txt"
    python3 - "$n" "$rs" "$ss" "$mem" "${f##*.}" <<'PY'
import sys
n, rs, ss, mem, fmt = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
print(f"{n/1e6:<8.2f} {fmt:<6} {rs:12.3f} {n/rs/1e6:10.1f} {ss:14.3f} {n/ss/1e6:12.1f} {mem/1024:10.0f}")
PY
  done
done
