# SPDX-License-Identifier: GPL-3.0-or-later
"""libsection: blade section inspection from 3D scans, on numpy arrays.

The pipe of the tools (slice | smooth | fitspline | camber) in Python:

    import libsection as ls
    s = ls.slice(cloud, normal=(0, 0, 1), at=[12, 20, 28])   # cloud: (N, 3) array, or a file
    s = ls.camber(ls.fit_spline(ls.smooth(s)))
    s.params["chord"]                                         # one value per section (mm)

Each stage takes a Stream and returns a new one, as its tool does, with the tool's flags as
keywords (`slab=0.05` for `--slab 0.05`, `no_fill=True` for `--no-fill`; `TOOL --help`
lists them); the same options give the same numbers as the tools. On one curve instead:
`smooth(points)` -> points, `fit_spline(points)` -> Spline, `camber(spline)` or
`camber(points)` (a plain profile, as `camber PROFILE`) -> dict.
`read_tables(path)` reads a stream written by the tools into pandas DataFrames. The
inspection, as the compare tool runs it: `compare_stream(s, "nominal.stl",
tolerances="tolerances.csv")`, then `verdict(...)` and `compare_report(...)`. A value that a
failed check flags is not to be taken bare: `failed_checks(params["flags"], "max_thickness")`
names the checks that flag it.
"""
import numpy as _np

from . import _libsection
from ._libsection import (Cancelled, Error, Nominal, Spline, Stream, canonical_loop, compare_report, failed_checks,
                          generate, measure_cavity, side_walls, parse_stream, read_cloud, read_stream, verdict)
from .tables import format_number, read_tables, table, to_csv

__all__ = ["slice", "smooth", "fit_spline", "camber", "blade", "compare", "compare_stream", "compare_report", "verdict",
           "prepare_nominal", "Nominal", "Stream", "Spline",
           "Error", "Cancelled", "read_stream",
           "parse_stream", "read_cloud", "read_tables", "table", "format_number", "to_csv", "generate",
           "failed_checks", "canonical_loop", "measure_cavity", "side_walls"]
__version__ = "0.1.0"


def slice(cloud, planes=None, progress=None, **flags):
    """Cuts a cloud by planes into ordered section profiles (the slice tool).

    cloud: an (N, 3) array of points, or the path of a cloud file (sliced as it is read) or a
    mesh file. planes: an optional (P, 6) array, each row an origin and a normal; else the
    flags normal=(x, y, z) with at=[offsets] or count=N; with none, the cloud's sparse rows (or
    a plain 2D profile file) are the sections; axis=(px, py, pz, dx, dy, dz) cuts surfaces of
    revolution (with radius, cone or streamline). Other flags as the tool's (slab,
    cell, band_spacing, no_fill, units, threads, ...). Returns a Stream (tables frames, loops,
    points, skeleton); failed sections are in its issues. Raises ValueError when no section
    can be sliced or a flag is bad. progress(stage, done, total), for a file or an array cut
    on planes or taken by rows (total 0: not known before), is told each section done;
    returning False cancels the call (raises Cancelled)."""
    return _libsection.slice_stream(cloud, planes, progress, **flags)


def smooth(x, closed=True, **flags):
    """Energy-minimising smoothing (the smooth tool): a Stream -> a Stream with the table
    'smoothed'; an (N, 2) array of ordered points -> the smoothed (M, 2) array."""
    if isinstance(x, Stream):
        return _libsection.smooth_stream(x, **flags)
    return _libsection.smooth_points(x, closed, **flags)


def fit_spline(x, measured=None, **flags):
    """Closed cubic B-spline refined by distance minimisation (the fitspline tool): a Stream
    -> a Stream with the tables 'splines', 'spline_knots', 'spline_ctrl', 'gaps'; an (N, 2)
    array of ordered points (refined against `measured`, default the points) -> a Spline."""
    if isinstance(x, Stream):
        return _libsection.fit_spline_stream(x, **flags)
    return _libsection.fit_spline_points(x, measured, **flags)


