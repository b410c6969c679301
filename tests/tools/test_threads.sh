#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The tools' output is byte-identical with --threads 1 and --threads 2 (sections are
# processed in parallel but stored by index), through slice | smooth | fitspline | camber.
set -euo pipefail
BIN=${SECTION_BIN:?SECTION_BIN must point to the tool directory}
SRC=${SECTION_SRC:?SECTION_SRC must point to the source tree}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "test_threads: FAIL: $*" >&2; exit 1; }

for tool in slice smooth fitspline camber; do
  "$BIN/$tool" --help | grep -q -- "--threads" || fail "$tool --help does not mention --threads"
done
set +e
"$BIN/smooth" --threads -1 < /dev/null > /dev/null 2>&1; rc=$?
set -e
[ $rc -eq 2 ] || fail "--threads -1 exited $rc, expected 2"

# Four planes through the example blade, plus one above it that fails in every run.
for t in 1 2; do
  "$BIN/slice" "$SRC/data/example_blade.ply" --normal 0,0,1 --at 8,20,32,44,500 --threads $t \
    > "$TMP/slice$t" 2> /dev/null
  "$BIN/smooth" --threads $t < "$TMP/slice$t" > "$TMP/smooth$t"
  "$BIN/fitspline" --threads $t --samples 40 < "$TMP/smooth$t" > "$TMP/fit$t"
  "$BIN/camber" --threads $t --allow-partial < "$TMP/fit$t" > "$TMP/camber$t" 2> /dev/null
done
for stage in slice smooth fit camber; do
  # The history line records the command (and so the --threads value): compare the rest.
  cmp -s <(grep -v '^# history' "$TMP/${stage}1") <(grep -v '^# history' "$TMP/${stage}2") ||
    fail "$stage output differs between --threads 1 and --threads 2"
done
grep -q '^# table params' "$TMP/camber2" || fail "no params table at the end of the pipe"
[ "$(grep -c '^# issue' "$TMP/camber2")" -ge 1 ] || fail "the plane above the blade is not reported"
echo "test_threads: ok"
