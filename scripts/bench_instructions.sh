#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Instructions each stage of the pipe executes, counted by valgrind's callgrind with one
# thread: a figure that does not move with the machine's other work, so two builds can be
# compared on a shared machine where seconds cannot. For each size (millions of points,
# the scans of scripts/bench.sh) it runs `slice FILE.ply --count 20`, then `smooth`,
# `fitspline` and `camber` each on the stream its own build's previous stage wrote, and
# prints G instructions per stage and M instructions per section; then the same for the
# sparse rows case (ROWS=0 skips it). Needs valgrind.
# Usage: scripts/bench_instructions.sh [SIZES...]     (default 1)
# Env:   BUILD_DIR (default build; a copy of built tools as /work/baseline-* works too),
#        BENCH_DIR (default /tmp/libsection-bench, shared with bench.sh: the scans are
#        generated there once), ROWS (default 1).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${BUILD_DIR:-build}"
WORK="${BENCH_DIR:-/tmp/libsection-bench}"
command -v valgrind >/dev/null || { echo "bench_instructions: valgrind is not installed" >&2; exit 1; }
if [ -f "$BUILD/CMakeCache.txt" ]; then
  cmake --build "$BUILD" --target bladegen slice smooth fitspline camber >/dev/null
fi
export LD_LIBRARY_PATH="$BUILD/libsection:$BUILD/libsection/extras${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
T="$BUILD/tools"
OUT=$(mktemp -d "${TMPDIR:-/tmp}/bench_instructions.XXXXXX")
trap 'rm -rf "$OUT"' EXIT
mkdir -p "$WORK"
SIZES=("$@")
[ ${#SIZES[@]} -eq 0 ] && SIZES=(1)

# counted STAGE IN OUT ARGS...: runs tool STAGE on IN (one thread) under callgrind, its
# stream to OUT; sets COUNT to the instructions executed.
counted() {
  local stage=$1 in=$2 out=$3; shift 3
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$T/$stage" "$in" "$@" --threads 1 \
    > "$out" 2> "$OUT/$stage.err" ||
    { echo "bench_instructions: $stage failed:" >&2; grep -v '^==' "$OUT/$stage.err" | tail -5 >&2; return 1; }
  COUNT=$(sed -nE 's/^==[0-9]+== Collected : ([0-9]+)$/\1/p' "$OUT/$stage.err" | tail -1)
}

# pipe LABEL INPUT SLICE_ARGS...: the four stages, one line each and the total.
pipe() {
  local label=$1 input=$2; shift 2
  local total=0 sections
  counted slice "$input" "$OUT/s.csv" "$@"
  local -A n=([slice]=$COUNT)
  counted smooth "$OUT/s.csv" "$OUT/m.csv"; n[smooth]=$COUNT
  counted fitspline "$OUT/m.csv" "$OUT/f.csv"; n[fitspline]=$COUNT
  counted camber "$OUT/f.csv" "$OUT/k.csv"; n[camber]=$COUNT
  sections=$(awk -F, '/^# table params/{t=1; getline; next} /^#/{t=0} t&&NF>1{c++} END{print c+0}' "$OUT/k.csv")
  for s in slice smooth fitspline camber total; do
    local c
    if [ "$s" = total ]; then c=$total; else c=${n[$s]}; total=$((total + c)); fi
    printf '%-6s %-10s %8.3f G %9.1f M/section\n' "$label" "$s" \
      "$(awk "BEGIN{print $c / 1e9}")" "$(awk "BEGIN{print $c / 1e6 / ($sections > 0 ? $sections : 1)}")"
  done
}

echo "# instructions (callgrind, one thread), $(date -u +%FT%TZ), build $BUILD"
for m in "${SIZES[@]}"; do
  spacing=$(python3 -c "import math; print(0.08*math.sqrt(0.94/$m))")
  ply="$WORK/blade_${m}M.ply"
  [ -f "$ply" ] || "$T/bladegen" --kind turbine --points --spacing "$spacing" --noise 0.005 --seed 3 -o "$ply"
  pipe "$m" "$ply" --count 20
done
if [ "${ROWS:-1}" = 1 ]; then
  rows="$WORK/blade_rows20.ply"
  [ -f "$rows" ] || "$T/bladegen" --kind turbine --rows 20 --row-pitch 3 --spacing 0.2 --noise 0.005 --seed 3 \
    -o "$rows"
  pipe rows "$rows" --rows
fi
