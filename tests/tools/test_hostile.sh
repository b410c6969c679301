#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Hostile environments (issue 26, docs/ROBUSTNESS.md): each numbered case of the issue
# reproduced against the tools, every run under `timeout` (a hang fails it) and, where the
# case is unbounded memory, under `ulimit -v` (skipped where it cannot be set, e.g. under
# AddressSanitizer, which maps terabytes up front). Inputs are made here from a small
# generated blade (tests/robustness/hostile.py).
source "$(dirname "$0")/lib.sh"
R="$SRC/tests/robustness"
H="python3 $R/hostile.py"
export ASAN_OPTIONS="${ASAN_OPTIONS:-}"
T=60  # seconds a run may take (a hang fails it)
if bash -c 'ulimit -v 2000000 && "$0" --help' "$BIN/slice" >/dev/null 2>&1; then CAPS=1; else CAPS=0; fi
[ $CAPS = 1 ] || echo "note: ulimit -v cannot be set here: the memory cap cases run without it"

# run NAME RC REGEX [CAP_KB] -- CMD...: CMD (a shell command line) under timeout (and
# `ulimit -v CAP_KB`), exit RC, stderr matching REGEX ('' = anything), never an abort.
run() {
  local name="$1" rc="$2" regex="$3" cap="$4"; shift 5
  local limit=""; [ -n "$cap" ] && [ $CAPS = 1 ] && limit="ulimit -v $cap;"
  bash -c "$limit timeout -k 5 $T bash -c '$*'" >"$TMP/out" 2>"$TMP/err" </dev/null
  local got=$? bad=""
  [ "$got" -eq "$rc" ] || bad+=" exit $got (expected $rc);"
  [ "$got" -ne 124 ] || bad+=" timed out (a hang);"
  ! grep -qE "terminate called|Aborted|AddressSanitizer|runtime error" "$TMP/err" || bad+=" aborted;"
  [ -z "$regex" ] || grep -qE -- "$regex" "$TMP/err" || bad+=" stderr does not match /$regex/;"
  if [ -n "$bad" ]; then
    echo "FAIL: $name:$bad"; sed 's/^/  stderr: /' "$TMP/err" | head -3 | cut -c1-300
    FAILS=$((FAILS + 1))
  else
    PASSES=$((PASSES + 1))
  fi
}
strip() { grep -v '^# history' "$1"; }  # a stream without its history (it names the input)
same() { cmp -s <(strip "$1") <(strip "$2"); }

cd "$TMP" || exit 1
B="$BIN"
"$B/bladegen" --points --spacing 0.2 --z-min 8 --z-max 16 --noise 0.002 -o blade.xyz
"$B/bladegen" --points --spacing 0.2 --z-min 8 --z-max 16 --noise 0.002 -o blade.ply
"$B/slice" blade.xyz --at 10,12,14 >s.csv 2>/dev/null
"$B/smooth" s.csv >sm.csv 2>/dev/null
"$B/fitspline" sm.csv >f.csv 2>/dev/null
"$B/camber" f.csv >c.csv 2>/dev/null
check "the blade goes through the pipe" -- grep -q '^# table params' c.csv