def camber(x, **flags):
    """Mean-camber line and section parameters (the camber tool): a Stream -> a Stream with
    the tables 'camber', 'params', 'thickness', 'sides' (and 'walls' when a section holds
    cavities, a hollow blade's: docs/CAMBER.md); a closed Spline (a profile), or an
    (N, 2) array of a plain profile's points in order around it (fitted and checked as
    `camber PROFILE` does, whichever point they start at: canonical_loop, le_start and
    te_start) -> a dict: 'params' (name -> float: mm, degrees), 'camber', 'thickness',
    'sides' (column -> array) and 'issues'. Raises Error when the profile fails."""
    if isinstance(x, Stream):
        return _libsection.camber_stream(x, **flags)
    if isinstance(x, Spline):
        s = _libsection.camber_stream(_libsection.profile_stream(x), **flags)
    else:
        s = _libsection.plain_profile_camber(_np.asarray(x, dtype=float), **flags)
    params = s.table("params")
    if len(params["section"]) == 0:
        raise Error("camber: " + "; ".join(i["message"] for i in s.issues))
    out = {name: s.table(name) for name in ("camber", "thickness", "sides")}
    out["params"] = {k: float(v[0]) for k, v in params.items() if k != "section"}
    out["issues"] = [i["message"] for i in s.issues]
    return out


def blade(stream, **flags):
    """The whole blade from the sections of a camber stream (the blade tool, docs/BLADE.md):
    stacking line, twist, lean, bow and sweep. Flags as the tool's (reference, axis,
    control_points, samples, off_line); its outputs (format, plot, lines) are the tool's.
    Returns a copy of the stream with the tables 'blade' (one row per section) and
    'stacking' (the fitted lines); a section left out or flagged is in its issues. Raises
    Error with fewer than two sections that have params."""
    return _libsection.blade_stream(stream, **flags)


def prepare_nominal(spline, le_point=None, te_point=None, pressure_side=None, **flags):
    """A nominal profile prepared once for comparing many measured sections with it (compare):
    a closed Spline, its edge points (u, v) and pressure side (+1: left of LE -> TE, -1:
    right), by default those camber(spline) finds; flags: the compare tool's (fit, freedom,
    edge_zone, hole, outlier_distance, keep_outliers, direction, center, weights). Returns a
    Nominal. Raises ValueError for a profile that is not closed or bad flags."""
    if le_point is None or te_point is None or pressure_side is None:
        p = camber(spline)["params"]
        le_point = (p["le_u"], p["le_v"]) if le_point is None else le_point
        te_point = (p["te_u"], p["te_v"]) if te_point is None else te_point
        pressure_side = int(p["pressure_side"]) if pressure_side is None else pressure_side
    return Nominal(spline, le_point, te_point, pressure_side, **flags)


def compare(nominal, points, **flags):
    """The best fit of a measured section's points onto its nominal and their deviations (the
    compare tool's fit, docs/COMPARE.md): nominal a Nominal (prepare_nominal: prepared once,
    reused for blade after blade) or a closed Spline (prepared on each call); points an
    (N, 2) array in the nominal's plane coordinates (mm). Flags as the compare tool's; with
    none, a Nominal's own. Returns a dict: 'angle' (deg) and 'translation' (mm) moving the
    points onto the nominal, 'iterations', 'converged', 'rms_before', 'max_before',
    'rms_after', 'max_after', 'hole', 'outlier_distance', 'outliers'; 'points': arrays per
    point ('point' moved, 'foot', 'normal', 't', 'before', 'after': signed deviations, positive
    = material outside; 'zone': 0 whole, 1 le, 2 te, 3 pressure, 4 suction; 'outlier');
    'zones': name -> dict (points, min, max, form, length, unmeasured, measured). Raises
    ValueError as the tool reports a section it cannot compare."""
    if not isinstance(nominal, Nominal):
        nominal = prepare_nominal(nominal, **flags)
        flags = {}
    return _libsection.compare_points(nominal, points, **flags)


def compare_stream(stream, nominal, **flags):
    """Every section of a measured stream (through camber) against its nominal, as the compare
    tool runs (docs/COMPARE.md): nominal the path of a mesh (.stl .obj .off .ply, sliced on
    the measured planes), of a stream or of a CSV of section points, or a Stream. Flags as the
    tool's (tolerances='file.csv', nominal_units, fit, freedom, decision_rule, whole, ...).
    Returns a copy of the stream with the tables 'fits', 'deviations', 'zones', 'compared' and
    'verdicts'; a section a tolerance names that the stream lacks is judged not measured, with
    an issue. verdict(result) and compare_report(result) give the tool's outcome and report.
    Raises Error naming the file for a nominal or tolerance file that cannot be used, and
    ValueError for bad flags; a doubtful nominal unit is a UserWarning."""
    return _libsection.compare_stream(stream, nominal, **flags)
