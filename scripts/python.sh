#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the Python module libsection with pip (pyproject.toml: scikit-build-core runs CMake
# into build-python/ for the module alone; ccache hands over the library's objects when
# scripts/build.sh compiled them already) for Debian's python3, then:
#   scripts/python.sh install   installs it for the user (~/.local), so that
#                               `python3 -c "import libsection"` works
#   scripts/python.sh test      installs it into build-python/site and runs pytest on
#                               tests/python with it (the tools of ${BUILD_DIR:-build}/tools)
# numpy, pandas, pytest and pybind11 come from Debian (scripts/setup.sh); what Debian 12
# lacks (scikit-build-core, and ezdxf for the tests) is installed from PyPI with pip for the
# user, once. PYTHON=... picks another interpreter (its numpy must suit pybind11 2.10: < 2).
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-install}"
PYTHON="${PYTHON:-$(command -v /usr/bin/python3 || command -v python3)}"
# The compilers and paths of scripts/build.sh, so that ccache finds its objects.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CC="${CC:-cc}" CXX="${CXX:-c++}"

# pip for the user (Debian marks its Python as managed by apt: PEP 668), or into the
# virtual environment the interpreter runs in.
pip_install() {
  local where=(--user --break-system-packages)
  "$PYTHON" -c 'import sys; sys.exit(sys.prefix == sys.base_prefix)' && where=()
  "$PYTHON" -m pip install --quiet --disable-pip-version-check --root-user-action=ignore "${where[@]}" "$@"
}
needs=("scikit_build_core:scikit-build-core>=0.10")
[ "$mode" = test ] && needs+=("ezdxf:ezdxf" "pytest:pytest" "pandas:pandas")
for need in "${needs[@]}"; do
  "$PYTHON" -c "import ${need%%:*}" 2>/dev/null || pip_install "${need#*:}"
done

build=(--no-build-isolation --no-deps --disable-pip-version-check --quiet --root-user-action=ignore)
case "$mode" in
  install)
    pip_install "${build[@]}" .
    "$PYTHON" -c 'import libsection; print("libsection", libsection.__version__, "for", __import__("sys").executable)'
    ;;
  test)
    rm -rf build-python/site
    "$PYTHON" -m pip install "${build[@]}" --target build-python/site .
    bin="${BUILD_DIR:-build}"
    case "$bin" in /*) ;; *) bin="$PWD/$bin" ;; esac
    PYTHONPATH="$PWD/build-python/site" SECTION_BIN="$bin/tools" \
      "$PYTHON" -m pytest -q -p no:cacheprovider tests/python
    ;;
  *) echo "usage: scripts/python.sh [install|test]" >&2; exit 2 ;;
esac
