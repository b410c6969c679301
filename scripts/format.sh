#!/usr/bin/env bash
# Formats the C++ sources with clang-format (.clang-format at the root); with --check,
# lists the files that are not formatted and exits 1 when any. Needs clang-format (Debian:
# apt install clang-format).
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if [ "${1:-}" = --check ]; then
  bad=0
  for f in "${files[@]}"; do
    clang-format --dry-run -Werror "$f" > /dev/null 2>&1 || { echo "not formatted: $f"; bad=1; }
  done
  exit $bad
fi
clang-format -i "${files[@]}"
