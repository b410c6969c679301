# SPDX-License-Identifier: GPL-3.0-or-later
"""libsection.compare against known rigid motions: an ellipse's points and a generated blade
section moved by a known rotation and translation are fitted back onto their nominal, on a
nominal prepared once (Nominal) and prepared per call (a Spline), with the same results."""
import math

import numpy as np
import pytest

import libsection as ls


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
