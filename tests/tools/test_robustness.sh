#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Hostile input (tests/robustness/, docs/ROBUSTNESS.md): every tool that reads a broken
# file exits 1 with one line on stderr naming the file (and line, point or section) and
# the problem, and writes nothing to stdout; a failing section is listed (a '# issue' line
# and a warning) while the other sections go on.
source "$(dirname "$0")/lib.sh"
R="$SRC/tests/robustness"
export ASAN_OPTIONS="${ASAN_OPTIONS:-}"

# refuse TOOL FILE REGEX [ARGS...]: exit 1, empty stdout, one stderr line "TOOL: error: ..."
# naming FILE (its base name, or <stdin> when FILE is '-') and matching REGEX.
refuse() {
  local tool="$1" file="$2" regex="$3"; shift 3
  local name; name=$(basename "$file"); [ "$file" = "-" ] && name="<stdin>"
  "$BIN/$tool" "$file" "$@" >"$TMP/out" 2>"$TMP/err" </dev/null
  local rc=$?
  verdict "$tool $name $*" $rc 1 "$name" "$regex" 1
}

# refuse_args TOOL NAME REGEX ARGS...: as refuse, for a file given by an option (NAME).
refuse_args() {
  local tool="$1" name="$2" regex="$3"; shift 3
  "$BIN/$tool" "$@" >"$TMP/out" 2>"$TMP/err" </dev/null
  local rc=$?
  verdict "$tool $*" $rc 1 "$name" "$regex" 1
}

# refuse_stdin TOOL FILE REGEX [ARGS...]: as refuse, the file piped on standard input.
refuse_stdin() {
  local tool="$1" file="$2" regex="$3"; shift 3
  "$BIN/$tool" - "$@" <"$file" >"$TMP/out" 2>"$TMP/err"
  local rc=$?
  verdict "$tool <stdin>=$(basename "$file") $*" $rc 1 "<stdin>" "$regex" 1
}

# verdict WHAT RC WANT_RC NAME REGEX LINES
verdict() {
  local what="$1" rc="$2" want="$3" name="$4" regex="$5" lines="$6" bad=""
  [ "$rc" -eq "$want" ] || bad+=" exit $rc (expected $want);"
  [ ! -s "$TMP/out" ] || bad+=" $(wc -c <"$TMP/out") bytes on stdout;"
  [ "$(wc -l <"$TMP/err")" -eq "$lines" ] || bad+=" $(wc -l <"$TMP/err") lines on stderr;"
  tail -n 1 "$TMP/err" | grep -q "^[a-z]*: error: " || bad+=" no 'tool: error:' line;"
  grep -qF -- "$name" "$TMP/err" || bad+=" the message does not name $name;"
  grep -qE -- "$regex" "$TMP/err" || bad+=" the message does not match /$regex/;"
  if [ -n "$bad" ]; then
    echo "FAIL: $what:$bad"; sed 's/^/  stderr: /' "$TMP/err" | head -3 | cut -c1-300
    FAILS=$((FAILS + 1))
  else
    PASSES=$((PASSES + 1))
  fi
}

# partial TOOL FILE SECTION [ARGS...]: exit 0, '# issue section=SECTION' in the stream, a
# warning naming the section on stderr, and the other sections (ids in $KEEP) present in
# the table $TABLE.
partial() {
  local tool="$1" file="$2" section="$3"; shift 3
  "$BIN/$tool" "$file" "$@" >"$TMP/out" 2>"$TMP/err" </dev/null
  local rc=$? bad=""
  [ $rc -eq 0 ] || bad+=" exit $rc;"
  grep -q "^# issue section=$section .*stage=$tool" "$TMP/out" || bad+=" no '# issue section=$section' line;"
  grep -q "^$tool: warning: section $section" "$TMP/err" || bad+=" no warning for section $section;"
  for s in $KEEP; do
    awk -F, -v t="$TABLE" -v s="$s" '$0 == "# table " t { on = 1; getline; next } /^#/ { on = 0 }
         on && $1 == s { n++ } END { exit n > 0 ? 0 : 1 }' "$TMP/out" || bad+=" section $s missing from '$TABLE';"
  done
  if [ -n "$bad" ]; then
    echo "FAIL: $tool $(basename "$file") (section $section fails alone):$bad"; sed 's/^/  stderr: /' "$TMP/err" | head -3
    FAILS=$((FAILS + 1))
  else
    PASSES=$((PASSES + 1))
  fi
}

