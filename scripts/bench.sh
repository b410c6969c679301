#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Benchmark driver: libsection against the Python a user would write instead, on the
# same generated files. For each cloud size (millions of points; the full turbine blade
# at 0.08 mm spacing is ~0.94 M points, so spacing = 0.08 sqrt(0.94 / M)) it times, with
# /usr/bin/time (wall s, peak MB):
#   read     bench/bench_read on the binary PLY and on the XYZ text (points per second)
#   slice    `slice FILE.ply --count 20`
#   pipe     `slice --count 20 | smooth | fitspline | camber` (peak = the largest process), and
#            the same with `slice --band-spacing 0` (the slab alone, no drift-corrected band)
#   peer     scripts/peers/slice_peer.py: numpy slab mask, NN chaining, splprep per section
# and on a ~1 M triangle mesh: `slice MESH --count 20` against trimesh section_multiplane
# (scripts/peers/mesh_peer.py). Ratios are peer / libsection wall time (> 1: we are faster).
# Usage: scripts/bench.sh [SIZES...]       (default 1 5 20)
# Env:   BUILD_DIR (default build), BENCH_DIR (default /tmp/libsection-bench),
#        REPEAT (default 1: runs per timing, the minimum is kept), PEER=0 skips Python.
set -euo pipefail
cd "$(dirname "$0")/.."
SRC=$PWD
BUILD="${BUILD_DIR:-build}"
WORK="${BENCH_DIR:-/tmp/libsection-bench}"
REPEAT="${REPEAT:-1}"
PEER="${PEER:-1}"
cmake --build "$BUILD" --target bladegen slice smooth fitspline camber bench_read >/dev/null
T="$BUILD/tools"
mkdir -p "$WORK"
SIZES=("$@")
[ ${#SIZES[@]} -eq 0 ] && SIZES=(1 5 20)

# timed CMD...: runs CMD REPEAT times (stdout discarded), sets WALL and PEAK_MB to the minimum.
timed() {
  local w kb
  WALL=""; PEAK_MB=""
  for _ in $(seq "$REPEAT"); do
    /usr/bin/time -f "%e %M" -o "$WORK/time.txt" "$@" > "$WORK/last.out" 2> "$WORK/last.err" ||
      { echo "bench: failed: $*" >&2; sed 's/^/  /' "$WORK/last.err" | tail -5 >&2; return 1; }
    read -r w kb < <(tail -1 "$WORK/time.txt")
    if [ -z "$WALL" ] || awk "BEGIN{exit !($w < $WALL)}"; then WALL=$w; fi
    local mb=$((kb / 1024))
    if [ -z "$PEAK_MB" ] || [ "$mb" -lt "$PEAK_MB" ]; then PEAK_MB=$mb; fi
  done
}

echo "# libsection benchmark, $(date -u +%FT%TZ), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-7s %-22s %9s %9s %12s\n' Mpts step wall_s peak_MB figure
for m in "${SIZES[@]}"; do
  spacing=$(python3 -c "import math; print(0.08*math.sqrt(0.94/$m))")
  ply="$WORK/blade_${m}M.ply"
  xyz="$WORK/blade_${m}M.xyz"
  [ -f "$ply" ] || "$T/bladegen" --kind turbine --points --spacing "$spacing" --noise 0.005 --seed 3 -o "$ply"
  [ -f "$xyz" ] || "$T/bladegen" --kind turbine --points --spacing "$spacing" --noise 0.005 --seed 3 -o "$xyz"
  for f in "$ply" "$xyz"; do
    timed "$BUILD/bench/bench_read" "$f"
    rate=$(sed -E 's/.* = ([0-9.]+) million points.*/\1/' "$WORK/last.out")
    printf '%-7s %-22s %9s %9s %12s\n' "$m" "read ${f##*.}" "$WALL" "$PEAK_MB" "${rate} Mpt/s"
  done
  timed "$T/slice" "$ply" --count 20
  printf '%-7s %-22s %9s %9s %12s\n' "$m" "slice 20" "$WALL" "$PEAK_MB" ""
  timed bash -c "set -o pipefail; '$T/slice' '$ply' --count 20 2>/dev/null | '$T/smooth' | '$T/fitspline' | '$T/camber' 2>/dev/null"
  pipe_s=$WALL
  fitted=$(awk -F, '/^# table params/{t=1; getline; next} /^#/{t=0} t&&NF>1{n++} END{print n+0}' "$WORK/last.out")
  printf '%-7s %-22s %9s %9s %12s\n' "$m" "pipe to camber" "$WALL" "$PEAK_MB" "$fitted sections"
  # The same pipe with the slab alone (no drift-corrected band: what a sparse scan costs).
  timed bash -c "set -o pipefail; '$T/slice' '$ply' --count 20 --band-spacing 0 2>/dev/null | '$T/smooth' | '$T/fitspline' | '$T/camber' 2>/dev/null"
  printf '%-7s %-22s %9s %9s %12s\n' "$m" "pipe, slab alone" "$WALL" "$PEAK_MB" ""
  if [ "$PEER" = 1 ]; then
    timed python3 "$SRC/scripts/peers/slice_peer.py" "$ply" --count 20
    peer_fitted=$(sed -E 's/.*sections=([0-9]+).*/\1/' "$WORK/last.out")
    printf '%-7s %-22s %9s %9s %12s\n' "$m" "python peer (spline)" "$WALL" "$PEAK_MB" "$peer_fitted sections"
    ratio=$(python3 -c "print(f'{($WALL/max($peer_fitted,1))/($pipe_s/max($fitted,1)):.1f}x')")
    printf '%-7s %-22s %9s %9s %12s\n' "$m" "ratio per section" "" "" "$ratio"
    sed 's/^/        peer: /' "$WORK/last.out"
  fi
done

mesh="$WORK/blade_mesh_1M.ply"
[ -f "$mesh" ] || "$T/bladegen" --kind turbine --mesh --profile-points 2000 --layers 251 -o "$mesh"
timed "$T/slice" "$mesh" --count 20
slice_s=$WALL
printf '%-7s %-22s %9s %9s %12s\n' mesh "slice 20 (1M tri)" "$WALL" "$PEAK_MB" ""
if [ "$PEER" = 1 ]; then
  timed python3 "$SRC/scripts/peers/mesh_peer.py" "$mesh" --count 20
  printf '%-7s %-22s %9s %9s %12s\n' mesh "trimesh multiplane" "$WALL" "$PEAK_MB" \
    "$(python3 -c "print(f'{$WALL/$slice_s:.1f}x')")"
  sed 's/^/        peer: /' "$WORK/last.out"
fi
