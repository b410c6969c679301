#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the libFuzzer targets (fuzz/) with clang + ASan + UBSan into build-fuzz/ and runs
# them. CI does not run this; see docs/ROBUSTNESS.md.
#
#   scripts/fuzz.sh build                 # install clang if missing, build every target
#   scripts/fuzz.sh run TARGET [SECONDS [LIBFUZZER FLAGS]]  # fuzz one target (default
#                                         # 660 s), seeded from tests/robustness/, new inputs in
#                                         # build-fuzz/corpus/TARGET; stops at the first crash
#                                         # (add -fork=1 -ignore_crashes=1 to go on past them)
#   scripts/fuzz.sh list                  # the target names
# Crashes land in build-fuzz/crashes/TARGET/; keep each one as a regression file in
# tests/robustness/ and add a case to tests/tools/test_robustness.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${FUZZ_BUILD_DIR:-build-fuzz}"
TARGETS=(fuzz_xyz fuzz_csv_cloud fuzz_ply fuzz_e57 fuzz_stl fuzz_obj_off fuzz_pipe fuzz_parts fuzz_planes)

# Seed files from the robustness corpus (and the example data) by target.
seeds_for() {
  case "$1" in
    fuzz_xyz) ls tests/robustness/*.xyz tests/robustness/*.txt 2>/dev/null ;;
    fuzz_csv_cloud) ls tests/robustness/*.csv 2>/dev/null | grep -v stream ;;
    fuzz_ply) ls tests/robustness/*.ply data/*.ply 2>/dev/null ;;
    fuzz_pts) ls tests/data/formats/*.pts 2>/dev/null ;;
    fuzz_pcd) ls tests/data/formats/*.pcd 2>/dev/null ;;
    fuzz_las) ls tests/data/formats/*.las tests/data/formats/*.laz 2>/dev/null ;;
    fuzz_e57) ls tests/data/formats/*.e57 2>/dev/null ;;
    fuzz_stl) ls tests/robustness/*.stl 2>/dev/null ;;
    fuzz_obj_off) ls tests/robustness/*.obj tests/robustness/*.off 2>/dev/null ;;
    fuzz_pipe) ls tests/robustness/*stream* tests/robustness/*.dat 2>/dev/null ;;
    fuzz_parts) ls tests/robustness/*stream* tests/robustness/parts_*.csv 2>/dev/null ;;
    fuzz_planes) ls tests/robustness/planes_*.csv 2>/dev/null ;;
  esac
}

build() {
  # clang and its runtime libraries (libFuzzer, ASan, UBSan: compiler-rt, not installed with
  # clang without its recommended packages)
  local rt; rt=$(clang++ -print-resource-dir 2>/dev/null)/lib/linux/libclang_rt.fuzzer-x86_64.a
  if ! command -v clang++ >/dev/null 2>&1 || [ ! -f "$rt" ]; then
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq --no-install-recommends clang
    local v; v=$(clang++ --version | sed -n 's/.*version \([0-9]*\).*/\1/p' | head -1)
    $SUDO apt-get install -y -qq --no-install-recommends "libclang-rt-$v-dev" ||
      $SUDO apt-get install -y -qq --no-install-recommends libclang-rt-dev
  fi
  GEN=(); command -v ninja >/dev/null 2>&1 && GEN=(-G Ninja)
  CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DSECTION_SANITIZE=ON -DSECTION_FUZZ=ON \
    -DSECTION_BUILD_TOOLS=OFF -DSECTION_BUILD_TESTS=OFF -DSECTION_BUILD_BENCH=OFF
  cmake --build "$BUILD_DIR" -j "$(nproc)" --target "${TARGETS[@]}"
}

run() {
  local target="$1" seconds="${2:-660}"
  local corpus="$BUILD_DIR/corpus/$target" crashes="$BUILD_DIR/crashes/$target"
  mkdir -p "$corpus" "$crashes"
  local seeds; seeds=$(seeds_for "$target" || true)
  for s in $seeds; do cp -n "$s" "$corpus/" 2>/dev/null || true; done
  # -rss_limit_mb: an input that makes a reader allocate gigabytes is a finding too.
  "$BUILD_DIR/fuzz/$target" "$corpus" -max_total_time="$seconds" -max_len=65536 \
    -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$crashes/" "${@:3}"
}

case "${1:-}" in
  build) build ;;
  run) shift; run "$@" ;;
  list) printf '%s\n' "${TARGETS[@]}" ;;
  *) sed -n '2,11p' "$0"; exit 2 ;;
esac
