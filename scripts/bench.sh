#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Benchmark driver: libsection against the Python a user would write instead, on the
# same generated files. For each cloud size (millions of points; the full turbine blade
# at 0.08 mm spacing is ~0.94 M points, so spacing = 0.08 sqrt(0.94 / M)) it times, with
# /usr/bin/time (wall s, peak MB, and user + system CPU of every process), each input file
# read into the page cache before every run:
#   read     bench/bench_read on the binary PLY and on the XYZ text (points per second)
#   slice    `slice FILE.ply --count 20`
#   pipe     `slice --count 20 | smooth | fitspline | camber` (peak = the largest process):
#            CPU ms per section of each stage and of the whole pipe, and the same pipe
#            with `slice --band-spacing 0` (the slab alone, no drift-corrected band)
#   peer     scripts/peers/slice_peer.py: numpy slab mask, NN chaining, splprep per section
#   first    when the first section's part comes out of `slice | smooth | fitspline`
#            (scripts/pipe_timeline.py): a section's latency through the pipe
#   ratios   the peer's wall time per section over the pipe's (> 1: we are faster), and
#            the pipe's wall time over reading the PLY file (bench_read)
# then a scan in sparse rows (`bladegen --rows 20 --row-pitch 3 --spacing 0.2`, each row
# a section: `slice ROWS.ply`, the peer with --rows), unless ROWS=0, and a ~1 M triangle
# mesh: `slice MESH --count 20` against trimesh section_multiplane
# (scripts/peers/mesh_peer.py), unless MESH=0.
# Usage: scripts/bench.sh [SIZES...]       (default 0.25 0.5 1 5 20)
# Env:   BUILD_DIR (default build), BENCH_DIR (default /tmp/libsection-bench),
#        REPEAT (default 1: runs per timing, the minimum is kept), PEER=0 skips Python,
#        PEER_PYTHON (default python3: the interpreter that runs the peers),
#        ROWS=0 skips the rows case, MESH=0 the mesh.
set -euo pipefail
cd "$(dirname "$0")/.."
SRC=$PWD
BUILD="${BUILD_DIR:-build}"
WORK="${BENCH_DIR:-/tmp/libsection-bench}"
REPEAT="${REPEAT:-1}"
PEER="${PEER:-1}"
# The peers' interpreter: a virtual environment with numpy, scipy, trimesh, networkx (trimesh
# 4 sections a mesh with it) and plyfile keeps their PyPI versions away from the Debian
# numpy that the Python module's tests import.
PEER_PYTHON="${PEER_PYTHON:-python3}"
# A build tree is brought up to date; a copy of built tools and libraries (tools/, bench/,
# libsection/, as /work/baseline-*) is run as it is.
if [ -f "$BUILD/CMakeCache.txt" ]; then
  cmake --build "$BUILD" --target bladegen slice smooth fitspline camber bench_read >/dev/null
