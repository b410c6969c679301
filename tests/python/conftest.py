# SPDX-License-Identifier: GPL-3.0-or-later
"""Fixtures of the Python tests: the tools (SECTION_BIN, default build/tools) and the
example blade's stream through them, made once per session."""
import os
import subprocess

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLE = os.path.join(ROOT, "data", "example_blade.ply")
PLANES = ["--normal", "0,0,1", "--at", "12,20,28"]


def tool(name):
    path = os.path.join(os.environ.get("SECTION_BIN", os.path.join(ROOT, "build", "tools")), name)
    if not os.access(path, os.X_OK):
        pytest.fail(f"no {name} binary at {path}: build the tools (scripts/build.sh) or set SECTION_BIN")
    return path


def pipe(commands, stdin=None, cwd=None):
    """Runs a pipe of commands (lists of words) and returns the last one's standard output."""
    data = open(stdin, "rb").read() if stdin else None
    for words in commands:
        r = subprocess.run(words, input=data, capture_output=True, cwd=cwd)
        assert r.returncode == 0, f"{' '.join(words)}: exit {r.returncode}: {r.stderr.decode()[-500:]}"
        data = r.stdout
    return data


@pytest.fixture(scope="session")
def example_splines(tmp_path_factory):
    """The example blade through slice | smooth | fitspline --samples 400 (the tools)."""
    out = tmp_path_factory.mktemp("example") / "splines.csv"
    out.write_bytes(pipe([[tool("slice"), EXAMPLE] + PLANES, [tool("smooth")],
                          [tool("fitspline"), "--samples", "400"]]))
    return out