# ---------------------------------------------------------------- point clouds (slice)
S=(--at 5)
refuse slice "$R/empty.xyz" "empty file" "${S[@]}"
refuse slice "$R/empty.ply" "empty file" "${S[@]}"
refuse slice "$R/only_comments.xyz" "no points" "${S[@]}"
refuse slice "$R/utf16.xyz" "UTF-16" "${S[@]}"
refuse slice "$R/utf16be.xyz" "UTF-16" "${S[@]}"
refuse slice "$R/binary_in_text.xyz" "binary data" "${S[@]}"
refuse slice "$R/nan.xyz" ":1441: non-finite coordinate 'nan'" "${S[@]}"
refuse slice "$R/inf.xyz" ":2: non-finite coordinate '-inf'" "${S[@]}"
refuse slice "$R/overflow.xyz" ":2: expected a number in column 1, found '1e400'" "${S[@]}"
refuse slice "$R/text_in_number.xyz" ":2: expected a number in column 2, found '5x'" "${S[@]}"
refuse slice "$R/missing_column.xyz" ":2: expected at least 3 columns, found 2" "${S[@]}"
refuse slice "$R/truncated_line.xyz" ":1441: expected at least 3 columns" "${S[@]}"
refuse slice "$R/giant.xyz" "point 1 has a coordinate beyond" "${S[@]}"
refuse slice "$R/missing_z.csv" ":1: a CSV cloud needs a header row naming the x, y and z" "${S[@]}"
refuse slice "$R/text_in_number.csv" ":3: expected a number in column 2, found 'two'" "${S[@]}"
refuse slice "$R/empty_header.csv" "no points" "${S[@]}"
refuse_stdin slice "$R/nan.xyz" ":1441: non-finite" "${S[@]}"
refuse_stdin slice "$R/utf16.xyz" "UTF-16" "${S[@]}"
refuse_stdin slice "$R/empty.xyz" "empty file" "${S[@]}"
python3 -c "print('1' * 1000000 + ' 2 3')" >"$TMP/long_line.xyz"
refuse slice "$TMP/long_line.xyz" ":1: line longer than 65536 characters" "${S[@]}"
refuse_stdin slice "$TMP/long_line.xyz" ":1: line longer than 65536 characters" "${S[@]}"

# A UTF-8 byte-order mark is skipped: the same section as without it.
"$BIN/slice" "$R/good.xyz" "${S[@]}" 2>/dev/null | grep -v '^# history' >"$TMP/plain.txt"
"$BIN/slice" "$R/bom.xyz" "${S[@]}" 2>/dev/null | grep -v '^# history' >"$TMP/bom.txt"
check "a BOM before an XYZ cloud is skipped" -- cmp -s "$TMP/plain.txt" "$TMP/bom.txt"
check "the good cloud slices" -- grep -q "^# table points" "$TMP/plain.txt"

# ---------------------------------------------------------------- PLY (slice)
refuse slice "$R/truncated_binary.ply" "declares 1440 vertices but the file holds only 1431" "${S[@]}"
refuse slice "$R/truncated_ascii.ply" ":1436: expected 3 vertex values, found 2" "${S[@]}"
refuse slice "$R/truncated_header.ply" "truncated PLY header" "${S[@]}"
refuse slice "$R/billions.ply" "declares 4000000000 vertices" "${S[@]}"
refuse slice "$R/too_many.ply" "declares 11 vertices but the file holds only 10" "${S[@]}"
refuse slice "$R/over_limit.ply" "more than the limit" "${S[@]}"
refuse slice "$R/nan_binary.ply" "vertex 5 has a non-finite coordinate" "${S[@]}"
refuse slice "$R/no_xyz.ply" "lacks x, y or z" "${S[@]}"
refuse slice "$R/bad_format.ply" ":2: unknown PLY format 'utf16'" "${S[@]}"
refuse slice "$R/billions_mesh.ply" "declares 4000000000 vertex elements but the file has only" "${S[@]}"
refuse_stdin slice "$R/billions.ply" "(ends after 10 of|declares) 4000000000 vertices( but the file holds only 10)?" "${S[@]}"
refuse_stdin slice "$R/truncated_binary.ply" "(ends after 1431 of|declares) 1440 vertices( but the file holds only 1431)?" "${S[@]}"

