# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python API against exact truth: an ellipse, a noisy circle, and generated blades
(libsection.generate: the exact sections bladegen writes), within the accuracy targets of
docs/ACCURACY.md (chord 10 um, max thickness 5 um, LE radius 3 %, TE radius 10 %, angles 0.5 deg)."""
import numpy as np
import pytest

import libsection as ls


def ellipse(a, b, n, phase=0.0):
    t = phase + 2 * np.pi * np.arange(n) / n
    return np.column_stack([a * np.cos(t), b * np.sin(t)])


def test_fit_spline_runs_on_the_ellipse():
    spline = ls.fit_spline(ellipse(20, 3, 800))
    assert isinstance(spline, ls.Spline) and spline.closed and spline.degree == 3
    t = np.linspace(spline.t_min, spline.t_max, 3001)
    p = spline(t)
    assert p.shape == (3001, 2)
    # |(x/a)^2 + (y/b)^2 - 1| * b / 2 ~ distance off the ellipse near its flat sides: under 1 um
    off = np.abs((p[:, 0] / 20) ** 2 + (p[:, 1] / 3) ** 2 - 1)
    assert off.max() * 3 / 2 < 1e-3
    assert spline(spline.t_min).shape == (2,)
    assert np.allclose(spline(spline.t_max), spline(spline.t_min))
    assert spline.clamped().knots[0] == spline.knots[0]


def test_camber_of_the_ellipse_gives_its_chord_and_thickness():
    r = ls.camber(ls.fit_spline(ellipse(20, 3, 800)), le_direction=[-1, 0])
    p = r["params"]
    assert abs(p["chord"] - 40) < 1e-3
    assert abs(p["max_thickness"] - 6) < 1e-3
    assert abs(p["max_thickness_pos"] - 0.5) < 1e-3
    mid = np.argmin(np.abs(r["thickness"]["fraction"] - 0.5))
    assert abs(r["thickness"]["thickness"][mid] - 6) < 1e-3
    assert r["camber"]["u"].shape == r["camber"]["v"].shape


def test_failed_checks_name_what_flags_a_value():
    # le_circle (bit 2) flags the LE's values and the chord it ends, jump_chord (bit 14) the chord.
    flags = float(4 + 16384)
    assert ls.failed_checks(flags) == ["le_circle", "jump_chord"]
    assert ls.failed_checks(flags, "chord") == ["le_circle", "jump_chord"]
    assert ls.failed_checks(flags, "le_radius") == ["le_circle"]
    assert ls.failed_checks(flags, "max_thickness") == []
    assert ls.failed_checks(2.0 ** 42) == []  # no mask: no check
    # A clean ellipse's values and thickness stations: none flagged.
    r = ls.camber(ls.fit_spline(ellipse(20, 3, 800)), le_direction=[-1, 0])
    assert ls.failed_checks(r["params"]["flags"]) == []
    assert all(ls.failed_checks(f) == [] for f in r["thickness"]["flags"])


def test_smooth_moves_noisy_points_toward_the_circle():
    rng = np.random.default_rng(3)
    clean = ellipse(5, 5, 400)
    noisy = clean + rng.normal(0, 0.01, clean.shape)
    smoothed = ls.smooth(noisy, length=0.5)
    before = np.abs(np.linalg.norm(noisy, axis=1) - 5).std()
    after = np.abs(np.linalg.norm(smoothed, axis=1) - 5).std()
    assert smoothed.shape == noisy.shape
    assert after < before / 2


@pytest.mark.parametrize("kind,z", [("turbine", 20.0), ("compressor", 35.0), ("thick-root", 5.0)])
def test_generated_section_profile_gives_the_true_params(kind, z):
    truth = ls.generate.truth(kind, z)
    profile = truth["profile"][::10]  # 2000 exact points, counterclockwise from the LE
    p = ls.camber(ls.fit_spline(profile))["params"]
    check_params(p, truth)


def test_generated_scan_through_the_pipe_gives_the_true_params():
    cloud = ls.generate.scan("compressor", noise=0.003, z_min=16, z_max=24, seed=4)
    assert cloud.ndim == 2 and cloud.shape[1] == 3 and len(cloud) > 10000
    s = ls.camber(ls.fit_spline(ls.smooth(ls.slice(cloud, normal=(0, 0, 1), at=[20]))))
    assert not s.issues, s.issues
    params = {k: v[0] for k, v in s.params.items()}
    check_params(params, ls.generate.truth("compressor", 20.0))


def check_params(p, truth):
    assert abs(p["chord"] - truth["chord"]) < 0.010
    assert abs(p["max_thickness"] - truth["max_thickness"]) < 0.005
    assert abs(p["le_radius"] / truth["le_radius"] - 1) < 0.03
    assert abs(p["te_radius"] / truth["te_radius"] - 1) < 0.10
    for angle in ("stagger", "inlet_angle", "outlet_angle"):
        assert abs(p[angle] - truth[angle]) < 0.5, angle


def test_generate_refuses_an_unknown_kind():
    assert "turbine" in ls.generate.kinds()
    with pytest.raises(ValueError, match="unknown kind 'rotor'.*known: turbine"):
        ls.generate.truth("rotor", 10)


def test_a_curve_crossing_over_sparse_ordered_points_says_they_are_sparse():
    # 20 points of a compressor section, crowded at its edges and 5-8 mm apart mid-chord: in
    # order, yet the curve through them crosses itself. It was said "not ordered along one
    # profile", which sent the user to sort points that were sorted.
    p = ls.generate.truth("compressor", 40)["profile"]
    th = np.linspace(0, 2 * np.pi, 20, endpoint=False)
    idx = np.unique(((th - 0.8 * np.sin(2 * th)) / (2 * np.pi) * len(p)).astype(int) % len(p))
    with pytest.raises(ls.Error, match="lie in order along one profile: they are too sparse"):
        ls.fit_spline(p[idx])
    shuffled = p[idx][np.random.default_rng(3).permutation(len(idx))]
    with pytest.raises(ls.Error, match="its points are not ordered along one profile"):
        ls.fit_spline(shuffled)


def test_camber_of_a_plain_profile_is_the_same_from_any_start():
    # A generated compressor section, a point every 0.2 mm with 2 um of noise (edge radii
    # 0.3 mm, a few points on each): the same parameters whichever point the array starts at
    # and whichever way it runs, the thickness within its 5 um target.
    truth = ls.generate.truth("compressor", 8.0)
    dense = truth["profile"]
    s = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))])
    pick = np.unique(np.searchsorted(s, np.arange(0, s[-1] - 0.1, 0.2)))
    rng = np.random.default_rng(11)
    points = dense[pick] + rng.normal(0, 0.002, (len(pick), 1)) * truth["profile_normal"][pick]
    first = ls.camber(points)["params"]
    for k in (len(points) // 3, 2 * len(points) // 3):
        again = ls.camber(np.roll(points, -k, axis=0)[::-1])["params"]
        assert again == pytest.approx(first, rel=0, abs=0, nan_ok=True)
    assert ls.canonical_loop(points).shape == points.shape
    assert abs(first["max_thickness"] - truth["max_thickness"]) < 0.005


def test_camber_of_a_plain_profile_flags_an_edge_its_points_do_not_fix():
    # A turbine TE of 0.45 mm radius with points 0.4 mm apart: fitted from the profile's
    # other end its point moves 0.27 mm (te_start); the same points 0.05 mm apart: nothing.
    truth = ls.generate.truth("turbine", 50.0)
    dense = truth["profile"]
    s = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))])
    for spacing, flagged in ((0.4, True), (0.05, False)):
        pick = np.unique(np.searchsorted(s, np.arange(0, s[-1] - spacing / 2, spacing)))
        r = ls.camber(dense[pick])
        assert ("te_start" in ls.failed_checks(r["params"]["flags"], "chord")) == flagged
        assert any("te_start" in i for i in r["issues"]) == flagged


def test_measure_cavity_gives_the_wall_of_a_circle_inside_an_ellipse():
    profile = ls.fit_spline(ellipse(20, 3, 4000))
    inside = ls.measure_cavity(profile, ls.fit_spline(ellipse(1.5, 1.5, 2000) + [0, 0.5]))
    assert inside["place"] == "inside"
    assert abs(inside["wall"] - 1.0) < 1e-5  # at the co-vertex (0, 3)
    assert np.linalg.norm(inside["profile_point"][0] - [0, 3]) < 1e-3
    assert abs(inside["area"] - np.pi * 1.5 ** 2) < 1e-4
    assert np.linalg.norm(inside["centroid"][0] - [0, 0.5]) < 1e-6
    assert ls.measure_cavity(profile, ls.fit_spline(ellipse(1, 1, 800) + [30, 0]))["place"] == "outside"
    assert ls.measure_cavity(profile, ls.fit_spline(ellipse(1, 1, 800) + [0, 3]))["place"] == "crossing"
    with pytest.raises(ValueError):
        ls.measure_cavity(profile, profile, samples=10)


def test_side_walls_gives_the_wall_to_each_side_of_an_ellipse():
    profile = ls.fit_spline(ellipse(20, 3, 4000))
    loop = ls.fit_spline(ellipse(1.5, 1.5, 2000) + [0, 0.5])
    t = np.linspace(profile.t_min, profile.t_max, 100001)
    at = profile(t)  # parted at the ends of the major axis: the upper side runs forward from (20, 0)
    right = t[np.argmin(np.linalg.norm(at - [20, 0], axis=1))]
    left = t[np.argmin(np.linalg.norm(at - [-20, 0], axis=1))]
    upper, lower = ls.side_walls(profile, loop, right, left)
    assert abs(upper["wall"] - 1.0) < 1e-5  # to (0, 3)
    assert abs(lower["wall"] - 2.0) < 1e-5  # to (0, -3)
    assert np.linalg.norm(lower["profile_point"][0] - [0, -3]) < 1e-3
    with pytest.raises(ValueError):
        ls.side_walls(profile, loop, right, right)