fi
export LD_LIBRARY_PATH="$BUILD/libsection:$BUILD/libsection/extras${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
T="$BUILD/tools"
mkdir -p "$WORK"
SIZES=("$@")
[ ${#SIZES[@]} -eq 0 ] && SIZES=(0.25 0.5 1 5 20)

# warm ARGS...: reads every file among ARGS into the page cache before a timed run, so that
# every run reads its input from memory (a kernel may reclaim idle cache within seconds:
# docs/PERFORMANCE.md), and reading and the pipe compare alike.
warm() {
  local a
  for a in "$@"; do
    if [ -f "$a" ]; then cat "$a" > /dev/null; fi
  done
}

# since T0: the seconds from T0 (date +%s.%N) to now, from the clock in ns (/usr/bin/time's
# %e counts in 10 ms steps: a quarter of reading the 5 M point file).
since() { awk "BEGIN{printf \"%.3f\", $(date +%s.%N) - $1}"; }

# timed CMD...: runs CMD REPEAT times (stdout to last.out), sets WALL and PEAK_MB to the minimum.
timed() {
  local w kb t0
  WALL=""; PEAK_MB=""
  for _ in $(seq "$REPEAT"); do
    warm "$@"
    t0=$(date +%s.%N)
    /usr/bin/time -f "%M" -o "$WORK/time.txt" "$@" > "$WORK/last.out" 2> "$WORK/last.err" ||
      { echo "bench: failed: $*" >&2; sed 's/^/  /' "$WORK/last.err" | tail -5 >&2; return 1; }
    w=$(since "$t0")
    read -r kb < <(tail -1 "$WORK/time.txt")
    if [ -z "$WALL" ] || awk "BEGIN{exit !($w < $WALL)}"; then WALL=$w; fi
    local mb=$((kb / 1024))
    if [ -z "$PEAK_MB" ] || [ "$mb" -lt "$PEAK_MB" ]; then PEAK_MB=$mb; fi
  done
}

STAGES=(slice smooth fitspline camber)
# pipe_timed SLICE_ARGS...: `slice SLICE_ARGS | smooth | fitspline | camber`, each process
# under /usr/bin/time, REPEAT times. Sets WALL (minimum), PEAK_MB (the largest process of
# the fastest run), FITTED (sections in camber's params table) and CPU_<stage> (user +
# system seconds, the minimum over the runs) and CPU_ALL (their sum).
pipe_timed() {
  local args="" a w best="" s
  for a in "$@"; do args+=" '$a'"; done
  local cmd="set -o pipefail; /usr/bin/time -f '%U %S %M' -o '$WORK/cpu.slice' '$T/slice'$args 2>/dev/null"
  for s in smooth fitspline camber; do
    cmd+=" | /usr/bin/time -f '%U %S %M' -o '$WORK/cpu.$s' '$T/$s' 2>/dev/null"
  done
  for s in "${STAGES[@]}"; do eval "CPU_$s="; done
  for _ in $(seq "$REPEAT"); do
    local t0
    warm "$@"
    t0=$(date +%s.%N)
    bash -c "$cmd" > "$WORK/last.out" || { echo "bench: failed: $cmd" >&2; return 1; }
    w=$(since "$t0")
    local peak=0
    for s in "${STAGES[@]}"; do
      local u sy kb c old
      read -r u sy kb < <(tail -1 "$WORK/cpu.$s")
      c=$(awk "BEGIN{print $u + $sy}")
      old=$(eval "echo \${CPU_$s}")
      if [ -z "$old" ] || awk "BEGIN{exit !($c < $old)}"; then eval "CPU_$s=$c"; fi
      [ $((kb / 1024)) -gt "$peak" ] && peak=$((kb / 1024))
    done
    if [ -z "$best" ] || awk "BEGIN{exit !($w < $best)}"; then best=$w; PEAK_MB=$peak; fi
  done
  WALL=$best
  CPU_ALL=$(awk "BEGIN{print $CPU_slice + $CPU_smooth + $CPU_fitspline + $CPU_camber}")
  FITTED=$(awk -F, '/^# table params/{t=1; getline; next} /^#/{t=0} t&&NF>1{n++} END{print n+0}' "$WORK/last.out")
}

# first_fitted SLICE_ARGS...: FIRST = the seconds until the first part comes out of
# `slice SLICE_ARGS | smooth | fitspline` (scripts/pipe_timeline.py; the least of REPEAT
# runs): each stage passes a section on as soon as it is done, so this is the latency of a
# section through the pipe (camber holds every part for its checks across the blade).
first_fitted() {
  local args="" a f
  for a in "$@"; do args+=" '$a'"; done
  FIRST=""
  for _ in $(seq "$REPEAT"); do
    warm "$@"
    f=$(python3 "$SRC/scripts/pipe_timeline.py" "'$T/slice'$args 2>/dev/null | '$T/smooth' | '$T/fitspline' 2>/dev/null" |
      sed -nE 's/^parts at ([0-9.]+).*/\1/p')
    [ -n "$f" ] || { echo "bench: no part came out of slice$args | smooth | fitspline" >&2; return 1; }
    if [ -z "$FIRST" ] || awk "BEGIN{exit !($f < $FIRST)}"; then FIRST=$f; fi
  done
}

row() { printf '%-7s %-22s %9s %9s %s\n' "$@"; }
per() { awk "BEGIN{printf \"%.1f\", 1000 * $1 / ($2 > 0 ? $2 : 1)}"; }

# bench_pipe LABEL PLY PEER_ARGS -- SLICE_ARGS...: the pipe, its stages' CPU, the peer.
bench_pipe() {
  local m=$1 ply=$2 peer_args=$3; shift 4
  pipe_timed "$ply" "$@"
  local pipe_s=$WALL fitted=$FITTED
  row "$m" "pipe to camber" "$WALL" "$PEAK_MB" "$fitted sections, CPU $(per "$CPU_ALL" "$fitted") ms/section"
  row "$m" "  CPU ms/section" "" "" "slice $(per "$CPU_slice" "$fitted"), smooth $(per "$CPU_smooth" "$fitted"), fitspline $(per "$CPU_fitspline" "$fitted"), camber $(per "$CPU_camber" "$fitted")"
  if [ -n "${READ_S:-}" ]; then
    row "$m" "pipe / read PLY" "" "" "$(awk "BEGIN{printf \"%.1fx\", $pipe_s / ($READ_S > 0.005 ? $READ_S : 0.005)}")"
  fi
  first_fitted "$ply" "$@"
  row "$m" "first section fitted" "$FIRST" "" "its part out of slice | smooth | fitspline (camber holds all)"
  if [ "$PEER" = 1 ]; then
    # shellcheck disable=SC2086
    timed "$PEER_PYTHON" "$SRC/scripts/peers/slice_peer.py" "$ply" $peer_args
    local peer_fitted
    peer_fitted=$(sed -E 's/.*sections=([0-9]+).*/\1/' "$WORK/last.out")
    row "$m" "python peer (spline)" "$WALL" "$PEAK_MB" "$peer_fitted sections"
    row "$m" "ratio per section" "" "" \
      "$(python3 -c "print(f'{($WALL/max($peer_fitted,1))/($pipe_s/max($fitted,1)):.1f}x')")"
    sed 's/^/        peer: /' "$WORK/last.out"
  fi
}

echo "# libsection benchmark, $(date -u +%FT%TZ), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
row Mpts step wall_s peak_MB figure
for m in "${SIZES[@]}"; do
  spacing=$(python3 -c "import math; print(0.08*math.sqrt(0.94/$m))")
  ply="$WORK/blade_${m}M.ply"
  xyz="$WORK/blade_${m}M.xyz"
  [ -f "$ply" ] || "$T/bladegen" --kind turbine --points --spacing "$spacing" --noise 0.005 --seed 3 -o "$ply"
  [ -f "$xyz" ] || "$T/bladegen" --kind turbine --points --spacing "$spacing" --noise 0.005 --seed 3 -o "$xyz"
  for f in "$ply" "$xyz"; do
    timed "$BUILD/bench/bench_read" "$f"
    [ "$f" = "$ply" ] && READ_S=$WALL
    rate=$(sed -E 's/.* = ([0-9.]+) million points.*/\1/' "$WORK/last.out")
    row "$m" "read ${f##*.}" "$WALL" "$PEAK_MB" "${rate} Mpt/s"
  done
  timed "$T/slice" "$ply" --count 20
  row "$m" "slice 20" "$WALL" "$PEAK_MB" ""
  bench_pipe "$m" "$ply" "--count 20" -- --count 20
  # The same pipe with the slab alone (no drift-corrected band: what a sparse scan costs).
  pipe_timed "$ply" --count 20 --band-spacing 0
  row "$m" "pipe, slab alone" "$WALL" "$PEAK_MB" "CPU $(per "$CPU_ALL" "$FITTED") ms/section"
done

if [ "${ROWS:-1}" = 1 ]; then
  rows="$WORK/blade_rows20.ply"
  [ -f "$rows" ] || "$T/bladegen" --kind turbine --rows 20 --row-pitch 3 --spacing 0.2 --noise 0.005 --seed 3 \
    -o "$rows"
  timed "$BUILD/bench/bench_read" "$rows"
  READ_S=$WALL
  row rows "read ply" "$WALL" "$PEAK_MB" "$(sed -E 's/.*: ([0-9]+) points.*/\1/' "$WORK/last.out") points"
  bench_pipe rows "$rows" "--rows" --
fi

if [ "${MESH:-1}" = 1 ]; then
  mesh="$WORK/blade_mesh_1M.ply"
  [ -f "$mesh" ] || "$T/bladegen" --kind turbine --mesh --profile-points 2000 --layers 251 -o "$mesh"
  timed "$T/slice" "$mesh" --count 20
  slice_s=$WALL
  row mesh "slice 20 (1M tri)" "$WALL" "$PEAK_MB" ""
  if [ "$PEER" = 1 ]; then
    timed "$PEER_PYTHON" "$SRC/scripts/peers/mesh_peer.py" "$mesh" --count 20
    row mesh "trimesh multiplane" "$WALL" "$PEAK_MB" "$(python3 -c "print(f'{$WALL/$slice_s:.1f}x')")"
    sed 's/^/        peer: /' "$WORK/last.out"
  fi
fi