# ---------------------------------------------------------------- meshes (slice)
# mesh.cpp reads every mesh format itself (OpenMesh's readers hung or aborted on such files).
refuse slice "$R/empty.stl" "empty file" "${S[@]}"
refuse slice "$R/truncated.stl" "declares 1000 triangles \\(50084 bytes\\) but the file has only 184" "${S[@]}"
refuse slice "$R/billions.stl" "declares 4294967295 triangles" "${S[@]}"
refuse slice "$R/header_only.stl" "no faces" "${S[@]}"
refuse slice "$R/short.stl" ": line 4: the file ends inside a facet" "${S[@]}"
refuse slice "$R/nan.stl" "triangle 0 has a non-finite coordinate" "${S[@]}"
refuse slice "$R/stl_text_coordinate.stl" ": line 5: expected a number, found 'zero'" "${S[@]}"
refuse slice "$R/stl_missing_coordinate.stl" ": line 6: expected a number, found 'vertex'" "${S[@]}"
refuse slice "$R/stl_no_endsolid.stl" "the file ends before 'endsolid'" "${S[@]}"
refuse slice "$R/stl_two_vertices.stl" ": line 6: a facet with 2 vertices" "${S[@]}"
refuse slice "$R/bad_index.obj" ": line 4: the face refers to vertex 99 but 3 vertices are defined" "${S[@]}"
refuse slice "$R/no_faces.obj" "no faces" "${S[@]}"
refuse slice "$R/text.obj" ": line 1: expected a number, found 'zero'" "${S[@]}"
refuse slice "$R/billions.off" "declares 4000000000 vertices but the file has only" "${S[@]}"
refuse slice "$R/bad_index.off" ": line 6: face 0 has the vertex index 7 \\(the mesh has 3 vertices" "${S[@]}"
refuse slice "$R/truncated.off" "declares 4 vertices but the file has only 22 bytes" "${S[@]}"
refuse slice "$R/off_negative_count.off" ": line 6: face 0 has a negative vertex count -3" "${S[@]}"
refuse slice "$R/off_short_face.off" ": line 6: face 0 announces 4 vertices but the line has 3" "${S[@]}"
refuse slice "$R/off_text_coordinate.off" ": line 4: vertex 1: expected a number, found 'zero'" "${S[@]}"
refuse slice "$R/off_truncated_faces.off" ": line 6: the file ends after 1 of 2 faces" "${S[@]}"
refuse slice "$R/off_binary.off" "binary OFF is not supported" "${S[@]}"
refuse slice "$R/crash-off-body-hang.off" "binary data in a text file" "${S[@]}"
refuse slice "$R/crash-obj-face-assert.obj" ": line 4: a face needs at least 3 vertices" "${S[@]}"
refuse slice "$R/crash-ply-no-end-header.ply" ": line 9: unexpected PLY header line starting '0'" "${S[@]}"
# Good meshes in other writers' forms read (comments, colours, a quad): the slice of the open
# good.off at z = 0.5 is one open polyline, reported as such, not a read error.
"$BIN/slice" "$R/good.off" --at 0.5 >"$TMP/out" 2>"$TMP/err" </dev/null
check "good.off reads (the slice reports the open mesh)" -- grep -q "open intersection polyline" "$TMP/err"
"$BIN/slice" "$R/good_mesh.ply" --at 0 >"$TMP/out" 2>"$TMP/err" </dev/null
check "good_mesh.ply reads and slices" -- grep -q "^# table points" "$TMP/out"

# ---------------------------------------------------------------- planes (slice --planes)
refuse_args slice planes_missing_column.csv "needs the column 'normal_z'" "$R/good.xyz" --planes "$R/planes_missing_column.csv"
refuse_args slice planes_zero_normal.csv "plane 0 \(data row 1\) has a zero normal" "$R/good.xyz" --planes "$R/planes_zero_normal.csv"

