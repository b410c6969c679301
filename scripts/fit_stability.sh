#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# How far fitspline's curves move when its input moves by 1e-8..1e-6 mm (docs/FITSPLINE.md,
# "Stability to the last bits of the input"), with the defaults and with each variant given:
# writes the smoothed streams of generated whole-blade scans once (evaluate_pipeline
# --full-scan with EVALUATE_STREAMS), then prints bench/fit_stability's summary line per
# preset and variant.
# Usage: scripts/fit_stability.sh [VARIANT...]   a variant is a quoted list of fit_stability
#        flags, e.g. '--first-iterations 12 --bridge-factor 4' (the default when none is given)
# Env:   BUILD_DIR (default build), WORK (default /tmp/libsection-stability),
#        FIRST_SEED (default 1), SEEDS (default 25), TURBINE_SEEDS (default 10), TRIALS (default 3)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${BUILD_DIR:-build}"
WORK="${WORK:-/tmp/libsection-stability}"
FIRST_SEED="${FIRST_SEED:-1}"
SEEDS="${SEEDS:-25}"
TURBINE_SEEDS="${TURBINE_SEEDS:-10}"
TRIALS="${TRIALS:-3}"
VARIANTS=("$@")
[ ${#VARIANTS[@]} -eq 0 ] && VARIANTS=("--first-iterations 12 --bridge-factor 4")
if [ -f "$BUILD/CMakeCache.txt" ]; then
  cmake --build "$BUILD" --target evaluate_pipeline fit_stability >/dev/null
fi
mkdir -p "$WORK"
# The streams depend on the seeds and the build only: written once per seed range.
streams() {
  local preset=$1 first=$2 count=$3 last=$(($2 + $3 - 1))
  [ -f "$WORK/s_${preset}_${last}.smooth" ] && [ -f "$WORK/s_${preset}_${first}.smooth" ] && return
  EVALUATE_STREAMS="$WORK/s" "$BUILD/bench/evaluate_pipeline" --first-seed "$first" --seeds "$count" \
    --preset "$preset" --full-scan --quiet >/dev/null
}
streams compressor "$FIRST_SEED" "$SEEDS"
streams turbine "$FIRST_SEED" "$TURBINE_SEEDS"
for variant in "" "${VARIANTS[@]}"; do
  echo "# ${variant:-defaults}"
  for preset in compressor turbine; do
    count=$SEEDS
    [ "$preset" = turbine ] && count=$TURBINE_SEEDS
    # shellcheck disable=SC2086  # a variant is a list of flags
    "$BUILD/bench/fit_stability" --streams "$WORK/s" --first-seed "$FIRST_SEED" --seeds "$count" \
      --preset "$preset" --trials "$TRIALS" $variant | tail -1
  done
done
