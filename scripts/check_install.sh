#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs libsection into a temporary prefix and uses it as an embedding project would:
# the installed tools run, examples/ configures with find_package(libsection CONFIG) and
# runs on a synthetic blade (its errors against the exact design must stay below 10 um)
# and on a mesh file written by the installed bladegen, and the pkg-config file compiles
# and links a one-file program.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
[ -f "$BUILD_DIR/CMakeCache.txt" ] || bash scripts/build.sh > /dev/null
cmake --build "$BUILD_DIR" -j "$(nproc)" > /dev/null
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
fail() { echo "check_install: FAILED: $*" >&2; exit 1; }

cmake --install "$BUILD_DIR" --prefix "$prefix" > /dev/null
[ -f "$prefix/include/section/io/stream.h" ] && [ -f "$prefix/include/section/extras/generate.h" ] && [ -f "$prefix/lib/cmake/libsection/libsectionConfig.cmake" ] \
  || fail "headers or CMake package not installed"

# 1. The installed tools find the installed library.
for tool in slice smooth fitspline camber plot bladegen; do
  "$prefix/bin/$tool" --version > /dev/null || fail "installed $tool does not run"
done

# 2. The example through the CMake package: a synthetic blade, errors in um.
gen=(); command -v ninja > /dev/null 2>&1 && gen=(-G Ninja)
cmake -S examples -B "$tmp/build" "${gen[@]}" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release > /dev/null \
  || fail "examples/ does not configure against the installed package"
cmake --build "$tmp/build" > /dev/null || fail "examples/ does not build against the installed package"
"$tmp/build/section_params" | tee "$tmp/synthetic.txt"
[ "$(grep -c 'error, um' "$tmp/synthetic.txt")" = 3 ] || fail "the example did not measure 3 sections"
awk '/error, um/ { for (i = 1; i <= 4; ++i) if ($i > 10 || $i < -10) exit 1 }' "$tmp/synthetic.txt" \
  || fail "a length is off by more than 10 um"

# 3. The example on a mesh file from the installed bladegen.
"$prefix/bin/bladegen" --mesh -o "$tmp/blade.stl" > /dev/null
"$tmp/build/section_params" "$tmp/blade.stl" 20.5 | tee "$tmp/mesh.txt"
awk 'NR == 2 && NF == 8 && $2 > 30 { ok = 1 } END { exit !ok }' "$tmp/mesh.txt" \
  || fail "no parameters measured on the mesh file"

# 4. pkg-config: compile and run a one-file program.
cat > "$tmp/pc.cpp" <<'EOF'
#include <section/bspline.h>
#include <cmath>
#include <cstdio>
#include <vector>
int main() {
  std::vector<Eigen::Vector2d> circle;
  for (int i = 0; i < 64; ++i) circle.emplace_back(std::cos(i * 0.09817477), std::sin(i * 0.09817477));
  const section::BSpline b = section::fit_curve(circle);
  std::printf("%.4f\n", section::arc_length(b, b.t_min(), b.t_max()));
}
EOF
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
# shellcheck disable=SC2046
c++ -std=c++17 "$tmp/pc.cpp" -o "$tmp/pc" $(pkg-config --cflags --libs libsection) -Wl,-rpath,"$prefix/lib" \
  || fail "pkg-config flags do not build a program"
"$tmp/pc" | awk '{ d = $1 - 6.2832; if (d > 0.001 || d < -0.001) exit 1 }' || fail "pkg-config program gives a wrong length"
echo "check_install: ok (prefix, tools, CMake package, example, pkg-config)"
