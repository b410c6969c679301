#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# How compare's decision rules judge perfect parts (docs/COMPARE.md, "Uncertain"): generated
# scans (bladegen --points --noise 0.005: holes, varying density, two views; turbine and
# compressor, seeds 1..SEEDS) of blades whose nominal mesh is their own exact design, so
# every edge radius truly deviates by ~0. Each blade's 9 sections are compared with tolerances
# of +-T on both edge radii, for each T, under --decision-rule simple and guarded: a FAIL of
# a perfect part is a false reject, which the guarded rule turns into uncertain.
# Usage: scripts/decision_rules.sh [SEEDS (default 6)] [T... (mm, default 0.001 0.002 0.003 0.005)]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${SECTION_BIN:-$here/../build/tools}"
[ -x "$bin/compare" ] || { echo "decision_rules: no tools in $bin (SECTION_BIN)" >&2; exit 2; }
seeds="${1:-6}"
shift || true
limits=("$@")
[ ${#limits[@]} -gt 0 ] || limits=(0.001 0.002 0.003 0.005)
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

for kind in turbine compressor; do
  for seed in $(seq 1 "$seeds"); do
    b="$tmp/${kind}_$seed"
    "$bin/bladegen" --kind "$kind" --points --noise 0.005 --seed "$seed" -o "$b.ply" 2>/dev/null
    "$bin/bladegen" --kind "$kind" --seed "$seed" --mesh --profile-points 4000 --layers 61 -o "$b.stl" 2>/dev/null
    "$bin/slice" "$b.ply" --normal 0,0,1 --count 9 2>/dev/null | "$bin/smooth" | "$bin/fitspline" 2>/dev/null |
      "$bin/camber" > "$b.csv" 2>/dev/null
  done
done

echo "tolerance +-T on le_radius and te_radius; 2 x $seeds blades x 9 sections; counts of values"
printf '%-9s %-8s %6s %6s %10s\n' "T (mm)" rule pass FAIL uncertain
for t in "${limits[@]}"; do
  printf 'item,section,low,high\nle_radius,*,-%s,%s\nte_radius,*,-%s,%s\n' "$t" "$t" "$t" "$t" > "$tmp/tol.csv"
  for rule in simple guarded; do
    for b in "$tmp"/*.csv; do
      [ "$b" = "$tmp/tol.csv" ] && continue
      "$bin/compare" "$b" --nominal "${b%.csv}.stl" --tolerances "$tmp/tol.csv" --decision-rule "$rule" \
        --report "$tmp/report.txt" -o /dev/null 2>/dev/null || true
      head -n 1 "$tmp/report.txt"
    done | awk -v t="$t" -v rule="$rule" '{ gsub(/[(,]/, " "); p += $3; f += $5; u += $10 }
      END { printf "%-9s %-8s %6d %6d %10d\n", t, rule, p, f, u }'
  done
done
# Usual tolerances on every value (guarded): each blade's verdict.
printf 'item,section,low,high\nprofile,*,-0.04,0.04\nchord,*,-0.05,0.05\nmax_thickness,*,-0.02,0.02\nle_radius,*,-0.05,0.05\nte_radius,*,-0.03,0.03\nstagger,*,-0.1,0.1\ninlet_angle,*,-0.5,0.5\noutlet_angle,*,-0.5,0.5\n' > "$tmp/usual.csv"
echo "profile +-0.04, chord +-0.05, max thickness +-0.02, radii +-0.05/+-0.03 mm, stagger +-0.1, metal angles +-0.5 deg:"
for b in "$tmp"/*.csv; do
  case "$b" in "$tmp/tol.csv" | "$tmp/usual.csv") continue ;; esac
  code=0
  "$bin/compare" "$b" --nominal "${b%.csv}.stl" --tolerances "$tmp/usual.csv" --report "$tmp/report.txt" \
    -o /dev/null 2>/dev/null || code=$?
  echo "  $(basename "${b%.csv}"): exit $code, $(head -n 1 "$tmp/report.txt")"
done
# The expanded uncertainties U written for the radii.
for b in "$tmp"/*.csv; do
  case "$b" in "$tmp/tol.csv" | "$tmp/usual.csv") continue ;; esac
  "$bin/compare" "$b" --nominal "${b%.csv}.stl" --tolerances "$tmp/tol.csv" --report "$tmp/report.txt" \
    -o /dev/null 2>/dev/null || true
  awk '{ for (i = 1; i < NF; ++i) if ($i == "+-") print $(i + 1) }' "$tmp/report.txt"
done | sort -g | awk '{ u[NR] = $1 } END { if (NR) printf "U of the radii: %d values, median %s, largest %s mm\n", NR, u[int((NR + 1) / 2)], u[NR] }'
