#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A tool's man page from its --help and --version (help2man), for the build (cmake/ToolDocs.cmake).
# Usage: scripts/man_page.sh HELP2MAN TOOL VERSION OUT.1
set -euo pipefail
help2man="$1" tool="$2" version="$3" out="$4"
# NAME's line: the first paragraph of --help without the tool's name ("slice: cut a blade ...").
help="$("$tool" --help)"
name="$(awk 'NF == 0 { exit } { printf "%s%s", (NR > 1 ? " " : ""), $0 }' <<<"$help" | sed -E 's/^[^:]*: *//; s/\.$//')"
mkdir -p "$(dirname "$out")"
"$help2man" --no-info --no-discard-stderr --section 1 --source libsection --version-string "$version" \
  --name "$name" --output "$out.tmp" "$tool"
mv "$out.tmp" "$out"