# ------------------------------------------------ 1. a worker thread that cannot start
# A stack limit of 4 GB under a 3 GB address space: no thread can map its stack, the main
# thread works on. The tools fall back to it and give what one thread gives.
if [ $CAPS = 1 ]; then
  for tool in smooth:s.csv fitspline:sm.csv camber:f.csv slice:blade.ply; do
    t=${tool%%:*} in=${tool#*:} args=""; [ "$t" = slice ] && args="--at 10,12,14"
    "$B/$t" "$in" $args --threads 1 >ref.csv 2>/dev/null
    run "1: $t --threads 2 without threads" 0 "" "" -- \
      "ulimit -s 4000000; ulimit -v 3000000; $B/$t $in $args --threads 2 > starved.csv"
    check "1: $t without threads gives what one thread gives" -- same ref.csv starved.csv
  done
fi

# ------------------------------------------------ 2. endless and huge inputs
for tool in smooth fitspline camber; do
  run "2: $tool /dev/zero" 1 "binary data" 1000000 -- "$B/$tool /dev/zero"
done
run "2: slice /dev/zero" 1 "binary data" 1000000 -- "$B/slice /dev/zero --at 1"
run "2: slice - < /dev/zero" 1 "binary data" 1000000 -- "$B/slice - --at 1 < /dev/zero"
run "2: endless rows to smooth" 1 "larger than .*--max-memory" 1000000 -- \
  "yes 1,2,3 | $B/smooth --max-memory 40M"
run "2: an endless preamble" 1 "preamble is larger than" 1000000 -- \
  "yes \"# note\" | $B/smooth --max-memory 40M"
run "2: an endless part" 1 "part 0 is larger than" 1000000 -- \
  "{ echo \"# libsection-stream 1\"; echo \"# part 0\"; yes \"# note\"; } | $B/smooth --max-memory 40M"
run "2: an endless line" 1 ":1: line longer than" 1000000 -- \
  "head -c 20000000 /dev/zero | tr \"\\\\0\" a | $B/smooth"
run "2: an endless cloud on stdin" 1 "<stdin> is larger than .*--max-memory" 1000000 -- \
  "yes \"1 2 3\" | $B/slice - --at 1 --max-memory 40M"
run "2: --count 100000 past the memory limit" 1 "100000 planes pass the memory limit.*--max-memory" 1000000 -- \
  "$B/slice $R/good.xyz --count 100000 --max-memory 100M"
$H planes 200000 many_planes.csv
run "2: 200000 planes past the memory limit" 1 "200000 planes pass the memory limit" 1000000 -- \
  "$B/slice $R/good.xyz --planes many_planes.csv --max-memory 100M"

# ------------------------------------------------ 3, 8. pipes, FIFOs, process substitution
# Every input format gives the same stream by path, redirected, piped, through a named pipe
# and through a process substitution (a pipe is read once, into a temporary file).
"$B/bladegen" --mesh --profile-points 64 --layers 8 -o mesh.stl
"$B/bladegen" --mesh --profile-points 64 --layers 8 -o mesh.obj
"$B/bladegen" --mesh --profile-points 64 --layers 8 -o mesh.off
"$B/bladegen" --mesh --profile-points 64 --layers 8 -o mesh_faces.ply
awk 'BEGIN { print "x,y,z" } { print $1 "," $2 "," $3 }' blade.xyz >blade.csv
awk 'NR == 1 { n = 0 } { p[n++] = $0 } END { print "ply\nformat ascii 1.0\nelement vertex " n;
     print "property double x\nproperty double y\nproperty double z\nend_header";
     for (i = 0; i < n; i++) print p[i] }' blade.xyz >blade_ascii.ply
for f in blade.xyz blade.csv blade.ply blade_ascii.ply mesh.stl mesh.obj mesh.off mesh_faces.ply; do
  "$B/slice" "$f" --at 12 >path.csv 2>/dev/null
  check "3: $f slices" -- grep -q '^# table points' path.csv
  run "8: $f redirected" 0 "" "" -- "$B/slice - --at 12 < $f > in.csv"
  check "8: $f redirected: the same stream" -- same path.csv in.csv
  run "8: $f piped" 0 "" "" -- "cat $f | $B/slice - --at 12 > in.csv"
  check "8: $f piped: the same stream" -- same path.csv in.csv
  run "3: $f through a process substitution" 0 "" "" -- "$B/slice <(cat $f) --at 12 > in.csv"
  check "3: $f through a process substitution: the same stream" -- same path.csv in.csv
  rm -f "fifo.${f#*.}"; mkfifo "fifo.${f#*.}"
  run "3: $f through a named pipe" 0 "" "" -- "cat $f > fifo.${f#*.} & $B/slice fifo.${f#*.} --at 12 > in.csv"
  check "3: $f through a named pipe: the same stream" -- same path.csv in.csv
