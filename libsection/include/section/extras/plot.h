// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file extras/plot.h
/// Drawings of the sections of a pipe stream, to scale: SVG per section, or one HTML page
/// holding every section (docs/PLOT.md). Each drawing, titled by the section's plane
/// ("z = 12 mm"), shows what the stream holds of the section: the measured points, the
/// fitted curve, the mean-camber line, the inscribed circles at the thickness stations with
/// their thickness, the LE and TE circles, the chord line, dimension lines (chord, maximum
/// thickness, edge radii), a parameter table, a scale bar, and a magnified inset of each
/// edge. Missing tables are simply not drawn, so a stream that stops after `slice` still
/// plots its points. Points and curves are thinned to the screen, so a drawing's size
/// follows what is drawn, not the number of points.
#include <string>
#include <vector>

namespace section {

struct Stream;

/// How a section is drawn (sizes in px unless said).
struct PlotOptions {
  double width = 1000;               ///< width of one section's drawing (its height follows the profile)
  double max_main_height = 520;      ///< the main view is shrunk to keep within this height
  double inset_size = 300;           ///< side of each square edge inset; 0 = no insets
  double inset_radii = 1.5;          ///< an inset's half-width around the edge circle's centre, in edge radii
  double inset_min_fraction = 0.02;  ///< smallest inset half-width, of the profile's extent (sharp edges)
  double point_radius = 1.6;         ///< radius of a measured point's dot
  bool points = true;                ///< draw the measured points ("points" table)
  bool stations = true;       ///< draw the inscribed circles at the thickness stations, with their values
  bool dimensions = true;     ///< draw the dimension lines (chord, maximum thickness, edge radii)
  bool table = true;          ///< draw the parameter table
  int spline_samples = 2000;  ///< points per loop when the curve comes from the spline tables
};

/// Section ids present in any per-section table of `stream` (frames, points, smoothed,
/// splines, samples, camber, params, ...) or in its issues, ascending.
std::vector<int> plot_sections(const Stream& stream);

/// A standalone SVG document of section `section`: the main view (v up, equal axes; px per
/// stream unit in its `data-scale`), the edge insets, the parameter table and the issues.
/// Ids start with `s<section>-`; classes name the elements (points, curve, camber, station,
/// le-circle, te-circle, chord, scale-bar, inset, param-table). The curve comes from the
/// spline tables, else the "samples" table, else the "smoothed" points. Throws
/// section::Error (`plot: ...`) when the section is not in the stream or an option is out
/// of range.
std::string plot_svg(const Stream& stream, int section, const PlotOptions& options = {});

/// One self-contained HTML page: the stream's history, a summary table of the main
/// parameters of every section (named by plane), then the SVG drawing of each section (as
/// plot_svg), which the wheel zooms and a drag pans (an inline script: nothing is fetched).
/// A section whose drawing fails is listed with the reason and the others go on.
/// Throws section::Error when the stream has no section at all.
std::string plot_html(const Stream& stream, const PlotOptions& options = {});

}  // namespace section
