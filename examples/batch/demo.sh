#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Tries the batch recipe: three generated scans (bladegen) in a folder, the workflow run,
# then one scan changed and the workflow run again, which redoes that scan and the summary
# only. Needs the tools (scripts/build.sh) and Snakemake (apt install snakemake).
# Usage: examples/batch/demo.sh [WORK_DIR]   (default: a new temporary folder)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="$here/../../build/tools"
work="${1:-$(mktemp -d)}"
mkdir -p "$work/scans"
cd "$work"
"$bin/bladegen" --kind turbine --points --noise 0.003 --seed 1 -o scans/blade-a.ply
"$bin/bladegen" --kind compressor --points --noise 0.003 --seed 2 -o scans/blade-b.ply
"$bin/bladegen" --kind turbine --points --noise 0.005 --holes 3 --seed 3 -o scans/blade-c.ply
run() { snakemake --snakefile "$here/Snakefile" --configfile "$here/config.yaml" --config bin="$bin" --cores 2 "$@"; }
run --quiet
echo "summary: $work/results/summary.csv ($(($(wc -l < results/summary.csv) - 1)) sections)"
echo "nothing changed, so nothing to do:"; run -n --quiet 2>&1 | tail -3
"$bin/bladegen" --kind turbine --points --noise 0.003 --seed 4 -o scans/blade-a.ply
echo "blade-a changed:"; run -n --quiet 2>&1 | tail -12