done
rm -f fifo.csv; mkfifo fifo.csv
run "3: a stream through a named pipe" 0 "" "" -- "cat s.csv > fifo.csv & $B/smooth fifo.csv > in.csv"
"$B/smooth" s.csv >path.csv 2>/dev/null
check "3: a stream through a named pipe: the same stream" -- same path.csv in.csv

# ------------------------------------------------ 4. files longer than their headers say
$H short-ply-binary short_binary.ply
$H short-ply-ascii short_ascii.ply
$H short-stl short.stl
run "4: binary PLY declaring 1000 of 20000 vertices" 1 "456000 bytes more than its PLY header declares" "" -- \
  "$B/slice short_binary.ply --at 5"
run "4: the same on stdin" 1 "<stdin>: the file holds 456000 bytes more" "" -- "$B/slice - --at 5 < short_binary.ply"
run "4: ascii PLY declaring 19990 of 20000" 1 "short_ascii.ply:19998: more lines than the PLY header declares" "" -- \
  "$B/slice short_ascii.ply --at 5"
run "4: binary STL declaring half its triangles" 1 "declares 50 triangles .*room for 100" "" -- \
  "$B/slice short.stl --at 5"
head -c -10 mesh_faces.ply >cut.ply; cat mesh_faces.ply >long.ply; printf 'extra' >>long.ply
run "4: a PLY mesh with bytes after its last element" 1 "more data than the PLY header declares" "" -- \
  "$B/slice long.ply --at 12"

# ------------------------------------------------ 5. outputs
echo "precious" >target.txt
ln -s target.txt out.csv.partial
run "5: a planted .partial symlink" 0 "" "" -- "$B/smooth s.csv -o out.csv"
check "5: the symlink's target is left alone" -- grep -qx precious target.txt
check "5: the output is whole" -- test "$(tail -n 1 out.csv)" = "# end"
rm -f out.csv
"$B/slice" blade.xyz --count 12 >big.csv 2>/dev/null
# Two runs writing one -o, the second starting while the first writes (the second's shorter
# stream truncated the first's file: two '# end' lines, NUL bytes, one run failing).
run "5: two runs with one -o" 0 "" "" -- "$B/slice blade.xyz --count 24 --threads 1 -o same.csv &
  sleep 0.2; $B/slice blade.xyz --count 6 --threads 1 -o same.csv; wait \$!"
check "5: ... leave one whole stream" -- \
  test "$(grep -c '^# end' same.csv)" = 1 -a "$(tr -d '\000' <same.csv | wc -c)" = "$(wc -c <same.csv)"
check "5: ... and no temporary file" -- test -z "$(ls same.csv.* 2>/dev/null)"
cp blade.xyz scan.xyz
run "5: slice scan.xyz -o scan.xyz" 2 "is the input scan.xyz" "" -- "$B/slice scan.xyz --at 12 -o scan.xyz"
check "5: the scan is left alone" -- cmp -s blade.xyz scan.xyz
run "5: camber --params X -o X" 2 "--params X is the output of --output too" "" -- "$B/camber f.csv --params X -o X"
cp s.csv s2.csv
run "5: smooth s2.csv --report s2.csv" 2 "--report s2.csv is the input" "" -- "$B/smooth s2.csv --report s2.csv"
check "5: the input is left alone" -- cmp -s s.csv s2.csv
ln -s s2.csv link.csv
run "5: an output that is a link to the input" 2 "is the input" "" -- "$B/smooth s2.csv -o link.csv"
cp c.csv c2.csv
run "5: blade c2.csv --plot c2.csv" 2 "--plot c2.csv is the input" "" -- "$B/blade c2.csv --plot c2.csv"
check "5: ... the stream is left alone" -- cmp -s c.csv c2.csv
run "5: /dev/null twice is fine" 0 "" "" -- "$B/camber f.csv --params /dev/null -o /dev/null"
"$B/slice" blade.ply --count 30 >many.csv 2>/dev/null
for sig in TERM:-15 INT:-2 HUP:-1; do
  got=$($H signal ${sig%:*} killed.csv "$B/fitspline" many.csv -o killed.csv --threads 1)
  check "5: SIG${sig%:*} ends the run ($got)" -- test "${got%% *}" = "${sig#*:}"
  check "5: SIG${sig%:*} leaves no temporary file ($got)" -- test "${got#* }" = ""
