#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Checks that two builds give byte-identical outputs at every stage of the pipe: the
# bundled example, a generated mesh, a plain profile, the benchmark's scan (BIG=1: the
# 21 M point scan of scripts/bench.sh; default a 1 M point one) and evaluate_pipeline
# seeds 1-8 (both presets, full scan; the timing column left out).
# Usage: scripts/check_identical.sh OLD_BUILD_DIR NEW_BUILD_DIR
#        (each a build tree with tools/ and bench/; OLD's library is taken from OLD/libsection)
# Env:   WORK (default /tmp/libsection-identical), BIG=1, SEEDS (default 8).
set -euo pipefail
cd "$(dirname "$0")/.."
OLD=$(cd "$1" && pwd); NEW=$(cd "$2" && pwd)
WORK="${WORK:-/tmp/libsection-identical}"
SEEDS="${SEEDS:-8}"
mkdir -p "$WORK/old" "$WORK/new"
fail=0

# run SIDE NAME CMD...: runs a tool of build SIDE with its own library, output to SIDE/NAME.
run() {
  local side=$1 name=$2; shift 2
  local dir; if [ "$side" = old ]; then dir=$OLD; else dir=$NEW; fi
  local tool=$1; shift
  # run in the side's folder with relative file names, so that the history lines agree
  (cd "$WORK/$side" && LD_LIBRARY_PATH="$dir/libsection:$dir/libsection/extras" "$dir/$tool" "$@" \
    > "$name" 2> "$name.err") || true
}
same() {
  if cmp -s "$WORK/old/$1" "$WORK/new/$1" &&
     { [ ! -f "$WORK/new/$1.err" ] || cmp -s "$WORK/old/$1.err" "$WORK/new/$1.err"; }; then
    echo "same      $1 ($(wc -c < "$WORK/new/$1") bytes)"
  else
    echo "DIFFERENT $1"; fail=1
  fi
}
# pipe NAME INPUT SLICE_ARGS...: every stage of the pipe on both builds.
pipe() {
  local name=$1 input=$2; shift 2
  for side in old new; do
    run $side "$name.slice" tools/slice "$input" "$@"
    run $side "$name.smooth" tools/smooth "$name.slice" --report "$name.report"
    run $side "$name.fit" tools/fitspline "$name.smooth" --samples 400
    run $side "$name.camber" tools/camber "$name.fit" --params "$name.params" --thickness "$name.thickness"
    run $side "$name.plot" tools/plot "$name.camber" --html
  done
  for s in slice smooth fit camber params thickness report plot; do
    [ -f "$WORK/new/$name.$s" ] && same "$name.$s"
  done
}

pipe example "$PWD/data/example_blade.ply" --normal 0,0,1 --at 12,20,28
pipe example_count "$PWD/data/example_blade.ply" --count 9 --threads 1

LD_LIBRARY_PATH="$OLD/libsection:$OLD/libsection/extras" "$OLD/tools/bladegen" --kind compressor --mesh -o "$WORK/mesh.ply"
pipe mesh ../mesh.ply --count 5

printf '# a thin profile\n' > "$WORK/profile.dat"
python3 - "$WORK/profile.dat" <<'EOF'
import math, sys
with open(sys.argv[1], "a") as f:
    for k in range(200):
        t = 2 * math.pi * k / 200
        x = 0.5 * (1 + math.cos(t)) * 40
        y = 3 * math.sin(t) * (1 - 0.3 * math.cos(t)) + 2 * math.sin(math.pi * x / 40)
        f.write(f"{x:.9f} {y:.9f}\n")
EOF
for side in old new; do run $side profile.camber tools/camber ../profile.dat --params profile.params; done
same profile.camber; same profile.params

if [ "${BIG:-0}" = 1 ]; then m=20; else m=1; fi
spacing=$(python3 -c "import math; print(0.08*math.sqrt(0.94/$m))")
scan="$WORK/blade_${m}M.ply"
[ -f "$scan" ] || LD_LIBRARY_PATH="$OLD/libsection" "$OLD/tools/bladegen" --kind turbine --points \
  --spacing "$spacing" --noise 0.005 --seed 3 -o "$scan"
LD_LIBRARY_PATH="$NEW/libsection:$NEW/libsection/extras" "$NEW/tools/bladegen" --kind turbine --points \
  --spacing "$spacing" --noise 0.005 --seed 3 -o "$WORK/new_scan.ply"
if cmp -s "$scan" "$WORK/new_scan.ply"; then echo "same      bladegen ${m}M scan"; else echo "DIFFERENT bladegen ${m}M scan"; fail=1; fi
rm -f "$WORK/new_scan.ply"
pipe "scan${m}M" "../blade_${m}M.ply" --count 20

for side in old new; do
  run $side eval tools/../bench/evaluate_pipeline --seeds "$SEEDS" --preset both --full-scan
  # column 16 of a section's row is its run time
  awk '$1 ~ /^(turbine|compressor)$/ && $2 ~ /^[0-9]+$/ {$16 = "-"} {print}' "$WORK/$side/eval" > "$WORK/$side/eval.cut"
  : > "$WORK/$side/eval.cut.err"
done
same eval.cut

[ $fail = 0 ] && echo "check_identical: every output is the same" || { echo "check_identical: outputs differ"; exit 1; }