# ---------------------------------------------------------------- degenerate geometry (slice)
# Every section fails: the warnings name the sections, the last line the file.
degenerate() {
  local file="$1" regex="$2" lines="$3"; shift 3
  "$BIN/slice" "$file" "$@" >"$TMP/out" 2>"$TMP/err" </dev/null
  local rc=$?
  verdict "slice $(basename "$file") $*" $rc 1 "$(basename "$file")" "$regex" "$lines"
  grep -q "^slice: warning: section 0: " "$TMP/err" || [ "$lines" -eq 1 ] ||
    { echo "FAIL: slice $(basename "$file"): no warning naming section 0"; FAILS=$((FAILS + 1)); }
}
degenerate "$R/line.xyz" "1 points, at least 8 are needed" 2 --normal 1,0,0 --at 5
degenerate "$R/line.xyz" "do not close into a loop" 2 --normal 0,1,0 --at 0 --slab 0.1
degenerate "$R/one_point.xyz" "cannot estimate the point spacing" 1 "${S[@]}"
degenerate "$R/one_point.xyz" "the points are all equal" 2 --at 3 --slab 0.1
degenerate "$R/three_points.xyz" "3 points, at least 8 are needed" 2 --at 0 --slab 0.1
# good.xyz lies on levels (lines of points, docs/SAMPLING.md: a line above the refusal says so)
degenerate "$R/good.xyz" "lies beyond the lines of points" 3 --at 1000
# A raster that would need gigabytes: a dense ring of radius 5 m cut with 0.5 mm cells
# (its heights spread, not on levels: those would be lines, interpolated without a raster).
awk 'BEGIN { pi = atan2(0, -1); for (i = 0; i < 40000; i++) { t = 2 * pi * i / 40000;
     for (k = -1; k <= 1; k++) printf "%.6f %.6f %.3f\n", 5000 * cos(t), 5000 * sin(t), 5 + 0.2 * k + 0.2 * ((i * 7919 + k * 104729) % 1009) / 1009 } }' \
  >"$TMP/ring.xyz"
degenerate "$TMP/ring.xyz" "exceeds max_cells" 2 --at 5 --cell 0.5
# A plane that misses the part among good ones fails alone.
KEEP="0" TABLE=points partial slice "$R/good.xyz" 1 --at 5,1000

# ---------------------------------------------------------------- streams (smooth, fitspline, camber)
python3 -c "
print('# libsection-stream 1'); print('# table points'); print('section,loop,index,u,v,nu,nv')
print('0,0,0,' + '1' * 1000000 + ',2,0,1')" >"$TMP/long_line_stream.csv"
for tool in smooth fitspline camber; do
  refuse $tool "$R/empty_stream.csv" "empty|no profile points"
  refuse $tool "$R/version2_stream.csv" ":1: stream version '2' is not supported"
  refuse $tool "$R/missing_column_stream.csv" "no column 'v'|no 'splines' table"
  refuse $tool "$R/text_in_number_stream.csv" ":11: column 'v' of table 'points': expected a number, found 'abc'"
  refuse $tool "$R/truncated_stream.csv" ":404: 6 values for the 7 columns of table 'points' \(truncated line\?\)"
  refuse $tool "$R/nan_stream.csv" ":11: column 'u' of table 'points': non-finite value 'nan'"
  refuse $tool "$R/utf16_stream.csv" "UTF-16"
  refuse $tool "$R/huge_id_stream.csv" ":11: column 'section' of table 'points': '1e12' is not an integer id"
  refuse $tool "$R/fraction_id_stream.csv" ":11: column 'loop' of table 'points': '0.5' is not an integer id"
  refuse $tool "$R/no_header_stream.csv" "table 'points' has no header row"
  refuse $tool "$R/row_outside_table_stream.csv" ":2: a data row outside any table"
  refuse $tool "$R/giant_stream.csv" ":5: column 'u' of table 'points': value 2e\+301 is beyond"
  refuse $tool "$TMP/long_line_stream.csv" ":4: column 'u' of table 'points': expected a number"
  refuse_stdin $tool "$R/truncated_stream.csv" ":404: 6 values"
done
refuse smooth "$R/no_version_stream.csv" ":1: not a libsection stream"
refuse fitspline "$R/no_version_stream.csv" ":1: not a libsection stream"
refuse smooth "$R/good_profile.dat" ":1: not a libsection stream"
refuse camber "$R/no_version_stream.csv" ":3: the header names the columns section, loop"  # not a profile either

# A BOM before a stream is skipped: smooth and fitspline read it as the plain stream.
for tool in smooth fitspline; do
  "$BIN/$tool" "$R/good_stream.csv" 2>/dev/null | grep -v '^# history' >"$TMP/plain.txt"
  "$BIN/$tool" "$R/bom_stream.csv" 2>/dev/null | grep -v '^# history' >"$TMP/bom.txt"
  check "$tool: a BOM before a stream is skipped" -- cmp -s "$TMP/plain.txt" "$TMP/bom.txt"
done

