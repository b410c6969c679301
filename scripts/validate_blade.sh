#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The whole-blade values (docs/BLADE.md) through the full pipe on noisy whole-blade scans of
# generated blades with a known stacking law, against bladegen's exact truth: per kind and
# seed, the largest error of the values not flagged and the number flagged.
# Usage: scripts/validate_blade.sh [seeds (default 1 2 3 4)]
# Environment: SECTION_BIN (default build/tools).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${SECTION_BIN:-$here/../build/tools}"
seeds="${*:-1 2 3 4}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
at=6,12,18,24,30,36,42,48,54
printf '%-11s %4s  %-28s %9s %9s %9s %9s  %s\n' kind seed "law (lean sweep bow, mm)" "twist deg" "lean um" \
  "sweep um" "bow um" "flagged (twist position bow)"
for kind in turbine compressor; do
  for seed in $seeds; do
    # A law per seed: lean, sweep and bow of both signs.
    law=$(awk -v s="$seed" 'BEGIN { printf "%.2f %.2f %.2f", 1.5 * sin(s), 0.8 * cos(2 * s), 0.4 * sin(3 * s + 1) }')
    set -- $law
    "$bin/bladegen" --kind "$kind" --points --noise 0.005 --holes 5 --density-min 0.25 --outliers 0.0002 \
      --lean "$1" --sweep "$2" --bow "$3" --seed "$seed" -o "$tmp/blade.ply" --truth "$tmp/truth.csv" --at "$at" \
      >/dev/null 2>&1
    "$bin/slice" "$tmp/blade.ply" --at "$at" 2>/dev/null | "$bin/smooth" 2>/dev/null | "$bin/fitspline" 2>/dev/null |
      "$bin/camber" --allow-partial 2>/dev/null | "$bin/blade" --allow-partial -o "$tmp/blade.csv" 2>/dev/null || true
    awk -F, -v kind="$kind" -v seed="$seed" -v law="$law" '
      FNR == 1 { for (i = 1; i <= NF; ++i) c[FILENAME, $i] = i; next }
      FILENAME ~ /truth/ { n++; z[n] = $c[FILENAME, "z"]; st[n] = $c[FILENAME, "stagger"]
        x[n] = $c[FILENAME, "centroid_x"]; y[n] = $c[FILENAME, "centroid_y"]; next }
      { k = 0; for (j = 1; j <= n; ++j) if ((z[j] - $c[FILENAME, "span"]) ^ 2 < 1e-4) k = j
        if (k == 0) next
        m++; id[m] = k; tw[m] = $c[FILENAME, "twist"]; le[m] = $c[FILENAME, "lean"]
        sw[m] = $c[FILENAME, "sweep"]; bo[m] = $c[FILENAME, "bow"]; f[m] = $c[FILENAME, "flags"] }
      function abs(v) { return v < 0 ? -v : v }
      function bit(v, b) { return int(v / b) % 2 }
      END {
        h = id[1]; t = id[m]; r = id[1]
        for (i = 1; i <= m; ++i) { k = id[i]; w = (z[k] - z[h]) / (z[t] - z[h])
          if (bit(f[i], 1) || bit(f[i], 128)) ft++; else et = abs(tw[i] - (st[k] - st[r])) > et ? abs(tw[i] - (st[k] - st[r])) : et
          if (bit(f[i], 2) || bit(f[i], 128)) fp++; else {
            el = abs(le[i] - (y[k] - y[r])) > el ? abs(le[i] - (y[k] - y[r])) : el
            es = abs(sw[i] - (x[k] - x[r])) > es ? abs(sw[i] - (x[k] - x[r])) : es }
          if (bit(f[i], 2) || bit(f[i], 64) || bit(f[i], 128)) fb++; else {
            b = y[k] - (y[h] + w * (y[t] - y[h])); eb = abs(bo[i] - b) > eb ? abs(bo[i] - b) : eb } }
        printf "%-11s %4s  %-28s %9.4f %9.2f %9.2f %9.2f  %d %d %d of %d\n", kind, seed, law, et, 1000 * el, 1000 * es,
          1000 * eb, ft, fp, fb, m }' "$tmp/truth.csv" "$tmp/blade.csv"
  done
done
echo "targets: twist 0.05 deg, lean and bow 10 um (issue 23)"
