#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Formats the C++ sources with clang-format (.clang-format at the root); with --check,
# lists the files that are not formatted and exits 1 when any. Needs clang-format (Debian:
# apt install clang-format).
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if [ "${1:-}" = --check ]; then
  # One process for all files; the names of those not formatted from its diagnostics.
  if ! out=$(clang-format --dry-run -Werror "${files[@]}" 2>&1); then
    grep -oE '^[^:]+\.(cpp|h):' <<<"$out" | sort -u | sed 's/:$//; s/^/not formatted: /'
    exit 1
  fi
  exit 0
fi
clang-format -i "${files[@]}"
