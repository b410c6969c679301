#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The shared libraries export namespace section alone, and the Python module its init
# function alone (issue 24: a host linking its own CGAL, Eigen or OpenMesh must not meet
# ours). `nm -D --defined-only` on each; fails listing every other exported symbol.
#   scripts/check_symbols.sh [BUILD_DIR or .so files...]   (default: build)
# With a directory: libsection.so, libsection_extras.so and the Python module found in it
# (lib/ of an installed prefix works too). ctest runs it as `symbols`.
set -euo pipefail
cd "$(dirname "$0")/.."
args=("$@")
[ ${#args[@]} -gt 0 ] || args=("${BUILD_DIR:-build}")
files=()
for a in "${args[@]}"; do
  if [ -d "$a" ]; then
    while IFS= read -r f; do files+=("$f"); done < <(find "$a" \( -name 'libsection.so' -o \
      -name 'libsection_extras.so' -o -name '_libsection*.so' \) \( -type f -o -type l \) | sort)
  else
    files+=("$a")
  fi
done
[ ${#files[@]} -gt 0 ] || { echo "check_symbols: no libsection .so under ${args[*]}" >&2; exit 1; }

# Mangled names allowed: namespace section's functions and variables (_ZN7section,
# _ZNK7section), its classes' typeinfo, typeinfo name, vtables and thunks; in the module
# only PyInit__libsection. Offenders are listed demangled.
library_ok='^_Z(NK?|T[ISVTC]N|Th[n0-9]*_NK?|Tv[n0-9_]*N)7section'
status=0
for f in "${files[@]}"; do
  ok="$library_ok" what="namespace section"
  case "$(basename "$f")" in _libsection*) ok='^PyInit__libsection$' what="PyInit__libsection" ;; esac
  names="$(nm -D --defined-only "$f" | awk '{ print $3 }')"
  total=$(printf '%s\n' "$names" | grep -c . || true)
  bad="$(printf '%s\n' "$names" | grep -Ev "$ok" | grep . || true)"
  if [ -n "$bad" ]; then
    status=1
    echo "check_symbols: FAILED: $f exports $(printf '%s\n' "$bad" | wc -l) of its $total symbols beside $what:" >&2
    printf '%s\n' "$bad" | head -40 | c++filt | sed 's/^/  /' >&2
    echo "  Code of the library belongs in namespace section (helpers in an anonymous namespace);" >&2
    echo "  what is exported is decided at link time by libsection/section.map (python/module.map)." >&2
  else
    echo "check_symbols: $f: $total symbols exported, all of $what"
  fi
done
exit $status
