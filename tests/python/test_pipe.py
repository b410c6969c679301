# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python pipe gives the same params as the tools, byte for byte in CSV (numbers
formatted in Python as the tools format them), from an array and from a file."""
import numpy as np
import pytest

import libsection as ls
from conftest import EXAMPLE, PLANES, pipe, tool


def tools_params(tmp_path, slice_words, stdin=None, fit=(), cam=()):
    params = tmp_path / "params.csv"
    pipe([slice_words, [tool("smooth")], [tool("fitspline"), *fit], [tool("camber"), "--params", str(params), *cam]],
         stdin=stdin)
    return params.read_text()


def python_params(cloud, fit={}, cam={}):
    s = ls.slice(cloud, normal=(0, 0, 1), at=[12, 20, 28])
    s = ls.camber(ls.fit_spline(ls.smooth(s), **fit), **cam)
    return s


def test_array_pipe_equals_the_tools_on_standard_input(tmp_path):
    # The tools read standard input whole and slice it in memory, as ls.slice does an array.
    expected = tools_params(tmp_path, [tool("slice"), "-"] + PLANES, stdin=EXAMPLE)
    s = python_params(ls.read_cloud(EXAMPLE))
    assert ls.to_csv(s.params) == expected
    assert s.csv("params") == expected
    assert len(s.params["chord"]) == 3


def test_file_pipe_equals_the_tools_on_a_file(tmp_path):
    # A file is sliced as it is read, by ls.slice as by the tool; flags are the tools'.
    expected = tools_params(tmp_path, [tool("slice"), EXAMPLE] + PLANES, fit=["--smoothing-length", "0.2"],
                            cam=["--stations", "0.1,0.5,0.9"])
    s = python_params(EXAMPLE, fit={"smoothing_length": 0.2}, cam={"stations": [0.1, 0.5, 0.9]})
    assert ls.to_csv(s.params) == expected
    assert list(s.table("thickness")["fraction"][:3]) == [0.1, 0.5, 0.9]


def test_stream_round_trip_and_history():
    s = ls.slice(ls.read_cloud(EXAMPLE), normal=(0, 0, 1), at=[20])
    assert s.history == ["libsection.slice --normal 0,0,1 --at 20"]
    again = ls.parse_stream(s.text())
    assert again.tables == s.tables
    for name in s.tables:
        for column, values in s.table(name).items():
            assert np.array_equal(again.table(name)[column], values)


def test_bad_input_raises_a_clear_error():
    with pytest.raises(ValueError, match=r"expected an array of shape \(N, 3\)"):
        ls.slice(np.zeros((10, 2)), normal=(0, 0, 1), at=[1])
    with pytest.raises(ValueError, match="row 3 holds a value that is not finite"):
        ls.slice(np.array([[0, 0, 0]] * 3 + [[np.nan, 0, 0]]), normal=(0, 0, 1), at=[1])
    with pytest.raises(ValueError, match="slice: usage error: .*--slab"):
        ls.slice(ls.read_cloud(EXAMPLE), at=[20], slab=-1)
    with pytest.raises(ValueError, match="no section planes given"):
        ls.slice(ls.read_cloud(EXAMPLE))
    with pytest.raises(ValueError, match="no section could be sliced"):
        ls.slice(ls.read_cloud(EXAMPLE), normal=(0, 0, 1), at=[500])
    with pytest.raises(KeyError, match="no 'params' table"):
        ls.Stream()["params"]
    with pytest.raises(ValueError, match="cannot read|No such file|example_none"):
        ls.read_cloud("example_none.ply")


def test_progress_reports_and_cancels():
    seen = []
    cloud = ls.read_cloud(EXAMPLE, progress=lambda stage, done, total: seen.append((stage, done, total)))
    assert seen[-1] == ("read", len(cloud), len(cloud))  # a binary PLY declares its count
    sections = []
    s = ls.slice(EXAMPLE, normal=(0, 0, 1), at=[12, 20, 28], progress=lambda *e: sections.append(e))
    assert sections == [("slice", 1, 3), ("slice", 2, 3), ("slice", 3, 3)]
    assert len(s.table("frames")["section"]) == 3
    with pytest.raises(ls.Cancelled, match="slice: cancelled"):
        ls.slice(EXAMPLE, normal=(0, 0, 1), at=[12, 20, 28], progress=lambda stage, done, total: done < 2)
    # An array held in memory is told the same way (it was not told at all).
    told = []
    ls.slice(cloud, normal=(0, 0, 1), at=[12, 20, 28], progress=lambda *e: told.append(e))
    assert told == sections
    with pytest.raises(ls.Cancelled, match="slice: cancelled"):
        ls.slice(cloud, normal=(0, 0, 1), at=[12, 20, 28], progress=lambda stage, done, total: done < 2)
    assert issubclass(ls.Cancelled, ls.Error)


def test_a_doubtful_unit_flags_every_row_as_the_tools_do(tmp_path):
    # The example blade in inches, read without --units: taken as mm, its extent doubtful.
    # camber_stream flags every row as the camber tool does (it did not before, from Python).
    inches = tmp_path / "inches.xyz"
    np.savetxt(inches, ls.read_cloud(EXAMPLE) / 25.4, fmt="%.12g")
    at = [f"{z / 25.4:.12g}" for z in (12, 20, 28)]
    expected = tools_params(tmp_path, [tool("slice"), str(inches), "--normal", "0,0,1", "--at", ",".join(at)])
    with pytest.warns(UserWarning, match="--units in"):
        s = ls.slice(str(inches), normal=(0, 0, 1), at=[float(z) for z in at])
    s = ls.camber(ls.fit_spline(ls.smooth(s)))
    assert ls.to_csv(s.params) == expected
    assert all(int(f) & (1 << 22) for f in s.params["flags"])
    assert sum("fail check units" in i["message"] for i in s.issues) == 3


def test_rows_and_surfaces_of_revolution_as_the_tools_take_them(tmp_path):
    # No planes: sparse rows are the sections (slice ROWS); axis: a rotor's rows cut on their
    # cylinders (slice --axis). Both were refused from Python as "no section planes given".
    rows, rotor = tmp_path / "rows.xyz", tmp_path / "rotor.xyz"
    pipe([[tool("bladegen"), "--kind", "turbine", "--rows", "3", "--row-pitch", "3", "--spacing", "0.2",
           "--noise", "0.003", "--seed", "3", "-o", str(rows)]])
    pipe([[tool("bladegen"), "--kind", "compressor", "--rotor", "cylinder", "--rows", "2", "--spacing", "0.1",
           "-o", str(rotor)]])
    for cloud, words, flags in [(rows, [], {}), (rotor, ["--axis", "0,0,0,1,0,0"], {"axis": (0, 0, 0, 1, 0, 0)})]:
        expected = tools_params(tmp_path, [tool("slice"), str(cloud), *words])
        s = ls.slice(str(cloud), **flags)
        assert s.notes[-1].startswith("sampling kind=rows")
        assert ls.to_csv(ls.camber(ls.fit_spline(ls.smooth(s))).params) == expected
    with pytest.raises(ls.Error, match="not sparse rows .* but a dense scan"):
        ls.slice(EXAMPLE)
    # Both told to progress section by section (they ran without it), and cancelled.
    told = []
    ls.slice(str(rotor), axis=(0, 0, 0, 1, 0, 0), progress=lambda *e: told.append(e))
    assert told == [("slice", 1, 2), ("slice", 2, 2)]
    with pytest.raises(ls.Cancelled, match="slice: cancelled"):
        ls.slice(str(rotor), axis=(0, 0, 0, 1, 0, 0), progress=lambda stage, done, total: False)


def test_a_mesh_is_told_to_progress_section_by_section(tmp_path):
    mesh = tmp_path / "blade.stl"
    pipe([[tool("bladegen"), "--kind", "turbine", "--mesh", "--profile-points", "400", "--layers", "20", "-o",
           str(mesh)]])
    told = []
    s = ls.slice(str(mesh), normal=(0, 0, 1), at=[12, 20, 28], progress=lambda *e: told.append(e))
    assert told == [("slice", 1, 3), ("slice", 2, 3), ("slice", 3, 3)]
    assert not s.issues
    with pytest.raises(ls.Cancelled, match="slice: cancelled"):
        ls.slice(str(mesh), normal=(0, 0, 1), count=5, progress=lambda stage, done, total: done < 2)


def test_blade_gives_the_tools_tables(tmp_path, example_splines):
    camber = tmp_path / "camber.csv"
    camber.write_bytes(pipe([[tool("camber"), str(example_splines)]]))
    expected = ls.parse_stream(pipe([[tool("blade"), str(camber), "--format", "stream", "--samples", "50"]]).decode())
    s = ls.blade(ls.read_stream(str(camber)), samples=50)
    for name in ("blade", "stacking"):
        assert s.csv(name) == expected.csv(name), name
    assert len(s.table("blade")["section"]) == 3
    assert s.history[-1] == "libsection.blade --samples 50"
    with pytest.raises(ValueError, match="plot is the tool's"):
        ls.blade(s, plot="blade.svg")
    one = ls.slice(EXAMPLE, normal=(0, 0, 1), at=[20])
    with pytest.raises(ls.Error):
        ls.blade(ls.camber(ls.fit_spline(ls.smooth(one))))  # one section is not a blade
