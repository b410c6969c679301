#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The man pages and bash completion the build makes from each tool's --help
# (cmake/ToolDocs.cmake): every tool has both, the pages render with their NAME and
# options, and the completion completes flags and a flag's choices.
. "$(dirname "$0")/lib.sh"
share="$BIN/../share"
for tool in "$BIN"/*; do
  [ -x "$tool" ] && [ -f "$tool" ] || continue
  name="$(basename "$tool")"
  completion="$share/bash-completion/completions/$name"
  check "$name: a completion" -- test -s "$completion"
  check "$name: the completion is valid bash" -- bash -n "$completion"
  if command -v help2man >/dev/null 2>&1; then
    page="$share/man/man1/$name.1"
    check "$name: a man page" -- test -s "$page"
    check "$name: the page's NAME line" -- grep -q "^$name \\\\- " "$page"
    check "$name: the page lists --help" -- grep -q "help" "$page"
  fi
done
# Completing: a flag from its start, and --units' choices.
complete_words() {
  bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _libsection_slice; echo "${COMPREPLY[*]}"' \
    _ "$share/bash-completion/completions/slice" "$@"
}
check "slice --sl completes to --slab" -- test "$(complete_words slice --sl)" = "--slab"
check "slice --units completes to the units" -- test "$(complete_words slice --units "")" = "mm m cm um in"
check "slice --slab takes a number, no file names" -- test -z "$(complete_words slice --slab "")"
finish
