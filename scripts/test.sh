#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sets up the dependencies, builds, and runs every test: Catch2 and the tool tests with ctest,
# then the Python module's with pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
(cd "${BUILD_DIR:-build}" && ctest --output-on-failure -j "$(nproc)")
bash scripts/python.sh test   # the Python module built with pip, and pytest on tests/python
