#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Prints the python of engeom's virtual environment (ENGEOM_VENV, default
# ~/.cache/libsection-engeom), made on the first call: engeom 0.5.0 and numpy from PyPI.
# Used by scripts/compare_engeom.sh and scripts/peers/python_speed.sh.
set -euo pipefail
venv="${ENGEOM_VENV:-$HOME/.cache/libsection-engeom}"
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import engeom, numpy" 2>/dev/null; then
  python3 -m venv "$venv" >&2
  "$venv/bin/pip" install -q "engeom==0.5.0" numpy >&2
fi
echo "$venv/bin/python"