done
run "5: a write past ulimit -f" 1 "capped.csv: write error: File too large" "" -- \
  "ulimit -f 200; $B/smooth big.csv -o capped.csv"
check "5: ... leaves no file" -- test -z "$(ls capped.csv* 2>/dev/null)"
run "9: a full disk names the reason" 1 "/dev/full: write error: No space left on device" "" -- \
  "$B/smooth s.csv -o /dev/full"

# ------------------------------------------------ 6. broken streams
for what in duplicate-point negative-loop negative-index negative-count wrong-label second-part duplicate-column; do
  $H edit s.csv "bad-$what.csv" $what
done
$H edit c.csv bad-duplicate-params.csv duplicate-params
run "6: two params rows for one section" 1 "table 'params' has two rows .* section 0" "" -- \
  "$B/plot bad-duplicate-params.csv -o plots"
run "6: a points row twice" 1 "table 'points' has two rows .* section 0 loop 0 index 0" "" -- \
  "$B/smooth bad-duplicate-point.csv"
run "6: a negative loop" 1 "column 'loop' of table 'points': '-1' is a negative id" "" -- \
  "$B/smooth bad-negative-loop.csv"
run "6: a negative index" 1 "column 'index' of table 'points': '-3' is a negative id" "" -- \
  "$B/fitspline bad-negative-index.csv"
run "6: loops.points = -5" 1 "column 'points' is -5, a count must be" "" -- "$B/smooth bad-negative-count.csv"
run "6: a part label that disagrees with its rows" 1 "section 0 in the part of section 7" "" -- \
  "$B/smooth bad-wrong-label.csv"
run "6: one section in two parts" 1 "a second part of section 0" "" -- "$B/smooth bad-second-part.csv"
run "6: a column twice in a header" 1 "column 'u' appears twice" "" -- "$B/smooth bad-duplicate-column.csv"
printf 'origin_x,origin_y,origin_z,normal_x,normal_y,normal_z,normal_z\n0,0,12,0,0,1,1\n' >dup_planes.csv
run "6: a column twice in a planes CSV" 1 "dup_planes.csv:1: column 'normal_z' appears twice" "" -- \
  "$B/slice blade.xyz --planes dup_planes.csv"
run "6: a report into a directory that does not exist, refused before the work" 1 \
  "report no-such-dir/r.txt: the directory no-such-dir does not exist" "" -- \
  "$B/smooth s.csv --report no-such-dir/r.txt > smoothed-unwritable.csv"
check "6: ... and no stream written" -- test ! -s smoothed-unwritable.csv
run "6: an output into a directory that does not exist" 1 "the directory no-such-dir does not exist" "" -- \
  "$B/fitspline s.csv -o no-such-dir/f.csv"
printf 'origin_x,origin_y,origin_z,normal_x,normal_y,normal_z\n0,0,1e300,0,0,1\n' >far_planes.csv
run "6: a planes CSV with an origin 1e300 away" 1 "far_planes.csv: plane 0 .data row 1. has an origin coordinate beyond" "" -- \
  "$B/slice blade.xyz --planes far_planes.csv"
$H edit s.csv empty-points.csv empty-points
run "6: a section without points (exit 3: incomplete)" 3 "smooth: warning: section 1: no points" "" -- \
  "$B/smooth empty-points.csv | $B/fitspline | $B/camber > out.csv"
