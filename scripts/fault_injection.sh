#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# CI stage: the robustness suite (tests/tools/test_robustness.sh and test_hostile.sh) run
# again under hostile limits of its environment, on a built tree (docs/ROBUSTNESS.md):
#   1. a low address space (ulimit -v 2 GB): the tools' memory limit shrinks with it,
#      threads may not start;
#   2. a file size cap (ulimit -f 256 MB);
#   3. every run of slice, smooth, fitspline and camber with --threads 2.
# Each must pass as it does without them. About a minute per round.
# Usage: scripts/fault_injection.sh [BUILD_DIR]   (default build/)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(cd "${1:-build}" && pwd)
SUITE=(tests/tools/test_robustness.sh tests/tools/test_hostile.sh)
export SECTION_SRC=$PWD
fail=0

# round NAME LIMITS BIN: the suite with the tools of BIN under the shell limits LIMITS.
round() {
  local name=$1 limits=$2 bin=$3
  for t in "${SUITE[@]}"; do
    if SECTION_BIN=$bin bash -c "$limits; bash $t" >"$WORK/log" 2>&1; then
      echo "fault_injection: $name: $(basename "$t"): $(tail -n 1 "$WORK/log")"
    else
      echo "fault_injection: $name: $(basename "$t") FAILED:"; grep -E "^FAIL|failed" "$WORK/log" | head -20
      fail=1
    fi
  done
}

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# Tools that run with --threads 2 unless the test gives --threads (or asks for help).
mkdir -p "$WORK/bin"
for tool in "$BUILD"/tools/*; do
  [ -x "$tool" ] && [ -f "$tool" ] || continue
  name=$(basename "$tool")
  case "$name" in
    slice | smooth | fitspline | camber)
      cat >"$WORK/bin/$name" <<WRAP
#!/usr/bin/env bash
for a in "\$@"; do case "\$a" in --threads | --threads=* | -h | --help | --version) exec "$tool" "\$@" ;; esac; done
exec "$tool" "\$@" --threads 2
WRAP
      chmod +x "$WORK/bin/$name" ;;
    *) ln -s "$tool" "$WORK/bin/$name" ;;
  esac
done

round "ulimit -v 2 GB" "ulimit -Sv 2000000" "$BUILD/tools"
round "ulimit -f 256 MB" "ulimit -Sf 262144" "$BUILD/tools"
round "--threads 2" "true" "$WORK/bin"
[ $fail = 0 ] && echo "fault_injection: every round passed"
exit $fail
