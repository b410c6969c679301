#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the library, tools and tests with AddressSanitizer + UndefinedBehaviorSanitizer
# into build-asan/ (benchmarks off, -O1 to keep the build short) and runs every test
# with ctest, then the robustness suite again under a memory and a file size cap. Any
# sanitizer report aborts the process, so the test fails.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${ASAN_BUILD_DIR:-build-asan}"
GEN=()
command -v ninja >/dev/null 2>&1 && GEN=(-G Ninja)
cmake -S . -B "$BUILD_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DSECTION_SANITIZE=ON -DSECTION_BUILD_BENCH=OFF
cmake --build "$BUILD_DIR" -j "$(nproc)"
# abort_on_error: a report ends in SIGABRT (exit 134), which no test mistakes for the tools'
# exit 1 on bad data. Leak checking stays on; tests/robustness/lsan.supp lists the leaks of
# third-party libraries we cannot fix.
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:abort_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$PWD/tests/robustness/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
cd "$BUILD_DIR"
ctest --output-on-failure -j "$(nproc)" --timeout 1500
# The robustness suite once more under caps: ASan maps terabytes of shadow memory up front,
# so `ulimit -v` cannot be set; its own cap on the resident memory stands for it (a run past
# 3 GB is a failure), with a file size cap beside it (docs/ROBUSTNESS.md, "CI").
ASAN_OPTIONS="$ASAN_OPTIONS:hard_rss_limit_mb=3072" bash -c 'ulimit -Sf 262144 &&
  ctest --output-on-failure -j "$(nproc)" --timeout 1500 -R "robustness|hostile"'