check "6: ... is an issue at the end of the pipe" -- grep -q '^# issue section=1 loop=-1 stage=smooth' out.csv
$H edit f.csv no-v.csv no-v
run "6: a points table without v" 1 "table 'points' has no column 'v'" "" -- "$B/camber no-v.csv"
awk 'BEGIN { print "x,y"; for (i = 0; i < 400; ++i) { t = 2 * 3.14159265358979 * i / 400;
     printf "%.9f,%.9f\n", 20 * cos(t), 3 * sin(t) + 0.02 * cos(t) * cos(t) } }' >xy.dat
awk -F, 'NR == 1 { print "y,x"; next } { print $2 "," $1 }' xy.dat >yx.dat
"$B/camber" xy.dat --params xy_params.csv -o /dev/null 2>/dev/null
"$B/camber" yx.dat --params yx_params.csv -o /dev/null 2>/dev/null
check "6: a profile headed y,x reads its columns by name" -- cmp -s xy_params.csv yx_params.csv

# ------------------------------------------------ 7. far from the origin
# (the parameters to 0.1 um: tests/test_robustness.cpp, "[robustness][far]")
$B/camber f.csv --params near.csv -o /dev/null 2>/dev/null
for d in 1e6 1e9; do
  $H shift $d blade.xyz far.xyz
  z=$(python3 -c "print(repr($d + 10) + ',' + repr($d + 12) + ',' + repr($d + 14))")
  run "7: a blade $d mm away" 0 "" "" -- \
    "$B/slice far.xyz --at $z | $B/smooth | $B/fitspline | $B/camber --params far.csv -o /dev/null"
  check "7: ... keeps its chord to 0.1 um" -- python3 -c "
import csv
a = [float(r['chord']) for r in csv.DictReader(open('near.csv'))]
b = [float(r['chord']) for r in csv.DictReader(open('far.csv'))]
assert len(a) == len(b) == 3 and max(abs(x - y) for x, y in zip(a, b)) < 1e-4, (a, b)"
done

# ------------------------------------------------ 9. unclear errors and codes
run "9: --normal 0,0,0" 2 "--normal: must not be 0,0,0" "" -- "$B/slice blade.xyz --normal 0,0,0 --at 1"
run "9: --at nan" 2 "--at: must be a finite number, got 'nan'" "" -- "$B/slice blade.xyz --at nan"
run "9: --slab nan" 2 "--slab: must be a finite number" "" -- "$B/slice blade.xyz --at 1 --slab nan"
run "9: --slab -1 without a 300-digit range" 2 "--slab: Value -1 is below 0$" "" -- "$B/slice blade.xyz --at 1 --slab -1"
mkdir -p adir
for tool in smooth fitspline camber plot; do
  run "9: a directory to $tool" 1 "adir: is a directory" "" -- "$B/$tool adir"
done
run "9: a directory to slice" 1 "adir: is a directory" "" -- "$B/slice adir --at 1"
$H cr blade.xyz cr.xyz
$H cr s.csv cr.csv
run "9: a cloud with CR-only line ends" 1 "cr.xyz: CR-only line ends" "" -- "$B/slice cr.xyz --at 12"
run "9: a stream with CR-only line ends" 1 "cr.csv: CR-only line ends" "" -- "$B/smooth cr.csv"
run "9: the tool's name once" 1 "^slice: error: <stdin>: cannot estimate the point spacing" "" -- \
  "$B/slice - --at 5 < $R/one_point.xyz"
check "9: ... not twice" -- test -z "$(grep 'slice: .*slice: ' "$TMP/err")"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\n' >neh.ply
printf '\x89\x13\xfe\x01\x80binary\x02\x03 \xff\x00\x10\n' >>neh.ply
run "9: a PLY header without end_header" 1 "binary data where a PLY header line should be" "" -- "$B/slice neh.ply --at 1"
check "9: ... without its bytes in the message" -- test "$(wc -c <"$TMP/err")" -lt 200

finish