# Degenerate sections between good ones (sections 0 and 2): each fails alone at the stage
# that cannot handle it, and the pipe carries the issue to the end.
KEEP="0 2" TABLE=smoothed partial smooth "$R/three_points_stream.csv" 1
KEEP="0 2" TABLE=smoothed partial smooth "$R/repeated_point_stream.csv" 1
KEEP="0 2" TABLE=splines partial fitspline "$R/collinear_stream.csv" 1
KEEP="0 2" TABLE=splines partial fitspline "$R/figure_eight_stream.csv" 1
KEEP="0 2" TABLE=splines partial fitspline "$R/three_points_stream.csv" 1
for f in three_points repeated_point collinear figure_eight; do
  "$BIN/smooth" "$R/${f}_stream.csv" 2>/dev/null | "$BIN/fitspline" 2>/dev/null | "$BIN/camber" >"$TMP/pipe.txt" 2>"$TMP/pipe.err"
  check "$f: the pipe goes on (exit $?)" -- test -s "$TMP/pipe.txt"
  check "$f: section 1 is listed as an issue" -- grep -q "^# issue section=1 " "$TMP/pipe.txt"
  check "$f: sections 0 and 2 get parameters" -- awk -F, '/^# table params/ { on = 1; getline; next } /^#/ { on = 0 }
        on { s[$1] = 1 } END { exit (0 in s) && (2 in s) && !(1 in s) ? 0 : 1 }' "$TMP/pipe.txt"
done

# ---------------------------------------------------------------- spline tables (camber, compare, tocad)
# Every reader of splines refuses a knot vector that defines no curve, naming the section.
for f in equal_knots decreasing_knots; do
  refuse camber "$R/spline_${f}_stream.csv" "spline of section 1 loop 0 is not a curve: bspline: "
  refuse tocad "$R/spline_${f}_stream.csv" "spline of section 1 loop 0 is not a curve" -f iges -o "$TMP/out.igs"
  refuse_args compare "spline_${f}_stream.csv" "spline of section 1 loop 0 is not a curve" \
    "$R/spline_collinear_stream.csv" --nominal "$R/spline_${f}_stream.csv"
done
check "tocad: no IGES file left after a refused stream" -- test ! -e "$TMP/out.igs"
# Control points on one line: no inside to triangulate, the section fails alone.
KEEP="0 2" TABLE=params partial camber "$R/spline_collinear_stream.csv" 1 --allow-partial
# A DXF polyline the tolerance cannot reach (the curve 1e10 mm across, or 9e14 mm from the
# origin where coordinates resolve to 0.125 mm) is refused at once, not written for minutes.
refuse tocad "$R/spline_huge_stream.csv" "polyline of section 0 loop 0: .*more than 1000000 points" -f dxf \
  -o "$TMP/out.dxf"
refuse tocad "$R/spline_far_stream.csv" "polyline of section 0 loop 0: .*below the resolution" -f dxf \
  -o "$TMP/out.dxf"

# ---------------------------------------------------------------- profiles (camber)
refuse camber "$R/empty_profile.dat" "no profile points"
refuse camber "$R/text_profile.dat" ":3: expected two numbers x, y, found '3 four'"
refuse camber "$R/nan_profile.dat" ":2: non-finite coordinate"
python3 -c "print('1 ' + '2' * 1000000)" >"$TMP/long_line.dat"
refuse camber "$TMP/long_line.dat" "no profile points"
"$BIN/camber" "$R/bom_stream.csv" >"$TMP/out" 2>"$TMP/err" </dev/null
check "camber: a BOM before a stream is read as a stream" -- grep -q "no 'splines' table" "$TMP/err"

# ---------------------------------------------------------------- fuzzer findings
# Inputs that crashed or hung a reader under libFuzzer (docs/ROBUSTNESS.md), kept as
# regressions: each must now be refused cleanly.
for f in "$R"/crash-*; do
  [ -e "$f" ] || continue
  case "$f" in
    *.xyz|*.csv) refuse slice "$f" "read_cloud" "${S[@]}" ;;
    *.ply) refuse slice "$f" "read_(cloud|mesh)" "${S[@]}" ;;
    *.stl|*.obj|*.off) refuse slice "$f" "read_mesh: " "${S[@]}" ;;
    *.stream) refuse smooth "$f" "pipe" ;;
    *.dat) refuse camber "$f" "pipe" ;;
  esac
done

finish
