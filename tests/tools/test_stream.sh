#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Black-box test of the stream between the tools: split into parts, one per section, and
# closed by '# end'; a cut stream is refused; an output file appears only whole.
. "$(dirname "$0")/lib.sh"

"$BIN/bladegen" --kind turbine --points --spacing 0.1 --noise 0.005 --z-min 10 --z-max 30 --seed 3 \
  -o "$TMP/blade.ply" 2>/dev/null
expect 0 "slice 3 planes, one missing the part" -- "$BIN/slice" "$TMP/blade.ply" --at 15,20,50
cp "$TMP/out" "$TMP/sliced.csv"
check "one part per section" -- test "$(grep -c '^# part ' "$TMP/sliced.csv")" -eq 3
check "closed by # end" -- test "$(tail -n 1 "$TMP/sliced.csv")" = "# end"
check "the failed section's part has its issue" -- sh -c "sed -n '/^# part 2/,\$p' '$TMP/sliced.csv' | grep -q '^# issue section=2 '"
expect 0 "smooth the parts" -- "$BIN/smooth" "$TMP/sliced.csv"
cp "$TMP/out" "$TMP/smoothed.csv"
check "smooth keeps the parts" -- test "$(grep -c '^# part ' "$TMP/smoothed.csv")" -eq 3
check "smooth closes with # end" -- test "$(tail -n 1 "$TMP/smoothed.csv")" = "# end"
# One thread or all: the same bytes.
"$BIN/smooth" "$TMP/sliced.csv" --threads 1 > "$TMP/one_thread.csv" 2>/dev/null
check "one thread, same bytes" -- cmp -s <(grep -v "^# history" "$TMP/smoothed.csv") <(grep -v "^# history" "$TMP/one_thread.csv")

# Cut before '# end' (a tool that failed half way): every tool refuses its input cut so,
# naming the file.
"$BIN/fitspline" "$TMP/smoothed.csv" > "$TMP/fitted.csv" 2>/dev/null
head -n -1 "$TMP/sliced.csv" > "$TMP/cut_smooth.csv"
head -n -1 "$TMP/smoothed.csv" > "$TMP/cut_fitspline.csv"
head -n -1 "$TMP/fitted.csv" > "$TMP/cut_camber.csv"
head -n -1 "$TMP/fitted.csv" > "$TMP/cut_plot.csv"
for tool in smooth fitspline camber plot; do
  expect 1 "$tool refuses a cut stream" -- "$BIN/$tool" "$TMP/cut_$tool.csv"
  check "$tool says why" -- grep -q "cut_$tool.csv.*lacks its closing '# end'" "$TMP/err"
done
# A bad line in a later part: the error names its line; no '# end' is written.
line=$(grep -n '^# part 1' "$TMP/sliced.csv" | cut -d: -f1)
bad=$((line + 7))  # the loops table's row
sed "${bad}s/^1,/1,x/" "$TMP/sliced.csv" > "$TMP/bad.csv"
expect 1 "a bad line in part 1" -- "$BIN/smooth" "$TMP/bad.csv"
check "its line is named" -- grep -q "bad.csv:$bad:" "$TMP/err"
check "no '# end' after a failure" -- sh -c "! grep -q '^# end' '$TMP/out'"
# To a file: written whole or not at all.
expect 0 "smooth -o FILE" -- "$BIN/smooth" "$TMP/sliced.csv" -o "$TMP/file.csv"
check "the file is the stream" -- cmp -s <(grep -v "^# history" "$TMP/file.csv") <(grep -v "^# history" "$TMP/smoothed.csv")
check "no temporary file left" -- test ! -e "$TMP/file.csv.partial"
expect 1 "smooth -o FILE on a bad stream" -- "$BIN/smooth" "$TMP/bad.csv" -o "$TMP/none.csv"
check "no file written" -- test ! -e "$TMP/none.csv" -a ! -e "$TMP/none.csv.partial"
# To /dev/null: written there, not replaced by a file.
expect 0 "smooth -o /dev/null" -- "$BIN/smooth" "$TMP/sliced.csv" -o /dev/null
check "/dev/null is still a device" -- test -c /dev/null
# A stage writes each part as soon as it is staged, not once its input has ended or a
# block of 1 MiB has come: here the writer sends part 0 and part 1's first line, then holds
# the pipe open. smooth must have written part 0 by then (the stage after it starts on it).
rm -f "$TMP/slow.fifo"; mkfifo "$TMP/slow.fifo"
part1=$(grep -n '^# part 1' "$TMP/sliced.csv" | cut -d: -f1)
(head -n "$part1" "$TMP/sliced.csv"; exec sleep 60) > "$TMP/slow.fifo" &
writer=$!
"$BIN/smooth" "$TMP/slow.fifo" > "$TMP/early.csv" 2>/dev/null &
stage=$!
for _ in $(seq 150); do grep -q '^# part 0' "$TMP/early.csv" && break; sleep 0.1; done
check "part 0 is written while the input is still open" -- grep -q '^# part 0' "$TMP/early.csv"
check "nothing after it yet" -- sh -c "! grep -q '^# part 1\|^# end' '$TMP/early.csv'"
kill "$writer" 2>/dev/null; wait "$writer" 2>/dev/null
wait "$stage"
check "the input cut after part 0 is then refused" -- test $? -ne 0
# The whole pipe through pipes.
"$BIN/slice" "$TMP/blade.ply" --at 15,20 2>/dev/null | "$BIN/smooth" | "$BIN/fitspline" 2>/dev/null |
  "$BIN/camber" --params "$TMP/params.csv" > "$TMP/camber.csv" 2>/dev/null
check "pipe: parameters of both sections" -- test "$(grep -c '^[01],' "$TMP/params.csv")" -eq 2
check "pipe: closed by # end" -- test "$(tail -n 1 "$TMP/camber.csv")" = "# end"
finish
