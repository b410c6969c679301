# SPDX-License-Identifier: GPL-3.0-or-later
"""The pandas reader of the stream, the stream_tables-style reader and the number format."""
import importlib.util
import math
import os

import numpy as np
import pandas as pd

import libsection as ls
from conftest import ROOT


def test_read_tables_gathers_every_part(example_splines):
    text = example_splines.read_text()
    assert "# part 2" in text  # the tools write a part per section
    tables = ls.read_tables(example_splines)
    s = ls.read_stream(str(example_splines))
    assert set(tables) == set(s.tables)
    for name, frame in tables.items():
        assert isinstance(frame, pd.DataFrame)
        assert list(frame.columns) == list(s.table(name))
        for column in frame.columns:
            assert np.array_equal(frame[column].to_numpy(), s.table(name)[column])
    assert sorted(tables["splines"]["section"].unique()) == [0, 1, 2]
    with open(example_splines) as f:  # an open file and the text work too
        assert ls.read_tables(f)["frames"].equals(tables["frames"])
    assert ls.read_tables(text)["frames"].equals(tables["frames"])


def test_table_is_what_stream_tables_gives(example_splines):
    spec = importlib.util.spec_from_file_location("stream_tables", os.path.join(ROOT, "scripts", "stream_tables.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert ls.table(example_splines, "frames") == module.table(example_splines, "frames")
    assert ls.table(example_splines, "spline_knots") == module.table(example_splines, "spline_knots")


def test_format_number_is_the_shortest_round_trip():
    cases = [(0.0, "0"), (-0.0, "-0"), (3.0, "3"), (1e-5, "1e-05"), (1e15, "1e+15"), (123.456, "123.456"),
             (1.5e-7, "1.5e-07"), (41.231247574804435, "41.231247574804435"), (1e22, "1e+22"),
             (12345678901234567890.0, "12345678901234567168"), (math.inf, "inf"), (-2.5, "-2.5")]
    for x, text in cases:
        assert ls.format_number(x) == text
        if math.isfinite(x):
            assert float(text) == x
    rng = np.random.default_rng(5)
    for x in rng.standard_normal(2000) * 10.0 ** rng.integers(-12, 12, 2000):
        assert float(ls.format_number(x)) == x
        assert len(ls.format_number(x)) <= len(repr(float(x)))


def test_to_csv_writes_the_tools_layout():
    assert ls.to_csv({"section": [0, 1], "chord": [41.25, 0.1]}) == "section,chord\n0,41.25\n1,0.1\n"
    assert ls.to_csv(pd.DataFrame({"a": [1.0]})) == "a\n1\n"
