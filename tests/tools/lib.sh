# SPDX-License-Identifier: GPL-3.0-or-later
# Helpers for the black-box tool tests: run a tool, check its exit code and output.
set -u
BIN="${SECTION_BIN:?SECTION_BIN must point at the tool directory}"
SRC="${SECTION_SRC:?SECTION_SRC must point at the source tree}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
FAILS=0
PASSES=0

# expect CODE DESCRIPTION -- command...: runs the command, stdout to $TMP/out, stderr to $TMP/err.
expect() {
  local code="$1" what="$2"
  shift 3
  "$@" >"$TMP/out" 2>"$TMP/err" </dev/null
  local got=$?
  if [ "$got" -ne "$code" ]; then
    echo "FAIL: $what: exit $got, expected $code"; sed 's/^/  stderr: /' "$TMP/err" | head -5
    FAILS=$((FAILS + 1))
  else
    PASSES=$((PASSES + 1))
  fi
}

# check DESCRIPTION -- command: a plain assertion.
check() {
  local what="$1"
  shift 2
  if "$@"; then PASSES=$((PASSES + 1)); else echo "FAIL: $what"; FAILS=$((FAILS + 1)); fi
}

finish() {
  echo "$PASSES passed, $FAILS failed"
  [ "$FAILS" -eq 0 ]
}
