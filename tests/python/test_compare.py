# SPDX-License-Identifier: GPL-3.0-or-later
"""libsection.compare against known rigid motions: an ellipse's points and a generated blade
section moved by a known rotation and translation are fitted back onto their nominal, on a
nominal prepared once (Nominal) and prepared per call (a Spline), with the same results; and
compare_stream on a whole stream, against the compare tool."""
import math
import os
import subprocess

import numpy as np
import pytest

import libsection as ls
from conftest import ROOT, pipe, tool

TOLERANCES = os.path.join(ROOT, "data", "example_tolerances.csv")


def moved(p, degrees, shift):
    a = math.radians(degrees)
    r = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    return p @ r.T + shift


@pytest.mark.parametrize("kind,z", [("turbine", 20.0), ("compressor", 35.0)])
def test_compare_fits_a_moved_section_back_onto_its_nominal(kind, z):
    truth = ls.generate.truth(kind, z)
    spline = ls.fit_spline(truth["profile"][::10])
    nominal = ls.prepare_nominal(spline)
    rng = np.random.default_rng(7)
    clean = truth["profile"][::7]
    measured = moved(clean + rng.normal(0, 0.002, clean.shape), 0.05, np.array([0.03, -0.02]))
    r = ls.compare(nominal, measured)
    assert r["converged"]
    # The fit undoes the move: the clean points moved and fitted back lie where they were.
    back = moved(moved(clean, 0.05, np.array([0.03, -0.02])), r["angle"], r["translation"])
    assert np.abs(back - clean).max() < 2e-3  # 2 um against 2 um of noise over ~3000 points
    assert r["rms_after"] < 3e-3 < r["rms_before"]
    points = r["points"]
    assert points["after"].shape == (len(measured),) and points["foot"].shape == (len(measured), 2)
    assert set(np.unique(points["zone"])) == {1, 2, 3, 4}
    assert r["zones"]["le"]["measured"] and r["zones"]["whole"]["points"] == len(measured)
    # The same results on a Spline (prepared in the call) and on the prepared nominal.
    again = ls.compare(spline, measured)
    assert again["angle"] == r["angle"] and np.array_equal(again["points"]["after"], points["after"])


def test_compare_options_and_errors():
    truth = ls.generate.truth("turbine", 20.0)
    spline = ls.fit_spline(truth["profile"][::10])
    nominal = ls.prepare_nominal(spline, fit="minimum-zone")
    points = truth["profile"][::11] + np.array([0.01, 0.0])
    r = ls.compare(nominal, points)
    least_squares = ls.compare(nominal, points, fit="least-squares", edge_zone=0.05)
    # The shift undone to within the nominal spline's own error (under 1 um), the largest
    # deviation below least squares'.
    assert abs(r["translation"][0] + 0.01) < 1e-3 and r["max_after"] < 1e-3
    assert r["max_after"] < least_squares["max_after"]
    r = ls.compare(nominal, points, freedom="none")
    assert r["angle"] == 0 and r["translation"][0] == 0
    with pytest.raises(ValueError, match="edge zone"):
        ls.compare(nominal, points, edge_zone=0.1)  # prepared for 0.05
    with pytest.raises(ValueError, match="--fit"):
        ls.compare(nominal, points, fit="best")
    with pytest.raises(ValueError, match="shape"):
        ls.compare(nominal, points[:, :1])


@pytest.fixture(scope="module")
def inspected(example_splines, tmp_path_factory):
    """The example's camber stream and its nominal mesh, made by the tools (as scripts/example.sh)."""
    d = tmp_path_factory.mktemp("compare")
    camber = d / "camber.csv"
    camber.write_bytes(pipe([[tool("camber"), str(example_splines)]]))
    nominal = d / "nominal.stl"
    pipe([[tool("bladegen"), "--kind", "turbine", "--mesh", "--profile-points", "4000", "--layers", "16", "-o",
           str(nominal)]])
    return camber, nominal


EXIT_OF = {"passed": 0, "failed": 4, "not measured": 5, "uncertain": 6}


def test_stream_compare_gives_the_tools_tables_verdict_and_report(inspected, tmp_path):
    camber, nominal = inspected
    report = tmp_path / "report.txt"
    words = [tool("compare"), str(camber), "--nominal", str(nominal), "--tolerances", TOLERANCES, "--report",
             str(report), "--format", "stream"]
    r = subprocess.run(words, capture_output=True)
    assert r.returncode in EXIT_OF.values(), r.stderr.decode()
    expected = ls.parse_stream(r.stdout.decode())
    s = ls.compare_stream(ls.read_stream(str(camber)), nominal, tolerances=TOLERANCES)
    for name in ("fits", "deviations", "zones", "compared", "verdicts"):
        assert s.csv(name) == expected.csv(name), name
    assert EXIT_OF[ls.verdict(s)] == r.returncode
    assert ls.compare_report(s) == report.read_text()
    assert s.history[-1] == "libsection.compare_stream --tolerances " + TOLERANCES


def test_stream_compare_on_a_stream_nominal_and_errors(inspected, tmp_path):
    camber, nominal = inspected
    measured = ls.read_stream(str(camber))
    # The measured points against their own spline: no motion to undo (under 10 nm and
    # 1e-4 degrees on three sections of ~3300 points each), the deviations the fit's residuals.
    s = ls.compare_stream(measured, measured)
    fits = s.table("fits")
    assert len(fits["section"]) == 3
    assert np.abs(fits["shift_u"]).max() < 1e-5 and np.abs(fits["shift_v"]).max() < 1e-5
    assert np.abs(fits["angle"]).max() < 1e-4
    splines = measured.table("splines")
    assert np.allclose(fits["rms_after"], splines["rms"], rtol=0.05)
    assert ls.verdict(s) == "passed"  # nothing toleranced
    # A tolerance on a section the stream lacks judges it not measured, with an issue.
    tolerances = tmp_path / "tolerances.csv"
    tolerances.write_text("item,section,low,high\nchord,7,-0.05,0.05\n")
    s = ls.compare_stream(measured, nominal, tolerances=str(tolerances))
    assert ls.verdict(s) == "not measured"
    assert any(i["section"] == 7 for i in s.issues)
    with pytest.raises(ValueError, match="a stream says its own unit"):
        ls.compare_stream(measured, measured, nominal_units="m")
    with pytest.raises(ValueError, match="format is the tool's"):
        ls.compare_stream(measured, nominal, format="json")
    with pytest.raises(ls.Error, match="missing.stl"):
        ls.compare_stream(measured, tmp_path / "missing.stl")
    with pytest.raises(ls.Error, match="missing.csv"):
        ls.compare_stream(measured, nominal, tolerances=str(tmp_path / "missing.csv"))
